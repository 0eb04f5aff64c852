// The SimNet matrix for rollback: {2, 4} peers x RTT {0, 50, 150 ms} x loss {0, 5,
// 20 %} x jitter {0, 30 ms}, plus one 10,000-frame match with no false desync. Each cell
// prints one line of figures (rollbacks, depth, waits, frame-advantage spread) for
// docs/rollback.md; the assertions are behaviour only.

#include <cstdio>

#include <gtest/gtest.h>

#include "../rollback_harness.h"

namespace lockbox::net::rbtest {
namespace LOCKBOX_TEST_FILE {

struct Cell {
    uint32_t peers, rtt, loss, jitter;
};

void CheckAndPrint(const RbSpec& spec, const RbResult& r) {
    SCOPED_TRACE(spec.Describe());
    const size_t compared = ExpectHealthy(spec, r);
    uint64_t resim = 0, waits = 0, advanced = 0;
    uint32_t deepest = 0;
    for (const RbPeer& p : r.peers) {
        const RollbackStats& s = p.session->Stats();
        resim += s.framesResimulated;
        waits += s.waits;
        advanced += s.framesAdvanced;
        deepest = std::max(deepest, s.deepestRollback);
    }
    int32_t spreadMax = 0;
    for (int32_t v : r.spread) spreadMax = std::max(spreadMax, v);
    // peers rtt loss jitter | rollbacks/peer/100f resim/frame deepest waits/peer p95 max compared
    uint64_t bytes = 0;
    for (uint64_t b : r.wireBytesSent) bytes += b;
    // kbit/s upstream per peer: bytes * 8 / (ticks / 60 s) / 1000 / peers.
    const double kbps = static_cast<double>(bytes) * 8.0 * 60.0 / static_cast<double>(r.ticks) / 1000.0 /
                        static_cast<double>(spec.peers);
    std::printf("RBCELL %u,%u,%u,%u,%llu,%.3f,%u,%llu,%d,%d,%zu,%lld,%.1f\n", spec.peers, spec.rttMs, spec.lossPct,
                spec.jitterMs, static_cast<unsigned long long>(r.Rollbacks()),
                advanced ? static_cast<double>(resim) / static_cast<double>(advanced) : 0.0, deepest,
                static_cast<unsigned long long>(waits), r.SpreadP95(), spreadMax, compared,
                static_cast<long long>(r.ticks), kbps);
}

class RollbackMatrix : public ::testing::TestWithParam<Cell> {};

TEST_P(RollbackMatrix, PeersAgree) {
    const Cell c = GetParam();
    RbSpec spec;
    spec.seed = 7000 + c.peers * 1000 + c.rtt * 10 + c.loss + c.jitter;
    spec.peers = c.peers;
    spec.rttMs = c.rtt;
    spec.lossPct = c.loss;
    spec.jitterMs = c.jitter;
    spec.frames = 900;
    CheckAndPrint(spec, RunRbMatch(spec));
}

std::vector<Cell> AllCells() {
    std::vector<Cell> cells;
    for (uint32_t peers : {2u, 4u})
        for (uint32_t rtt : {0u, 50u, 150u})
            for (uint32_t loss : {0u, 5u, 20u})
                for (uint32_t jitter : {0u, 30u}) cells.push_back(Cell{peers, rtt, loss, jitter});
    return cells;
}

INSTANTIATE_TEST_SUITE_P(Cells, RollbackMatrix, ::testing::ValuesIn(AllCells()));

TEST(RollbackLong, TenThousandFramesNoFalseDesync) {
    RbSpec spec;
    spec.seed = 10000;
    spec.peers = 2;
    spec.rttMs = 150;
    spec.lossPct = 5;
    spec.jitterMs = 30;
    spec.frames = 10000;
    spec.desyncInterval = 1;  // every frame compared
    CheckAndPrint(spec, RunRbMatch(spec));
}

// The budget guard on a link that gets slow and then fast again (RTT 50 -> 250 -> 50 ms,
// 5 % loss, 30 ms jitter; 1 ms per frame stepped, 4 ms budget), every frame compared: the
// delay goes up while the link is slow and comes back down after, no false desync, no
// input lost through the changes.
TEST(RollbackLong, BudgetGuardFollowsAChangingLink) {
    for (uint32_t peers : {2u, 3u}) {
        RbSpec spec = SlowLinkSpec(20000 + peers, peers, 50, 8000, true);
        spec.desyncInterval = 1;
        spec.rttChanges = {{2000, 250}, {4500, 50}};
        const RbResult r = RunRbMatch(spec);
        CheckAndPrint(spec, r);
        for (size_t i = 0; i < r.peers.size(); ++i) {
            const RbPeer& p = r.peers[i];
            SCOPED_TRACE(::testing::Message() << spec.Describe() << " peer " << i);
            EXPECT_GE(p.maxDelay, 6u);                           // 125 ms one way is 7.5 frames
            EXPECT_LE(p.session->InputDelay() + 3, p.maxDelay);  // and most of it given back
            EXPECT_GE(p.guard->Lowerings(), 3u);
            ExpectNoInputLost(p);
            std::printf(
                "guard on a changing link: peers %u peer %zu: max delay %u, final %u, raises %u, lowerings %u, "
                "repeated %llu, absorbed %llu\n",
                peers, i, p.maxDelay, p.session->InputDelay(), p.guard->Raises(), p.guard->Lowerings(),
                static_cast<unsigned long long>(p.session->Stats().inputsRepeated),
                static_cast<unsigned long long>(p.session->Stats().inputsAbsorbed));
        }
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::rbtest
