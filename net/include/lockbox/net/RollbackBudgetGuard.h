#pragma once
/// @file
/// RollbackBudgetGuard (docs/rollback.md, "The budget guard"): chooses a rollback session's
/// input delay from what its rollbacks measurably cost, so that the game's re-simulation
/// stays inside a time budget per tick. Each frame of input delay takes about one frame off
/// every rollback's depth (the remote inputs arrive that much earlier relative to the frame
/// they are for), at the price of that much more latency between a press and its effect.
///
/// The game reports every tick (Record): how many frames that tick re-simulated (0 when it
/// did not roll back) and how long executing its requests took. The guard keeps the latest
/// rollbacks (and forgets those older than sampleTicks, so a link that got fast again is not
/// judged by its slow past); when the chosen percentile of their cost is over the budget it raises the delay
/// at once by as many frames as its cost model says are needed, and it lowers the delay by
/// one frame only after a long quiet period and only when the model predicts the rollbacks,
/// one frame deeper, would still stay clearly under the budget. Raise quickly, lower slowly:
/// a slow machine or a bad link settles at a larger delay instead of oscillating.
///
/// The cost model: a tick that re-simulates d frames does about d + 1 steps (the d again and
/// the new one) plus a restore and d + 1 saves, so its cost scales as (d + 1); one more frame
/// of delay turns it into a rollback of depth d - 1 (none when d was 1). Only integers: the
/// same reports give the same decisions everywhere (tests replay them exactly).
///
/// The guard only advises; the game applies Delay() with RollbackSession::SetInputDelay,
/// which loses no input either way.

#include <cstdint>
#include <string_view>
#include <vector>

#include "lockbox/Export.h"

namespace lockbox::net {

/// Settings of a RollbackBudgetGuard (checked by RollbackBudgetGuard::Check).
struct RollbackBudgetConfig {
    uint32_t budgetMicros = 8000;    ///< the chosen percentile of a rollback tick's cost, at most (>= 1)
    uint32_t percentile = 99;        ///< 1 .. 100
    uint32_t minDelay = 0;           ///< the guard never goes below this
    uint32_t maxDelay = 16;          ///< nor above this (<= kRollbackMaxInputDelay)
    uint32_t rollbacksKept = 120;    ///< the latest rollbacks the percentile is taken over, 10 .. 4096
    uint32_t sampleTicks = 1200;     ///< a rollback older than this many ticks no longer counts (>= 1)
    uint32_t minRollbacks = 20;      ///< a raise needs at least this many since the last change, 1 .. rollbacksKept
    uint32_t settleTicks = 60;       ///< ticks after any change before the next raise is considered
    uint32_t lowerAfterTicks = 600;  ///< ticks after any change before a lowering is considered
    uint32_t lowerMarginPercent =
        75;  ///< lower only if the deeper rollbacks' cost fits in this % of the budget, 1 .. 100
};

/// Advises the input delay of one rollback session.
class LOCKBOX_API RollbackBudgetGuard {
public:
    /// Empty when `config` is valid, else a one-line reason.
    static std::string_view Check(const RollbackBudgetConfig& config) noexcept;

    /// `config` must pass Check; `initialDelay` is the session's delay now, clamped to
    /// [minDelay, maxDelay] (apply Delay() if it differs).
    RollbackBudgetGuard(const RollbackBudgetConfig& config, uint32_t initialDelay);

    /// One tick: `depth` frames re-simulated by its rollback (0: no rollback; the growth of
    /// RollbackStats::framesResimulated over the tick's AdvanceFrame), and `micros` spent
    /// executing the tick's requests (read only when depth > 0). True when Delay() changed;
    /// apply it with RollbackSession::SetInputDelay.
    bool Record(uint32_t depth, uint32_t micros);

    /// The input delay the session should use.
    uint32_t Delay() const noexcept { return m_delay; }
    /// The chosen percentile of the cost of the rollbacks kept since the last change and not
    /// older than sampleTicks (0 with none).
    uint32_t CostPercentileMicros() const;
    /// Rollbacks kept since the last change.
    uint32_t RollbacksKept() const noexcept { return static_cast<uint32_t>(m_kept.size()); }
    /// Delay changes so far, up and down.
    ///@{
    uint32_t Raises() const noexcept { return m_raises; }
    uint32_t Lowerings() const noexcept { return m_lowerings; }
    ///@}

private:
    struct Sample {
        uint64_t tick = 0;
        uint32_t depth = 0;
        uint32_t micros = 0;
    };
    // The percentile of the kept rollbacks' cost as if each were `shift` frames shallower
    // (negative: deeper); rollbacks that vanish (depth <= shift) or are older than
    // sampleTicks drop out.
    uint64_t PredictedPercentile(int32_t shift) const;
    void Changed();

    RollbackBudgetConfig m_config;
    uint32_t m_delay = 0;
    std::vector<Sample> m_kept;  // a ring once full
    size_t m_next = 0;           // ring position of the oldest sample when full
    uint64_t m_ticks = 0;        // Record calls so far
    uint64_t m_sinceChange = 0;  // ticks
    uint64_t m_frameMicros = 0;  // the latest per-frame cost seen (0 also when under 1 us)
    bool m_costSeen = false;     // any rollback recorded: lowering is never blind
    uint32_t m_raises = 0;
    uint32_t m_lowerings = 0;
    mutable std::vector<uint64_t> m_scratch;
};

}  // namespace lockbox::net
