# LockboxDependencies.cmake: find lockbox's third-party dependencies and expose each one as a
# `lockbox_dep::<name>` imported target. A missing dependency stops configuration with a message
# that names the Debian package to install.
#
# Included by the top-level CMakeLists.txt. Provides:
#
#   lockbox_require_package(...)   generic finder (see below)
#   lockbox_dep::xxhash            found on include: state hashing in core (xxhash.h, libxxhash)
#   lockbox_dep::cereal            found on include: serialization in core (header-only)
#   lockbox_find_zstd()         -> lockbox_dep::zstd         replay compression
#   lockbox_find_enet()         -> lockbox_dep::enet         UDP transport
#   lockbox_find_rapidjson()    -> lockbox_dep::rapidjson    scene files (header only)
#   lockbox_find_test_deps()    -> GTest::gtest, GTest::gtest_main, GTest::gmock (+ GoogleTest module)
#   lockbox_find_bench_deps()   -> benchmark::benchmark
#   lockbox_find_box2d_float()  -> lockbox_dep::box2d_float  float Box2D 2.4.1, for differential
#                                  tests and side-by-side benchmarks only; include as
#                                  <box2d/box2d.h>
#
# Every target is GLOBAL, so a function may be called from any directory and the target is then
# usable everywhere. Calling a function twice is harmless.

include_guard(GLOBAL)

include(LockboxFindLibrary)

set(LOCKBOX_DEPS_HINT "(or run scripts/install-deps.sh)")

# Stop configuration because a dependency is missing.
function(_lockbox_missing display_name debian_package)
    message(FATAL_ERROR
        "${display_name} not found: install the Debian package ${debian_package} "
        "${LOCKBOX_DEPS_HINT}")
endfunction()

# Make an imported target found by find_package() visible in every directory. This is only
# allowed in the directory that created it, so callers do it right after find_package().
function(_lockbox_make_global)
    foreach(target IN LISTS ARGN)
        if(TARGET ${target})
            get_target_property(is_global ${target} IMPORTED_GLOBAL)
            get_target_property(aliased ${target} ALIASED_TARGET)
            if(NOT is_global AND NOT aliased)
                set_target_properties(${target} PROPERTIES IMPORTED_GLOBAL TRUE)
            endif()
        endif()
    endforeach()
endfunction()

# lockbox_require_package(
#     TARGET  <lockbox_dep::name>   target to create (INTERFACE IMPORTED GLOBAL)
#     NAME    <display name>        used in the error message, e.g. "xxHash"
#     DEBIAN  <package>             Debian package that provides it, e.g. libxxhash-dev
#     # Either a CMake package shipped by Debian:
#     [PACKAGE <find_package name> LINK <upstream target>...]
#     # or a plain header (and library) found by path:
#     [HEADER <file> [LIBRARY <name>]]
# )
# Does nothing if TARGET already exists.
function(lockbox_require_package)
    cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;NAME;DEBIAN;PACKAGE;HEADER;LIBRARY" "LINK")
    foreach(required IN ITEMS TARGET NAME DEBIAN)
        if(NOT arg_${required})
            message(FATAL_ERROR "lockbox_require_package: ${required} is required")
        endif()
    endforeach()
    if(TARGET ${arg_TARGET})
        return()
    endif()

    if(arg_PACKAGE)
        find_package(${arg_PACKAGE} CONFIG QUIET)
        if(NOT ${arg_PACKAGE}_FOUND)
            _lockbox_missing("${arg_NAME}" "${arg_DEBIAN}")
        endif()
        foreach(upstream IN LISTS arg_LINK)
            if(NOT TARGET ${upstream})
                message(FATAL_ERROR
                    "${arg_NAME}: package ${arg_PACKAGE} was found but has no target ${upstream}; "
                    "reinstall the Debian package ${arg_DEBIAN}")
            endif()
        endforeach()
        _lockbox_make_global(${arg_LINK})
        add_library(${arg_TARGET} INTERFACE IMPORTED GLOBAL)
        target_link_libraries(${arg_TARGET} INTERFACE ${arg_LINK})
        message(STATUS "Found ${arg_NAME}: ${${arg_PACKAGE}_DIR} -> ${arg_TARGET}")
    elseif(arg_HEADER)
        lockbox_find_library(${arg_TARGET} NAME "${arg_NAME}" DEBIAN ${arg_DEBIAN} HEADER ${arg_HEADER}
                             LIBRARY ${arg_LIBRARY} GLOBAL RESULT found)
        if(NOT found)
            _lockbox_missing("${arg_NAME}" "${arg_DEBIAN}")
        endif()
        message(STATUS "Found ${arg_NAME}: ${arg_HEADER} ${arg_LIBRARY} -> ${arg_TARGET}")
    else()
        message(FATAL_ERROR "lockbox_require_package(${arg_TARGET}): give PACKAGE or HEADER")
    endif()
endfunction()

# Under Emscripten the dependencies come from elsewhere (header-only copies, zstd from Debian's
# source): those targets exist first, so the finders below do nothing.
if(EMSCRIPTEN)
    include(LockboxWasmDependencies)
endif()

# --- Always required by core -------------------------------------------------------------------

lockbox_require_package(TARGET lockbox_dep::xxhash NAME xxHash DEBIAN libxxhash-dev
    HEADER xxhash.h LIBRARY xxhash)

lockbox_require_package(TARGET lockbox_dep::cereal NAME cereal DEBIAN libcereal-dev
    PACKAGE cereal LINK cereal::cereal)

# --- Found on demand by the modules that need them ---------------------------------------------

# Replay compression. Found by path (zstd.h, libzstd) rather than through the zstdConfig.cmake
# that Debian 12 ships, so it works with any zstd install that has no CMake config.
function(lockbox_find_zstd)
    lockbox_require_package(TARGET lockbox_dep::zstd NAME zstd DEBIAN libzstd-dev
        HEADER zstd.h LIBRARY zstd)
endfunction()

# UDP transport. Debian's libenet-dev has only a pkg-config file, so find it by path.
function(lockbox_find_enet)
    lockbox_require_package(TARGET lockbox_dep::enet NAME ENet DEBIAN libenet-dev
        HEADER enet/enet.h LIBRARY enet)
endfunction()

# Scene files (scenefile/): RapidJSON's SAX reader, which hands over each number's text
# (kParseNumbersAsStringsFlag). Header only; Debian's rapidjson-dev also ships a CMake config,
# but it carries nothing beyond this include directory.
function(lockbox_find_rapidjson)
    lockbox_require_package(TARGET lockbox_dep::rapidjson NAME RapidJSON DEBIAN rapidjson-dev
        HEADER rapidjson/reader.h)
endfunction()

# Float Box2D 2.4.1, only for differential tests and side-by-side benchmarks. Debian's
# libbox2d-dev ships box2dConfig.cmake with box2d::box2d, which carries no include directory; the
# headers are /usr/include/box2d/*.h, so code includes <box2d/box2d.h>. The directory
# /usr/include/box2d itself is deliberately NOT put on the include path: its b2_*.h names would
# shadow lockbox's own headers.
function(lockbox_find_box2d_float)
    if(TARGET lockbox_dep::box2d_float)
        return()
    endif()
    lockbox_require_package(TARGET lockbox_dep::box2d_float NAME "Box2D (float)"
        DEBIAN libbox2d-dev PACKAGE box2d LINK box2d::box2d)
    find_path(LOCKBOX_BOX2D_FLOAT_INCLUDE_DIR NAMES box2d/box2d.h
        DOC "Directory holding box2d/box2d.h (libbox2d-dev)")
    if(NOT LOCKBOX_BOX2D_FLOAT_INCLUDE_DIR)
        _lockbox_missing("Box2D (float) headers" libbox2d-dev)
    endif()
    # compat/box2d_float/Box2DFloat.h: includes Box2D and removes its constant macros, which
    # share names with lockbox's constants.
    target_include_directories(lockbox_dep::box2d_float INTERFACE
        "${LOCKBOX_BOX2D_FLOAT_INCLUDE_DIR}" "${PROJECT_SOURCE_DIR}/compat/box2d_float")
endfunction()

# GoogleTest and GoogleMock (libgtest-dev, libgmock-dev). A macro so GTest_FOUND and the
# GoogleTest module's gtest_discover_tests() reach the caller.
macro(lockbox_find_test_deps)
    find_package(GTest QUIET)
    if(NOT GTest_FOUND OR NOT TARGET GTest::gtest OR NOT TARGET GTest::gtest_main)
        _lockbox_missing(GoogleTest "libgtest-dev")
    endif()
    if(NOT TARGET GTest::gmock)
        _lockbox_missing(GoogleMock "libgmock-dev")
    endif()
    _lockbox_make_global(GTest::gtest GTest::gtest_main GTest::gmock GTest::gmock_main)
    include(GoogleTest)
endmacro()

# Google Benchmark (libbenchmark-dev).
macro(lockbox_find_bench_deps)
    if(NOT TARGET benchmark::benchmark)
        find_package(benchmark CONFIG QUIET)
        if(NOT benchmark_FOUND OR NOT TARGET benchmark::benchmark)
            _lockbox_missing("Google Benchmark" "libbenchmark-dev")
        endif()
        _lockbox_make_global(benchmark::benchmark benchmark::benchmark_main)
    endif()
endmacro()
