# `npm pack` of the package folder, offline (ctest web_npm_pack): the tarball must be made and
# must hold the package's files. Arguments: NPM, PACKAGE_DIR, OUT_DIR.
if(NOT NPM)
    message(FATAL_ERROR "npm not found (Debian package npm)")
endif()
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}/cache")
execute_process(
    COMMAND "${NPM}" pack "${PACKAGE_DIR}" --offline --ignore-scripts --json --pack-destination "${OUT_DIR}"
            --cache "${OUT_DIR}/cache" --no-audit --no-fund --loglevel=error
    WORKING_DIRECTORY "${OUT_DIR}"
    RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT result EQUAL 0)
    message(FATAL_ERROR "npm pack failed (${result}): ${err}")
endif()
file(GLOB tarballs "${OUT_DIR}/*.tgz")
list(LENGTH tarballs n)
if(NOT n EQUAL 1)
    message(FATAL_ERROR "npm pack made ${n} tarballs: ${out}")
endif()
foreach(f lockbox.js lockbox-wasm.js lockbox-wasm.wasm index.d.ts README.md package.json)
    string(FIND "${out}" "\"${f}\"" at)
    if(at EQUAL -1)
        message(FATAL_ERROR "the tarball lacks ${f}: ${out}")
    endif()
endforeach()
file(SIZE "${tarballs}" size)
message(STATUS "npm pack: ${tarballs} (${size} bytes)")
