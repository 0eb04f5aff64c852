// RollbackBudgetGuard: the input delay from measured rollback costs (see the header for the
// policy and its cost model).

#include "lockbox/net/RollbackBudgetGuard.h"

#include <algorithm>

#include "lockbox/net/RollbackSession.h"

namespace lockbox::net {

std::string_view RollbackBudgetGuard::Check(const RollbackBudgetConfig& c) noexcept {
    if (c.budgetMicros < 1) return "budget must be at least 1 microsecond";
    if (c.percentile < 1 || c.percentile > 100) return "percentile must be in 1..100";
    if (c.maxDelay > kRollbackMaxInputDelay) return "max delay must be in 0..16";
    if (c.minDelay > c.maxDelay) return "min delay must not exceed max delay";
    if (c.rollbacksKept < 10 || c.rollbacksKept > 4096) return "rollbacks kept must be in 10..4096";
    if (c.sampleTicks < 1) return "sample ticks must be at least 1";
    if (c.minRollbacks < 1 || c.minRollbacks > c.rollbacksKept) return "min rollbacks must be in 1..rollbacks kept";
    if (c.lowerMarginPercent < 1 || c.lowerMarginPercent > 100) return "lower margin must be in 1..100 percent";
    return {};
}

RollbackBudgetGuard::RollbackBudgetGuard(const RollbackBudgetConfig& config, uint32_t initialDelay)
    : config_(config), delay_(std::clamp(initialDelay, config.minDelay, config.maxDelay)) {
    kept_.reserve(config_.rollbacksKept);
    scratch_.reserve(config_.rollbacksKept);
}

uint64_t RollbackBudgetGuard::PredictedPercentile(int32_t shift) const {
    scratch_.clear();
    for (const Sample& s : kept_) {
        if (ticks_ - s.tick > config_.sampleTicks) continue;  // the link may have changed since
        const int64_t depth = int64_t{s.depth} - shift;
        if (depth <= 0) continue;  // that rollback no longer happens
        // Cost scales with the steps the tick does: the re-simulated frames and the new one.
        scratch_.push_back(uint64_t{s.micros} * static_cast<uint64_t>(depth + 1) / (uint64_t{s.depth} + 1));
    }
    if (scratch_.empty()) return 0;
    const size_t rank = (scratch_.size() * config_.percentile + 99) / 100 - 1;
    std::nth_element(scratch_.begin(), scratch_.begin() + static_cast<std::ptrdiff_t>(rank), scratch_.end());
    return scratch_[rank];
}

uint32_t RollbackBudgetGuard::CostPercentileMicros() const {
    const uint64_t p = PredictedPercentile(0);
    return p > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(p);
}

void RollbackBudgetGuard::Changed() {
    // Remember what one frame costs (the median over the kept rollbacks) for lowering
    // decisions made before any rollback is seen at the new delay.
    if (!kept_.empty()) {
        scratch_.clear();
        for (const Sample& s : kept_) scratch_.push_back(uint64_t{s.micros} / (uint64_t{s.depth} + 1));
        const size_t mid = scratch_.size() / 2;
        std::nth_element(scratch_.begin(), scratch_.begin() + static_cast<std::ptrdiff_t>(mid), scratch_.end());
        frameMicros_ = scratch_[mid];
    }
    // The old samples describe the old delay.
    kept_.clear();
    next_ = 0;
    sinceChange_ = 0;
}

bool RollbackBudgetGuard::Record(uint32_t depth, uint32_t micros) {
    ++ticks_;
    ++sinceChange_;
    if (depth > 0) {
        const Sample s{ticks_, depth, micros};
        if (kept_.size() < config_.rollbacksKept) {
            kept_.push_back(s);
        } else {
            kept_[next_] = s;
            next_ = (next_ + 1) % kept_.size();
        }
        if (!costSeen_) frameMicros_ = uint64_t{micros} / (uint64_t{depth} + 1);
        costSeen_ = true;
        if (sinceChange_ >= config_.settleTicks && kept_.size() >= config_.minRollbacks && delay_ < config_.maxDelay &&
            PredictedPercentile(0) > config_.budgetMicros) {
            // The smallest raise the model says fits; the largest allowed if none does.
            uint32_t k = 1;
            while (delay_ + k < config_.maxDelay && PredictedPercentile(static_cast<int32_t>(k)) > config_.budgetMicros)
                ++k;
            delay_ += k;
            ++raises_;
            Changed();
            return true;
        }
    }
    if (delay_ > config_.minDelay && sinceChange_ >= config_.lowerAfterTicks && costSeen_) {
        // One frame less delay: every rollback one frame deeper, and ticks that did not roll
        // back may now re-simulate one frame (two frames' worth of steps).
        const uint64_t deeper = std::max(PredictedPercentile(-1), 2 * frameMicros_);
        if (deeper * 100 <= uint64_t{config_.budgetMicros} * config_.lowerMarginPercent) {
            --delay_;
            ++lowerings_;
            Changed();
            return true;
        }
    }
    return false;
}

}  // namespace lockbox::net
