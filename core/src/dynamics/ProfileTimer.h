#pragma once
// The clock of the step's profile (b2Profile, in nanoseconds): the world's step, its solve and
// the islands' solve time their phases alike.

#include <chrono>
#include <cstdint>

namespace lockbox::core_detail {

using Clock = std::chrono::steady_clock;

/// Nanoseconds from `from` to now.
inline int64_t Nanos(Clock::time_point from) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - from).count();
}

/// The clock when the step's timers are on (b2World::SetProfileTimers); with them off a step
/// reads no clock at all, and its stages' times stay zero.
inline Clock::time_point StartTimer(bool on) { return on ? Clock::now() : Clock::time_point{}; }
/// Nanoseconds since a StartTimer(on), or 0 with the timers off.
inline int64_t Elapsed(bool on, Clock::time_point from) { return on ? Nanos(from) : 0; }

}  // namespace lockbox::core_detail
