# LockboxCompilerOptions.cmake: the INTERFACE target `lockbox_compile_options` that every target
# of this repository links PRIVATELY (libraries through $<BUILD_INTERFACE:...>, so it is never
# exported). It carries our warnings, -Werror (LOCKBOX_WERROR) and -ffp-contract=off. None of it
# reaches a consumer:
#
# - Warnings and -Werror are our policy, not a requirement of the headers.
# - -ffp-contract=off keeps the display and benchmark float code of this repository free of
#   fused multiply-adds. A consumer does not need it: the simulation state is integers, and the
#   only floating point in the public headers is the compile-time (consteval) literal conversion,
#   which the compiler evaluates one exact IEEE operation at a time whatever the flag says, and
#   ToDouble/ToFloat for display.
#
# What does reach consumers (as usage requirements of lockbox::fixed) are the two defines that
# change the ABI or the bits: LOCKBOX_CHECKED and LOCKBOX_PORTABLE_INT128 (see fixed/CMakeLists.txt).

include_guard(GLOBAL)

add_library(lockbox_compile_options INTERFACE)

set(_lockbox_gnu_like "$<CXX_COMPILER_ID:GNU,Clang,AppleClang>")

target_compile_options(lockbox_compile_options INTERFACE
    "$<${_lockbox_gnu_like}:-Wall;-Wextra;-Wpedantic;-Wshadow>"
    # Never fuse a multiply and an add into an FMA, not even in display code.
    "$<${_lockbox_gnu_like}:-ffp-contract=off>"
    "$<$<AND:$<BOOL:${LOCKBOX_WERROR}>,${_lockbox_gnu_like}>:-Werror>"
)

# Extra compile options for lockbox's own libraries (the modules), not for tests, tools or
# samples. The sanitize preset gives them -O1: the engine then runs its tests under ASan and
# UBSan about nine times faster than at -O0 (the stability cases: 148 s -> 16 s), while the test
# files, most of the build, still compile at -O0 (-O1 everywhere would double the build for
# another 7 s). AddressSanitizer's own guide asks for -O1 or higher for reasonable speed.
set(LOCKBOX_LIBRARY_COMPILE_OPTIONS "" CACHE STRING "Extra compile options for lockbox's libraries only (a ;-list)")
