// The budget guard over a slow link (150 ms RTT, 30 ms jitter, 5 % loss, no initial delay):
// more seeds with 2 peers and a 4-peer match (the fast suite runs one 2-peer seed). Heavy:
// each match is run with and without the guards, 1,500 frames.

#include <gtest/gtest.h>

#include "../rollback_budget_match.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

TEST(RollbackBudgetLong, KeepsASlowLinkMatchInsideTheBudget) {
    for (uint64_t seed : {6u, 7u}) ExpectGuardKeepsBudget(seed, 2);
}

TEST(RollbackBudgetLong, KeepsAFourPeerMatchInsideTheBudget) { ExpectGuardKeepsBudget(8, 4); }

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
