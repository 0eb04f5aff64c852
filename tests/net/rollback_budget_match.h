#pragma once
// The budget guard in a SimNet match over a slow link (rollback_budget_test.cpp, and more
// seeds and peers in heavy/rollback_budget_matrix_test.cpp).

#include <algorithm>
#include <cstdint>
#include <cstdio>

#include <gtest/gtest.h>

#include "rollback_harness.h"

namespace lockbox::net {

// 150 ms RTT with jitter and loss and no input delay: rollbacks 5-8 frames deep. With 1 ms
// per frame stepped and a 4 ms budget the guards must raise the delay, then hold the cost
// under budget, the peers agree on every final hash, and no local press is lost.
inline void ExpectGuardKeepsBudget(uint64_t seed, uint32_t peers) {
    using namespace rbtest;
    const RbSpec spec = SlowLinkSpec(seed, peers, 150, 1500, false);
    const RbSpec guarded = SlowLinkSpec(seed, peers, 150, 1500, true);
    SCOPED_TRACE(guarded.Describe());

    const RbResult plain = RunRbMatch(spec);
    const RbResult r = RunRbMatch(guarded);
    ExpectHealthy(guarded, r);
    // Ticks from 10 s on (the guards have settled) whose re-simulation costs over the budget,
    // in thousandths of those ticks.
    auto overBudget = [&](const RbResult& run, const RbPeer& p) {
        const int64_t ticks = std::max<int64_t>(run.ticks - 600, 1);
        int64_t over = 0;
        for (const auto& [tick, micros] : p.rollbackCosts)
            over += tick >= 600 && micros > guarded.guardBudgetMicros ? 1 : 0;
        return over * 1000 / ticks;
    };
    int64_t plainWorst = 0;
    for (const RbPeer& p : plain.peers) plainWorst = std::max(plainWorst, overBudget(plain, p));
    EXPECT_GE(plainWorst, 50);  // without the guard, one tick in twenty or more is over budget
    for (size_t i = 0; i < r.peers.size(); ++i) {
        const RbPeer& p = r.peers[i];
        SCOPED_TRACE(::testing::Message() << "peer " << i);
        EXPECT_GE(p.session->InputDelay(), 2u);
        // The 99th percentile tick stays inside the budget.
        EXPECT_LE(overBudget(r, p), 10);
        std::printf(
            "budget guard seed %llu peer %zu/%u: delay %u (max %u), wish %u, raises %u, lowerings %u, "
            "over budget %lld/1000 ticks (%lld without the guard), repeated %llu absorbed %llu\n",
            static_cast<unsigned long long>(seed), i, peers, p.session->InputDelay(), p.maxDelay, p.guard->Delay(),
            p.guard->Raises(), p.guard->Lowerings(), static_cast<long long>(overBudget(r, p)),
            static_cast<long long>(overBudget(plain, plain.peers[i])),
            static_cast<unsigned long long>(p.session->Stats().inputsRepeated),
            static_cast<unsigned long long>(p.session->Stats().inputsAbsorbed));
        ExpectNoInputLost(p);
    }
}

}  // namespace lockbox::net
