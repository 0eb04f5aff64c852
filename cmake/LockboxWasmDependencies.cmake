# LockboxWasmDependencies.cmake: lockbox's third-party dependencies for the WebAssembly build
# (EMSCRIPTEN), as the lockbox_dep:: targets LockboxDependencies.cmake defines natively.
# Included by LockboxDependencies.cmake before it looks for anything; the native finders then
# see the targets and do nothing.
#
# Emscripten compiles against its own sysroot, and Debian's packages hold x86-64 libraries, so:
# - xxHash, Cereal and RapidJSON are used header-only: their Debian headers are copied into a
#   directory of the build tree (never /usr/include itself on the include path, whose libc
#   headers would shadow Emscripten's), xxHash with XXH_INLINE_ALL;
# - zstd (replay files) is compiled from Debian's own source package, decoder only (a browser
#   verifies replays, it does not record them), the same release as the native libzstd-dev.
#   LOCKBOX_ZSTD_SOURCE_DIR points at an unpacked zstd source tree; when empty, configure runs
#   scripts/fetch-zstd-source.sh, which fetches it with apt-get source (needs the deb-src entry
#   that scripts/install-deps.sh --web adds).

include_guard(GLOBAL)

set(_lockbox_wasm_include "${CMAKE_BINARY_DIR}/wasm-deps/include")
foreach(header IN ITEMS xxhash.h cereal rapidjson)
    if(NOT EXISTS "/usr/include/${header}")
        message(FATAL_ERROR "/usr/include/${header} not found: install libxxhash-dev, libcereal-dev and "
                            "rapidjson-dev (scripts/install-deps.sh)")
    endif()
    file(COPY "/usr/include/${header}" DESTINATION "${_lockbox_wasm_include}")
endforeach()

add_library(lockbox_dep::xxhash INTERFACE IMPORTED GLOBAL)
target_include_directories(lockbox_dep::xxhash INTERFACE "${_lockbox_wasm_include}")
target_compile_definitions(lockbox_dep::xxhash INTERFACE XXH_INLINE_ALL)
add_library(lockbox_dep::cereal INTERFACE IMPORTED GLOBAL)
target_include_directories(lockbox_dep::cereal INTERFACE "${_lockbox_wasm_include}")
add_library(lockbox_dep::rapidjson INTERFACE IMPORTED GLOBAL)
target_include_directories(lockbox_dep::rapidjson INTERFACE "${_lockbox_wasm_include}")

set(LOCKBOX_ZSTD_SOURCE_DIR "" CACHE PATH "Unpacked zstd source tree for the WebAssembly decoder (empty: fetch Debian's)")
if(NOT LOCKBOX_ZSTD_SOURCE_DIR)
    execute_process(
        COMMAND bash "${PROJECT_SOURCE_DIR}/scripts/fetch-zstd-source.sh" "${CMAKE_BINARY_DIR}/wasm-deps/zstd"
        OUTPUT_VARIABLE _lockbox_zstd_dir OUTPUT_STRIP_TRAILING_WHITESPACE
        RESULT_VARIABLE _lockbox_zstd_result)
    if(NOT _lockbox_zstd_result EQUAL 0 OR NOT EXISTS "${_lockbox_zstd_dir}/lib/zstd.h")
        message(FATAL_ERROR "Could not fetch Debian's zstd source package (scripts/fetch-zstd-source.sh); run "
                            "scripts/install-deps.sh --web, or set LOCKBOX_ZSTD_SOURCE_DIR to a zstd source tree")
    endif()
    set(LOCKBOX_ZSTD_SOURCE_DIR "${_lockbox_zstd_dir}" CACHE PATH "" FORCE)
endif()
message(STATUS "zstd decoder for WebAssembly from ${LOCKBOX_ZSTD_SOURCE_DIR}")

enable_language(C)
set(_zstd "${LOCKBOX_ZSTD_SOURCE_DIR}/lib")
add_library(lockbox_zstd_decoder STATIC
    "${_zstd}/common/debug.c"
    "${_zstd}/common/entropy_common.c"
    "${_zstd}/common/error_private.c"
    "${_zstd}/common/fse_decompress.c"
    "${_zstd}/common/xxhash.c"
    "${_zstd}/common/zstd_common.c"
    "${_zstd}/decompress/huf_decompress.c"
    "${_zstd}/decompress/zstd_ddict.c"
    "${_zstd}/decompress/zstd_decompress.c"
    "${_zstd}/decompress/zstd_decompress_block.c")
# As zstd's own build (lib/libzstd.mk) defines them: its xxHash under its own names, no legacy
# formats, no assembly, no run-time CPU dispatch.
target_compile_definitions(lockbox_zstd_decoder PRIVATE
    XXH_NAMESPACE=ZSTD_ ZSTD_LEGACY_SUPPORT=0 ZSTD_DISABLE_ASM DYNAMIC_BMI2=0 DEBUGLEVEL=0)
target_include_directories(lockbox_zstd_decoder PUBLIC "${_zstd}")
add_library(lockbox_dep::zstd ALIAS lockbox_zstd_decoder)
