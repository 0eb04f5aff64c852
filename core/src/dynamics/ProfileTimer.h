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

}  // namespace lockbox::core_detail
