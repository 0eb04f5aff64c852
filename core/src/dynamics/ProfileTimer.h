#pragma once
// The clock of the step's profile (b2Profile, in nanoseconds): the world's step, its solve and
// the islands' solve time their phases alike.

#include <chrono>
#include <cstdint>

namespace lockbox::core_detail {

/// A stage's stopwatch. With the step's timers off (b2World::SetProfileTimers) it reads no clock
/// at all and every stage's time stays zero.
class StageTimer {
public:
    explicit StageTimer(bool on) : m_on(on) { Restart(); }
    /// Starts the next stage.
    void Restart() {
        if (m_on) m_start = Clock::now();
    }
    /// Nanoseconds since the start, or 0 with the timers off.
    int64_t Nanos() const {
        if (!m_on) return 0;
        return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - m_start).count();
    }

private:
    using Clock = std::chrono::steady_clock;
    bool m_on;
    Clock::time_point m_start{};
};

}  // namespace lockbox::core_detail
