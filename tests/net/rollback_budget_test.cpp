// The rollback budget guard: RollbackSession::SetInputDelay (raising repeats, lowering absorbs
// repeats, no input lost) and RollbackBudgetGuard's policy, alone on scripted costs and in a
// SimNet match over a slow link where it must bring the re-simulation cost under budget.

#include <algorithm>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "RollbackMixGame.h"
#include "lockbox/net/RollbackBudgetGuard.h"
#include "lockbox/net/RollbackSession.h"
#include "rollback_budget_match.h"
#include "rollback_harness.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

std::vector<uint8_t> In(uint8_t v) { return std::vector<uint8_t>(2, v); }

std::unique_ptr<RollbackSession> Solo(uint32_t delay) {
    return RollbackSessionBuilder()
        .Players(2)
        .InputBytes(2)
        .LocalPlayer(0)
        .InputDelay(delay)
        .PredictionWindow(kRollbackMaxWindow)
        .Build();
}

// The local player's inputs as the frames got them, frame 0 on (first byte of each).
std::vector<uint8_t> LocalStream(const RollbackSession& s) {
    std::vector<uint8_t> out;
    for (int32_t f = 0; f < s.ReceivedFrame(0); ++f) out.push_back(s.ConfirmedInput(0, f)[0]);
    return out;
}

// Runs of equal values collapsed to one: what a player meant, whatever it was held for.
template <class T>
std::vector<T> Collapse(const std::vector<T>& v) {
    std::vector<T> out;
    for (const T& x : v)
        if (out.empty() || !(out.back() == x)) out.push_back(x);
    return out;
}

TEST(RollbackInputDelay, RaisingRepeatsTheLatestInputIntoTheOpenedFrames) {
    auto s = Solo(1);
    EXPECT_EQ(s->AddLocalInput(0, In(7)), InputResult::e_ok);  // frame 1 (frame 0 is the delay's zero)
    s->AdvanceFrame();
    EXPECT_TRUE(s->SetInputDelay(4));
    EXPECT_EQ(s->InputDelay(), 4u);
    EXPECT_EQ(s->Stats().inputsRepeated, 3u);
    // Frames 2..4 repeat 7; the next input lands on CurrentFrame() + 4 = frame 5.
    EXPECT_EQ(s->ReceivedFrame(0), 5);
    EXPECT_EQ(s->AddLocalInput(0, In(9)), InputResult::e_ok);
    EXPECT_EQ(s->AddLocalInput(0, In(9)), InputResult::e_alreadyAdded);
    EXPECT_EQ(LocalStream(*s), (std::vector<uint8_t>{0, 7, 7, 7, 7, 9}));
    EXPECT_FALSE(s->SetInputDelay(kRollbackMaxInputDelay + 1));
    EXPECT_EQ(s->InputDelay(), 4u);
}

TEST(RollbackInputDelay, LoweringAbsorbsOnlyRepeatsSoNoPressIsLost) {
    auto s = Solo(4);
    const std::vector<uint8_t> script = {1, 1, 2, 3, 3, 3, 4, 5, 5, 5, 5, 6, 6, 6};
    std::vector<int32_t> lead;  // queued frames ahead of the current one after each tick
    for (size_t t = 0; t < script.size(); ++t) {
        if (t == 2) {
            EXPECT_TRUE(s->SetInputDelay(1));
        }
        EXPECT_EQ(s->AddLocalInput(0, In(script[t])), InputResult::e_ok) << t;
        s->AdvanceFrame();
        lead.push_back(s->ReceivedFrame(0) - s->CurrentFrame());
    }
    // Three frames were owed; the repeats at ticks 4, 5 and 8 paid them (the 2 -> 3 and 3 -> 4
    // changes were queued, not dropped).
    EXPECT_EQ(s->Stats().inputsAbsorbed, 3u);
    EXPECT_EQ(lead.front(), 4);
    EXPECT_EQ(lead.back(), 1);
    const std::vector<uint8_t> got = LocalStream(*s);
    std::vector<uint8_t> meant = {0, 0, 0, 0};  // the delay's four leading zero frames
    for (uint8_t v : script) meant.push_back(v);
    EXPECT_EQ(Collapse(got), Collapse(meant));
    EXPECT_EQ(got.size() + 3, meant.size());
}

// Analog input: byte 0 is the buttons, byte 1 a stick that moves every tick, so no two
// inputs are equal.
std::vector<uint32_t> AnalogLowering(InputRepeatTest test, uint64_t* absorbed) {
    auto s = RollbackSessionBuilder()
                 .Players(2)
                 .InputBytes(2)
                 .LocalPlayer(0)
                 .InputDelay(4)
                 .PredictionWindow(kRollbackMaxWindow)
                 .RepeatTest(std::move(test))
                 .Build();
    const std::vector<uint8_t> buttons = {0, 0, 0, 1, 1, 0, 0, 0, 2, 2, 2, 0};
    std::vector<uint32_t> lead;
    for (size_t t = 0; t < buttons.size(); ++t) {
        if (t == 2) {
            EXPECT_TRUE(s->SetInputDelay(1));
        }
        const std::vector<uint8_t> in = {buttons[t], static_cast<uint8_t>(100 + t)};
        EXPECT_EQ(s->AddLocalInput(0, in), InputResult::e_ok) << t;
        s->AdvanceFrame();
        lead.push_back(static_cast<uint32_t>(s->ReceivedFrame(0) - s->CurrentFrame()));
    }
    // Every button edge arrived, in order, whatever was absorbed.
    std::vector<uint8_t> got;
    for (int32_t f = 4; f < s->ReceivedFrame(0); ++f) got.push_back(s->ConfirmedInput(0, f)[0]);
    EXPECT_EQ(Collapse(got), (std::vector<uint8_t>{0, 1, 0, 2, 0}));
    *absorbed = s->Stats().inputsAbsorbed;
    return lead;
}

TEST(RollbackInputDelay, AnalogInputPaysBackALoweringOnlyWithARepeatTest) {
    uint64_t absorbed = 0;
    // Equal bytes only (the default): the stick never repeats, the old delay stays.
    std::vector<uint32_t> lead = AnalogLowering({}, &absorbed);
    EXPECT_EQ(absorbed, 0u);
    EXPECT_EQ(lead.back(), 4u);
    // "The same buttons": ticks 2, 4 and 6 repeat their predecessor's buttons and pay the
    // three frames owed; the press at tick 3 and the release at tick 5 are queued.
    int calls = 0;
    lead = AnalogLowering(
        [&calls](uint32_t player, std::span<const uint8_t> previous, std::span<const uint8_t> next) {
            EXPECT_EQ(player, 0u);
            ++calls;
            return previous[0] == next[0];
        },
        &absorbed);
    EXPECT_EQ(absorbed, 3u);
    EXPECT_EQ(calls, 5);  // asked only while frames were owed (ticks 2..6)
    EXPECT_EQ(lead[6], 1u);
    EXPECT_EQ(lead.back(), 1u);
}

TEST(RollbackInputDelay, ARaiseCancelsWhatALoweringStillOwes) {
    auto s = Solo(3);
    EXPECT_TRUE(s->SetInputDelay(0));  // owes 3, nothing repeated yet
    EXPECT_TRUE(s->SetInputDelay(2));  // cancels 2 of the 3 owed: still owes 1, repeats none
    EXPECT_EQ(s->Stats().inputsRepeated, 0u);
    EXPECT_EQ(s->AddLocalInput(0, In(5)), InputResult::e_ok);
    s->AdvanceFrame();
    EXPECT_EQ(s->AddLocalInput(0, In(5)), InputResult::e_ok);  // a repeat: absorbed
    EXPECT_EQ(s->Stats().inputsAbsorbed, 1u);
    s->AdvanceFrame();
    EXPECT_EQ(s->ReceivedFrame(0) - s->CurrentFrame(), 2);  // the delay asked for
}

TEST(RollbackInputDelay, TheWindowEdgeStillRefusesASecondInputPerTick) {
    auto s = RollbackSessionBuilder().Players(2).InputBytes(2).LocalPlayer(0).PredictionWindow(2).InputDelay(3).Build();
    for (int t = 0; t < 3; ++t) {
        s->AddLocalInput(0, In(1));
        s->AdvanceFrame();
    }
    EXPECT_TRUE(s->SetInputDelay(1));  // owes 2 while the session waits at the edge
    const int32_t before = s->ReceivedFrame(0);
    EXPECT_EQ(s->AddLocalInput(0, In(1)), InputResult::e_alreadyAdded);
    EXPECT_EQ(s->AddLocalInput(0, In(2)), InputResult::e_alreadyAdded);
    EXPECT_EQ(s->ReceivedFrame(0), before);
    EXPECT_EQ(s->Stats().inputsAbsorbed, 0u);
}

RollbackBudgetConfig Quick() {
    RollbackBudgetConfig c;
    c.budgetMicros = 4000;
    c.rollbacksKept = 20;
    c.minRollbacks = 10;
    c.settleTicks = 10;
    c.lowerAfterTicks = 50;
    return c;
}

TEST(RollbackBudgetGuard, ChecksItsSettings) {
    EXPECT_TRUE(RollbackBudgetGuard::Check(RollbackBudgetConfig{}).empty());
    // Each setting just outside its range, with the words the reason must name.
    struct Bad {
        void (*spoil)(RollbackBudgetConfig&);
        const char* names;
    };
    const Bad bad[] = {
        {[](RollbackBudgetConfig& c) { c.budgetMicros = 0; }, "budget"},
        {[](RollbackBudgetConfig& c) { c.percentile = 101; }, "percentile"},
        {[](RollbackBudgetConfig& c) { c.maxDelay = kRollbackMaxInputDelay + 1; }, "max delay"},
        {[](RollbackBudgetConfig& c) {
             c.minDelay = 5;
             c.maxDelay = 4;
         },
         "min delay"},
        {[](RollbackBudgetConfig& c) { c.rollbacksKept = 9; }, "rollbacks kept"},
        {[](RollbackBudgetConfig& c) { c.minRollbacks = c.rollbacksKept + 1; }, "min rollbacks"},
        {[](RollbackBudgetConfig& c) { c.sampleTicks = 0; }, "sample ticks"},
        {[](RollbackBudgetConfig& c) { c.lowerMarginPercent = 0; }, "lower margin"},
    };
    for (const Bad& b : bad) {
        RollbackBudgetConfig c;
        b.spoil(c);
        const std::string_view why = RollbackBudgetGuard::Check(c);
        EXPECT_NE(why.find(b.names), std::string_view::npos) << b.names << ": " << why;
    }
    EXPECT_EQ(RollbackBudgetGuard(RollbackBudgetConfig{}, 40).Delay(), 16u);  // clamped
}

TEST(RollbackBudgetGuard, RaisesAtOnceByWhatTheCostModelNeeds) {
    RollbackBudgetGuard g(Quick(), 0);
    int changes = 0;
    // Depth-8 rollbacks at 1 ms per frame stepped: 9 ms against a 4 ms budget. Depth 3
    // (4 frames, 4 ms) is the first that fits: a raise of 5.
    for (int t = 0; t < 10; ++t) changes += g.Record(8, 9000) ? 1 : 0;
    EXPECT_EQ(changes, 1);  // the 10th rollback (settled, enough of them) raised
    EXPECT_EQ(g.Delay(), 5u);
    EXPECT_EQ(g.Raises(), 1u);
    EXPECT_EQ(g.RollbacksKept(), 0u);  // the old delay's samples are dropped
    // Rollbacks now depth 3 at the same per-frame cost: within budget, no further change.
    for (int t = 0; t < 40; ++t) changes += g.Record(3, 4000) ? 1 : 0;
    EXPECT_EQ(changes, 1);
    EXPECT_EQ(g.CostPercentileMicros(), 4000u);
}

TEST(RollbackBudgetGuard, StopsAtTheLargestDelayAllowed) {
    RollbackBudgetConfig c = Quick();
    c.maxDelay = 3;
    RollbackBudgetGuard g(c, 1);
    for (int t = 0; t < 30; ++t) g.Record(12, 13000);
    EXPECT_EQ(g.Delay(), 3u);
}

TEST(RollbackBudgetGuard, OnePercentOfOutliersDoesNotRaise) {
    RollbackBudgetConfig c = Quick();
    c.rollbacksKept = 200;
    c.minRollbacks = 100;
    c.lowerAfterTicks = 100000;
    RollbackBudgetGuard g(c, 2);
    // 99 % of rollbacks at 2 ms, 1 % at 30 ms: the 99th percentile is 2 ms.
    for (int t = 0; t < 400; ++t) EXPECT_FALSE(g.Record(t % 100 == 99 ? 29 : 1, t % 100 == 99 ? 30000 : 2000)) << t;
    EXPECT_EQ(g.Delay(), 2u);
}

TEST(RollbackBudgetGuard, LowersSlowlyAndOnlyWithRoomToSpare) {
    RollbackBudgetGuard g(Quick(), 4);
    // Depth-1 rollbacks at 1 ms per frame: one frame deeper costs 3 ms, within 75 % of 4 ms.
    int t = 0;
    for (; t < 49; ++t) EXPECT_FALSE(g.Record(1, 2000));
    EXPECT_TRUE(g.Record(1, 2000));  // tick 50: the first moment a lowering is considered
    EXPECT_EQ(g.Delay(), 3u);
    EXPECT_EQ(g.Lowerings(), 1u);
    // No rollbacks at all: the per-frame cost remembered (1 ms) predicts 2 ms for the new
    // depth-1 rollbacks a lower delay brings; it lowers once per quiet period.
    for (t = 0; t < 50; ++t) g.Record(0, 0);
    EXPECT_EQ(g.Delay(), 2u);
    for (t = 0; t < 50; ++t) g.Record(0, 0);
    EXPECT_EQ(g.Delay(), 1u);

    // Depth-2 rollbacks (3 ms): one deeper would be 4 ms, over 75 % of the budget: stays.
    RollbackBudgetGuard h(Quick(), 4);
    for (t = 0; t < 300; ++t) EXPECT_FALSE(h.Record(2, 3000));
    EXPECT_EQ(h.Delay(), 4u);
}

TEST(RollbackBudgetGuard, ForgetsRollbacksOlderThanTheSampleTicks) {
    RollbackBudgetConfig c = Quick();
    c.sampleTicks = 100;
    RollbackBudgetGuard g(c, 6);
    // Depth-3 rollbacks at 1 ms per frame: one deeper is 5 ms, over 75 % of 4 ms: stays.
    for (int t = 0; t < 60; ++t) EXPECT_FALSE(g.Record(3, 4000));
    EXPECT_EQ(g.CostPercentileMicros(), 4000u);
    // Then the link gets fast: no rollbacks. Once the last one is 100 ticks old, only the
    // remembered per-frame cost counts (2 ms for a depth-1 rollback) and the delay comes down.
    int t = 0;
    while (!g.Record(0, 0)) ASSERT_LT(++t, 200);
    EXPECT_EQ(t, 100);  // the 101st quiet tick: the newest rollback has just aged out
    EXPECT_EQ(g.Delay(), 5u);
    EXPECT_EQ(g.CostPercentileMicros(), 0u);
}

TEST(RollbackBudgetGuard, NeverLowersWithoutHavingSeenACost) {
    RollbackBudgetGuard g(Quick(), 3);
    for (int t = 0; t < 500; ++t) EXPECT_FALSE(g.Record(0, 0));
    EXPECT_EQ(g.Delay(), 3u);
}

TEST(RollbackBudgetGuard, LowersWhenTheSeenCostRoundsToZeroMicroseconds) {
    // A cheap game: its rollbacks take under a microsecond, so the per-frame cost remembered
    // is 0. That is a cost seen, not none: the delay still comes down after the quiet period.
    RollbackBudgetGuard g(Quick(), 3);
    EXPECT_FALSE(g.Record(1, 0));
    int t = 1;
    while (!g.Record(0, 0)) ASSERT_LT(++t, 200);
    EXPECT_EQ(t, 49);  // the 50th tick since the start: lowerAfterTicks
    EXPECT_EQ(g.Delay(), 2u);
}

// One seed here; more seeds and 4 peers in heavy/rollback_budget_matrix_test.cpp.
TEST(RollbackBudgetGuard, KeepsASlowLinkMatchInsideTheBudget) { ExpectGuardKeepsBudget(5, 2); }

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
