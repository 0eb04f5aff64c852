// The disconnect agreement over the whole leave matrix (docs/rollback.md "Disconnects"):
// {3, 4} peers x {abrupt, RbDisconnect} x RTT {0, 50 ms} x loss {0, 5 %}, jitter 30 ms. The
// leaver's link to peer 0 dies 30 ticks before it leaves, so the survivors hold different
// amounts of its inputs; every survivor must cut it at the same frame and agree on every
// final hash 300 frames past the cut. Each run prints RBLEAVE lines (figures for the docs).
// The fast suite (rollback_disconnect_test.cpp) runs four of these cells.

#include <vector>

#include <gtest/gtest.h>

#include "../rollback_leave.h"

namespace lockbox::net::rbtest {
namespace LOCKBOX_TEST_FILE {

class RollbackLeaveMatrix : public ::testing::TestWithParam<Leave> {};

TEST_P(RollbackLeaveMatrix, SurvivorsAgreeOnTheCut) {
    const Leave c = GetParam();
    // Seeds apart from the fast suite's, so the heavy run adds draws rather than repeating them.
    RunLeaveCell(c, 41000 + c.peers * 1000 + c.rtt * 10 + c.loss + (c.graceful ? 500 : 0));
}

std::vector<Leave> AllLeaveCells() {
    std::vector<Leave> cells;
    for (uint32_t peers : {3u, 4u})
        for (bool graceful : {false, true})
            for (uint32_t rtt : {0u, 50u})
                for (uint32_t loss : {0u, 5u}) cells.push_back(Leave{peers, rtt, loss, 30, graceful});
    return cells;
}

INSTANTIATE_TEST_SUITE_P(Cells, RollbackLeaveMatrix, ::testing::ValuesIn(AllLeaveCells()));

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::rbtest
