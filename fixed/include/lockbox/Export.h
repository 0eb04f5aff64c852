#pragma once
/// @file
/// LOCKBOX_API marks what the lockbox libraries export: the public classes and the free functions
/// that the public headers declare and the libraries define. Every lockbox library is compiled
/// with hidden symbols (-fvisibility=hidden, -fvisibility-inlines-hidden), so a shared library's
/// ABI is exactly what carries the mark; in a static library the mark changes nothing a program
/// sees. It goes before the class name (`class LOCKBOX_API b2World`) or before the return type
/// of a free function. What a header defines completely (inline functions, templates, constexpr
/// variables, aggregates without out-of-line members) needs no mark: every user compiles its own
/// copy. Public headers define no inline variable and no function-local static that would then
/// exist once in the library and once in the program.

#if defined(_WIN32)
// A Windows DLL would need dllexport/dllimport per library; lockbox builds static libraries
// there (the top-level CMakeLists.txt refuses BUILD_SHARED_LIBS on Windows).
/// Empty on Windows: the libraries are static there.
#define LOCKBOX_API
#elif defined(__GNUC__) || defined(__clang__)
/// Default visibility: the marked class or function is part of a shared library's ABI.
#define LOCKBOX_API __attribute__((visibility("default")))
#else
/// Empty on compilers without a visibility attribute.
#define LOCKBOX_API
#endif
