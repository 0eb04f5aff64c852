#pragma once
/// @file
/// Overflow policy of the fixed-point layer.
///
/// Overflow is never undefined behaviour. Every operation that can leave its format's range
/// (add, sub, mul, div, negate, narrowing, division by zero) takes one of two documented paths:
/// - checked builds (LOCKBOX_CHECKED): the trap handler is called with the operation and its
///   operands. The default handler prints them and aborts; tests may install their own.
/// - default builds: the result saturates to the format's symmetric limit (+-max raw, never
///   INT_MIN) and a per-thread saturation counter is incremented. The world folds the counter
///   into its state hash, so lockstep peers see the event, and all peers saturate identically.
///   A world stepping on several threads captures each piece of work's saturations
///   (SaturationCapture) and adds them to the stepping thread's counter (AddSaturations), so a
///   step counts the same with any number of workers.
/// See docs/numerics.md.

#include <cstdint>

#include "lockbox/Export.h"

namespace lockbox {

/// Called on overflow in checked builds. `op` names the operation ("Fixed::operator*", ...),
/// `a` and `b` are the raw operands (b is 0 for unary operations). Must not return normally
/// unless the program accepts the saturated result that follows.
using OverflowTrapHandler = void (*)(const char* op, int64_t a, int64_t b);

/// Replaces the trap handler; returns the previous one. nullptr restores the default
/// (print to stderr and abort).
LOCKBOX_API OverflowTrapHandler SetOverflowTrapHandler(OverflowTrapHandler handler) noexcept;

/// Number of saturations on this thread since the last reset (those made under a
/// SaturationCapture go to the capture instead). Monotonic; wraps at 2^64.
LOCKBOX_API uint64_t SaturationCount() noexcept;

/// Resets this thread's saturation counter to zero.
LOCKBOX_API void ResetSaturationCount() noexcept;

/// Adds `count` saturations to this thread's counter (or to the capture active on this thread),
/// as if they had happened here. A world uses it to count, on the thread that steps it, the
/// saturations its workers captured.
LOCKBOX_API void AddSaturations(uint64_t count) noexcept;

/// While alive, this thread's saturations go to `*sink` instead of the thread's counter.
/// Captures nest: the previous one is restored on destruction. A world's workers wrap each
/// piece of work in one, so what a piece saturated is known whichever thread ran it.
class LOCKBOX_API SaturationCapture {
public:
    /// Starts capturing into `*sink` (not owned; must outlive the capture).
    explicit SaturationCapture(uint64_t* sink) noexcept;
    /// Restores the previous capture (or the thread's counter).
    ~SaturationCapture();
    SaturationCapture(const SaturationCapture&) = delete;
    SaturationCapture& operator=(const SaturationCapture&) = delete;

private:
    uint64_t* m_previous;
};

/// True when this build traps on overflow (LOCKBOX_CHECKED).
constexpr bool kOverflowTraps =
#ifdef LOCKBOX_CHECKED
    true;
#else
    false;
#endif

namespace detail {
/// Slow path for every overflow: traps (checked) or counts (default). Never inlined, so the
/// fast path stays a compare and a branch. Not constexpr on purpose: an overflow during
/// constant evaluation is a compile error.
LOCKBOX_API void OnOverflow(const char* op, int64_t a, int64_t b) noexcept;
}  // namespace detail

}  // namespace lockbox
