// The whole lockstep impairment matrix on SimNet: RTT {0, 50, 150, 300 ms} x loss {0, 5 %,
// 20 %, bursts} x jitter {0, 30 ms} x {2, 4, 8} clients (the jitter-0 rows are the
// constant-latency ones). Every cell: equal final hashes, a moving world, no desync, and the
// upstream budget (tests/net/LockstepHarness.h, UpBudgetBitsPerSecond).

#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "../LockstepHarness.h"

namespace lockbox::net::testing {
namespace LOCKBOX_TEST_FILE {

enum Loss { e_none, e_five, e_twenty, e_bursts };
using Cell = std::tuple<uint32_t, Loss, uint32_t, uint32_t>;  // rtt ms, loss, jitter ms, clients

class LockstepMatrix : public ::testing::TestWithParam<Cell> {};

TEST_P(LockstepMatrix, Agrees) {
    const auto [rtt, loss, jitter, clients] = GetParam();
    MatchSpec s;
    // A distinct seed per cell, printed by RunMatrixCell's trace on failure.
    s.seed = 1000 + rtt * 97 + static_cast<uint64_t>(loss) * 13 + jitter * 7 + clients;
    s.clients = clients;
    s.rttMs = rtt;
    s.lossPpm = loss == e_five ? 50'000 : loss == e_twenty ? 200'000 : 0;
    s.bursts = loss == e_bursts;
    s.jitterMs = jitter;
    s.frames = 400;
    RunMatrixCell(s);
}

std::string CellName(const ::testing::TestParamInfo<Cell>& info) {
    const auto [rtt, loss, jitter, clients] = info.param;
    static const char* kLoss[] = {"Loss0", "Loss5", "Loss20", "Bursts"};
    return "Rtt" + std::to_string(rtt) + "_" + kLoss[loss] + "_Jitter" + std::to_string(jitter) + "_Clients" +
           std::to_string(clients);
}

INSTANTIATE_TEST_SUITE_P(All, LockstepMatrix,
                         ::testing::Combine(::testing::Values(0u, 50u, 150u, 300u),
                                            ::testing::Values(e_none, e_five, e_twenty, e_bursts),
                                            ::testing::Values(0u, 30u), ::testing::Values(2u, 4u, 8u)),
                         CellName);

// Ten per cent loss, the budget's second point: at most twice the no-loss budget.
TEST(LockstepBudget, TenPercentLossStaysWithinTwiceTheBudget) {
    for (uint32_t rtt : {50u, 150u, 300u}) {
        MatchSpec s;
        s.seed = 77 + rtt;
        s.clients = 4;
        s.rttMs = rtt;
        s.lossPpm = 100'000;
        s.frames = 600;
        RunMatrixCell(s);
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::testing
