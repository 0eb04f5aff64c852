# LockboxCompilerOptions.cmake: the INTERFACE target `lockbox_compile_options` that every lockbox
# target links to. It carries warnings, the floating-point flags that keep results bit-identical,
# and the compile definitions selected by these cache options (declared by the top-level
# CMakeLists.txt, before or after including this file):
#
#   LOCKBOX_CHECKED          -> LOCKBOX_CHECKED=1          asserts and overflow traps
#   LOCKBOX_PORTABLE_INT128  -> LOCKBOX_PORTABLE_INT128=1  force the portable 128-bit fallback
#   LOCKBOX_WERROR           -> -Werror
#
# The options are read at the end of the directory that includes this file, so the order of
# option() and include() does not matter.

include_guard(GLOBAL)

add_library(lockbox_compile_options INTERFACE)

set(_lockbox_gnu_like "$<CXX_COMPILER_ID:GNU,Clang,AppleClang>")

target_compile_options(lockbox_compile_options INTERFACE
    "$<${_lockbox_gnu_like}:-Wall;-Wextra;-Wpedantic;-Wshadow>"
    # Determinism: never fuse a multiply and an add into an FMA, not even in display code.
    "$<${_lockbox_gnu_like}:-ffp-contract=off>"
)

function(_lockbox_apply_option_flags)
    if(LOCKBOX_CHECKED)
        target_compile_definitions(lockbox_compile_options INTERFACE LOCKBOX_CHECKED=1)
    endif()
    if(LOCKBOX_PORTABLE_INT128)
        target_compile_definitions(lockbox_compile_options INTERFACE LOCKBOX_PORTABLE_INT128=1)
    endif()
    if(LOCKBOX_WERROR)
        target_compile_options(lockbox_compile_options INTERFACE
            "$<${_lockbox_gnu_like}:-Werror>")
    endif()
    message(STATUS "lockbox options: CHECKED=${LOCKBOX_CHECKED} "
        "PORTABLE_INT128=${LOCKBOX_PORTABLE_INT128} WERROR=${LOCKBOX_WERROR}")
endfunction()

cmake_language(DEFER CALL _lockbox_apply_option_flags)
