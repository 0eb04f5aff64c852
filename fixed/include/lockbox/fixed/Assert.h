#pragma once
/// @file
/// Programmer errors: LOCKBOX_ASSERT(cond, message) and its replaceable handler, shared by every
/// module (fixed, core, replay, net).
///
/// A programmer error is a call the API forbids: creating a body inside a Step callback, a
/// fixture definition without a shape, a broad-phase proxy id the tree never gave out. It is a
/// bug in the calling code. Untrusted input (snapshots, replays, packets, files) never reaches
/// an assert: it is checked and refused with an error value that names what is wrong.
///
/// What a failed check does depends on the build:
/// - debug builds (NDEBUG not defined) and checked builds (LOCKBOX_CHECKED) evaluate the
///   condition and, when it is false, call the assert handler with the condition's text, the
///   message, the file and the line. The default handler prints them to stderr and aborts.
/// - release builds neither evaluate the condition nor call anything.
/// After the check, the code goes on as a release build does. Where the API documents a refusal
/// (b2World and b2Body calls on a locked world, CreateFixture without a shape), the call then
/// changes nothing and creators return nullptr: that is what release builds do, and what a
/// replaced handler that returns gets. Elsewhere a handler that returns lets the call go on
/// with its precondition broken: replace the handler to log or count failures (in tests, say),
/// not to carry on in production. A handler must not throw (checks run in noexcept code).

#include "lockbox/Export.h"

namespace lockbox {

/// Receives a failed check: expr is the condition as written, msg explains it, file and line
/// locate it. The default prints all four to stderr and aborts.
using b2AssertHandler = void (*)(const char* expr, const char* msg, const char* file, int line);

/// Replaces the assert handler for the whole process and returns the previous one; nullptr
/// restores the default. Not synchronised with checks running in other threads: set it at
/// start-up or in a test's set-up.
LOCKBOX_API b2AssertHandler b2SetAssertHandler(b2AssertHandler handler) noexcept;

/// True in builds where LOCKBOX_ASSERT checks (debug or LOCKBOX_CHECKED), as seen by the
/// translation unit that includes this header.
inline constexpr bool b2_assertsEnabled =
#if defined(LOCKBOX_CHECKED) || !defined(NDEBUG)
    true;
#else
    false;
#endif

namespace detail {
/// Calls the assert handler (LOCKBOX_ASSERT's failure path).
[[gnu::cold]] LOCKBOX_API void AssertFailed(const char* expr, const char* msg, const char* file, int line) noexcept;
}  // namespace detail

}  // namespace lockbox

#if defined(LOCKBOX_CHECKED) || !defined(NDEBUG)
/// Checks a programmer-error condition (see above): message is a C string.
#define LOCKBOX_ASSERT(cond, message)                                                                          \
    do {                                                                                                       \
        if (__builtin_expect(!(cond), 0)) ::lockbox::detail::AssertFailed(#cond, message, __FILE__, __LINE__); \
    } while (false)
#else
// Unevaluated (sizeof): the condition and message cost nothing, yet what they name counts as used.
#define LOCKBOX_ASSERT(cond, message) \
    do {                              \
        (void)sizeof((cond) ? 1 : 0); \
        (void)sizeof(message);        \
    } while (false)
#endif
