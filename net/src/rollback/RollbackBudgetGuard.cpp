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
    : m_config(config), m_delay(std::clamp(initialDelay, config.minDelay, config.maxDelay)) {
    m_kept.reserve(m_config.rollbacksKept);
    m_scratch.reserve(m_config.rollbacksKept);
}

uint64_t RollbackBudgetGuard::PredictedPercentile(int32_t shift) const {
    m_scratch.clear();
    for (const Sample& s : m_kept) {
        if (m_ticks - s.tick > m_config.sampleTicks) continue;  // the link may have changed since
        const int64_t depth = int64_t{s.depth} - shift;
        if (depth <= 0) continue;  // that rollback no longer happens
        // Cost scales with the steps the tick does: the re-simulated frames and the new one.
        m_scratch.push_back(uint64_t{s.micros} * static_cast<uint64_t>(depth + 1) / (uint64_t{s.depth} + 1));
    }
    if (m_scratch.empty()) return 0;
    const size_t rank = (m_scratch.size() * m_config.percentile + 99) / 100 - 1;
    std::nth_element(m_scratch.begin(), m_scratch.begin() + static_cast<std::ptrdiff_t>(rank), m_scratch.end());
    return m_scratch[rank];
}

uint32_t RollbackBudgetGuard::CostPercentileMicros() const {
    const uint64_t p = PredictedPercentile(0);
    return p > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(p);
}

void RollbackBudgetGuard::Changed() {
    // Remember what one frame costs (the median over the kept rollbacks) for lowering
    // decisions made before any rollback is seen at the new delay.
    if (!m_kept.empty()) {
        m_scratch.clear();
        for (const Sample& s : m_kept) m_scratch.push_back(uint64_t{s.micros} / (uint64_t{s.depth} + 1));
        const size_t mid = m_scratch.size() / 2;
        std::nth_element(m_scratch.begin(), m_scratch.begin() + static_cast<std::ptrdiff_t>(mid), m_scratch.end());
        m_frameMicros = m_scratch[mid];
    }
    // The old samples describe the old delay.
    m_kept.clear();
    m_next = 0;
    m_sinceChange = 0;
}

bool RollbackBudgetGuard::Record(uint32_t depth, uint32_t micros) {
    ++m_ticks;
    ++m_sinceChange;
    if (depth > 0) {
        const Sample s{m_ticks, depth, micros};
        if (m_kept.size() < m_config.rollbacksKept) {
            m_kept.push_back(s);
        } else {
            m_kept[m_next] = s;
            m_next = (m_next + 1) % m_kept.size();
        }
        if (!m_costSeen) m_frameMicros = uint64_t{micros} / (uint64_t{depth} + 1);
        m_costSeen = true;
        if (m_sinceChange >= m_config.settleTicks && m_kept.size() >= m_config.minRollbacks &&
            m_delay < m_config.maxDelay && PredictedPercentile(0) > m_config.budgetMicros) {
            // The smallest raise the model says fits; the largest allowed if none does.
            uint32_t k = 1;
            while (m_delay + k < m_config.maxDelay &&
                   PredictedPercentile(static_cast<int32_t>(k)) > m_config.budgetMicros)
                ++k;
            m_delay += k;
            ++m_raises;
            Changed();
            return true;
        }
    }
    if (m_delay > m_config.minDelay && m_sinceChange >= m_config.lowerAfterTicks && m_costSeen) {
        // One frame less delay: every rollback one frame deeper, and ticks that did not roll
        // back may now re-simulate one frame (two frames' worth of steps).
        const uint64_t deeper = std::max(PredictedPercentile(-1), 2 * m_frameMicros);
        if (deeper * 100 <= uint64_t{m_config.budgetMicros} * m_config.lowerMarginPercent) {
            --m_delay;
            ++m_lowerings;
            Changed();
            return true;
        }
    }
    return false;
}

}  // namespace lockbox::net
