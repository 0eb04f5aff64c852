# EmscriptenToolchain.cmake: the toolchain file of the `wasm` preset. It loads Emscripten's own
# CMake toolchain (Debian's package puts it in /usr/share/emscripten; an emsdk install is found
# through $EMSCRIPTEN or em-config) and makes the build independent of the developer's shell:
#
# - em++ runs a JavaScript optimizer when it links at -O2 and above, which needs Debian's acorn
#   module from /usr/share/nodejs: every link runs through `env NODE_PATH=...`.
# - Debian ships Emscripten's system libraries prebuilt in a frozen cache that nothing writes,
#   so it is used as it is. An Emscripten whose cache is not frozen and not writable by this
#   user gets a private cache in the build tree (EM_CACHE on every compile and link).

set(_lockbox_em_root "$ENV{EMSCRIPTEN}")
if(NOT _lockbox_em_root)
    find_program(_lockbox_em_config em-config)
    if(_lockbox_em_config)
        execute_process(COMMAND "${_lockbox_em_config}" EMSCRIPTEN_ROOT OUTPUT_VARIABLE _lockbox_em_root
                        OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    endif()
endif()
if(NOT _lockbox_em_root AND EXISTS /usr/share/emscripten)
    set(_lockbox_em_root /usr/share/emscripten)
endif()
set(_lockbox_em_toolchain "${_lockbox_em_root}/cmake/Modules/Platform/Emscripten.cmake")
if(NOT EXISTS "${_lockbox_em_toolchain}")
    message(FATAL_ERROR "Emscripten not found: install the Debian package emscripten "
                        "(scripts/install-deps.sh --web) or set EMSCRIPTEN to its root")
endif()
include("${_lockbox_em_toolchain}")

set(_lockbox_em_env "NODE_PATH=/usr/share/nodejs")
find_program(_lockbox_em_config em-config HINTS "${_lockbox_em_root}")
if(_lockbox_em_config)
    execute_process(COMMAND "${_lockbox_em_config}" CACHE OUTPUT_VARIABLE _lockbox_em_cache
                    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    execute_process(COMMAND "${_lockbox_em_config}" FROZEN_CACHE OUTPUT_VARIABLE _lockbox_em_frozen
                    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(NOT _lockbox_em_frozen STREQUAL "True" AND _lockbox_em_cache AND NOT DEFINED ENV{EM_CACHE})
        execute_process(COMMAND test -w "${_lockbox_em_cache}" RESULT_VARIABLE _lockbox_em_unwritable)
        if(_lockbox_em_unwritable)
            list(APPEND _lockbox_em_env "EM_CACHE=${CMAKE_BINARY_DIR}/emcache")
        endif()
    endif()
endif()
set(CMAKE_C_COMPILER_LAUNCHER env ${_lockbox_em_env} CACHE STRING "Environment for emcc" FORCE)
set(CMAKE_CXX_COMPILER_LAUNCHER env ${_lockbox_em_env} CACHE STRING "Environment for em++" FORCE)
set(CMAKE_C_LINKER_LAUNCHER env ${_lockbox_em_env} CACHE STRING "Environment for emcc links" FORCE)
set(CMAKE_CXX_LINKER_LAUNCHER env ${_lockbox_em_env} CACHE STRING "Environment for em++ links" FORCE)

# lockbox's snapshot parser reports a malformed image with a C++ exception that Restore catches
# (core/src/state/SnapshotParse.cpp). Emscripten's default build cannot catch one (a throw
# aborts the module), so everything is compiled and linked with -fexceptions, Emscripten's
# JavaScript-based exception handling: no measurable step-time cost, the .wasm 12 % larger.
# (-fwasm-exceptions would need libc++ variants that Debian's frozen cache does not hold.)
set(CMAKE_CXX_FLAGS_INIT "-fexceptions")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-fexceptions")
