// RollbackSession core: the request stream, prediction, the window edge, input delay,
// disconnects, and final-hash desync detection, on a tiny integer game with no network.

#include <cstdint>
#include <deque>
#include <map>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "RollbackMixGame.h"
#include "lockbox/net/RollbackSession.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

std::vector<uint8_t> In(uint8_t v) { return std::vector<uint8_t>(2, v); }

std::unique_ptr<RollbackSession> Two(uint32_t local, uint32_t delay = 0, uint32_t window = 8, uint32_t interval = 1) {
    return RollbackSessionBuilder()
        .Players(2)
        .InputBytes(2)
        .LocalPlayer(local)
        .InputDelay(delay)
        .PredictionWindow(window)
        .DesyncInterval(interval)
        .Build();
}

int CountAdvances(const std::vector<RollbackRequest>& reqs) {
    int n = 0;
    for (const auto& r : reqs) n += std::holds_alternative<AdvanceRequest>(r) ? 1 : 0;
    return n;
}

TEST(RollbackSession, BuilderChecksSettings) {
    EXPECT_TRUE(RollbackSessionBuilder().LocalPlayer(0).Check().empty());
    EXPECT_FALSE(RollbackSessionBuilder().Players(0).Check().empty());
    EXPECT_FALSE(RollbackSessionBuilder().Players(9).Check().empty());
    EXPECT_FALSE(RollbackSessionBuilder().InputBytes(0).Check().empty());
    EXPECT_FALSE(RollbackSessionBuilder().LocalPlayer(2).Check().empty());
    EXPECT_FALSE(RollbackSessionBuilder().LocalPlayer(1).LocalPlayer(1).Check().empty());
    EXPECT_FALSE(RollbackSessionBuilder().PredictionWindow(0).Check().empty());
    EXPECT_FALSE(RollbackSessionBuilder().InputDelay(17).Check().empty());
    EXPECT_EQ(RollbackSessionBuilder().Players(0).Build(), nullptr);
}

TEST(RollbackSession, FirstTickSavesAdvancesSaves) {
    auto s = Two(0);
    EXPECT_EQ(s->AddLocalInput(0, In(5)), InputResult::e_ok);
    EXPECT_EQ(s->AddLocalInput(0, In(5)), InputResult::e_alreadyAdded);
    EXPECT_EQ(s->AddLocalInput(1, In(5)), InputResult::e_badPlayer);
    EXPECT_EQ(s->AddLocalInput(0, std::vector<uint8_t>(3, 0)), InputResult::e_badSize);
    const auto reqs = s->AdvanceFrame();
    ASSERT_EQ(reqs.size(), 3u);
    EXPECT_EQ(std::get<SaveState>(reqs[0]).frame, 0);
    const auto& a = std::get<AdvanceRequest>(reqs[1]);
    EXPECT_EQ(a.frame, 0);
    EXPECT_EQ(a.inputs, (std::vector<uint8_t>{5, 5, 0, 0}));
    EXPECT_EQ(a.status[0], InputStatus::e_confirmed);
    EXPECT_EQ(a.status[1], InputStatus::e_predicted);
    EXPECT_EQ(std::get<SaveState>(reqs[2]).frame, 1);
    EXPECT_EQ(s->CurrentFrame(), 1);
    // No local input for frame 1 yet: nothing to advance.
    EXPECT_EQ(CountAdvances(s->AdvanceFrame()), 0);
}

TEST(RollbackSession, WaitsAtWindowEdgeAndNeverDropsInputs) {
    auto s = Two(0, 0, 4);
    MixGame g;
    for (int t = 0; t < 10; ++t) {
        s->AddLocalInput(0, In(static_cast<uint8_t>(t)));
        g.Run(*s, s->AdvanceFrame());
    }
    EXPECT_EQ(s->CurrentFrame(), 4);
    EXPECT_GE(s->Stats().waits, 6u);
    auto ev = s->TakeEvents();
    ASSERT_EQ(ev.size(), 1u);  // one waiting event per stall
    EXPECT_EQ(ev[0].kind, RollbackEvent::Kind::e_waiting);
    // The local inputs of the stalled ticks were refused, not dropped silently: the one of
    // frame 4 is still queued.
    EXPECT_EQ(s->ReceivedFrame(0), 5);
    // Remote inputs for frames 0..2: the window opens by 3 frames.
    for (int32_t f = 0; f < 3; ++f) EXPECT_EQ(s->AddRemoteInput(1, f, In(0)), InputResult::e_ok);
    EXPECT_EQ(s->AddRemoteInput(1, 2, In(0)), InputResult::e_duplicate);
    EXPECT_EQ(s->AddRemoteInput(1, 5, In(0)), InputResult::e_gap);
    EXPECT_EQ(s->AddRemoteInput(0, 3, In(0)), InputResult::e_badPlayer);
    g.Run(*s, s->AdvanceFrame());
    EXPECT_EQ(s->CurrentFrame(), 5);
    EXPECT_EQ(s->Stats().rollbacks, 0u);  // zeros were predicted right
}

TEST(RollbackSession, MispredictionRollsBackToTheFirstWrongFrame) {
    auto s = Two(0);
    MixGame g;
    for (int t = 0; t < 6; ++t) {
        s->AddLocalInput(0, In(1));
        g.Run(*s, s->AdvanceFrame());
    }
    ASSERT_EQ(s->CurrentFrame(), 6);
    s->AddRemoteInput(1, 0, In(0));
    s->AddRemoteInput(1, 1, In(0));
    s->AddRemoteInput(1, 2, In(9));  // predicted 0: wrong from frame 2
    s->AddLocalInput(0, In(1));
    const auto reqs = s->AdvanceFrame();
    ASSERT_FALSE(reqs.empty());
    EXPECT_EQ(std::get<LoadState>(reqs[0]).frame, 2);
    EXPECT_EQ(CountAdvances(reqs), 5);  // frames 2..5 again, then frame 6
    const auto& resim = std::get<AdvanceRequest>(reqs[1]);
    EXPECT_EQ(resim.frame, 2);
    EXPECT_EQ(resim.status[1], InputStatus::e_confirmed);
    const auto& predicted = std::get<AdvanceRequest>(reqs[3]);
    EXPECT_EQ(predicted.frame, 3);
    EXPECT_EQ(predicted.inputs[2], 9);  // repeat the last confirmed input
    EXPECT_EQ(predicted.status[1], InputStatus::e_predicted);
    g.Run(*s, reqs);
    EXPECT_EQ(s->Stats().rollbacks, 1u);
    EXPECT_EQ(s->Stats().deepestRollback, 4u);
    EXPECT_EQ(s->Stats().framesResimulated, 4u);
}

TEST(RollbackSession, CustomPredictorAndInputDelay) {
    auto s = RollbackSessionBuilder()
                 .Players(2)
                 .InputBytes(2)
                 .LocalPlayer(1)
                 .InputDelay(2)
                 .Predictor([](uint32_t, int32_t frame, std::span<const uint8_t>, int32_t, std::span<uint8_t> out) {
                     out[0] = static_cast<uint8_t>(frame);
                     out[1] = 0xAA;
                 })
                 .Build();
    ASSERT_NE(s, nullptr);
    s->AddLocalInput(1, In(7));
    const auto reqs = s->AdvanceFrame();
    const auto& a = std::get<AdvanceRequest>(reqs[1]);
    // Input delay 2: frame 0 has the empty input of player 1; its first input lands at 2.
    EXPECT_EQ(a.inputs, (std::vector<uint8_t>{0, 0xAA, 0, 0}));
    EXPECT_EQ(s->ReceivedFrame(1), 3);
    EXPECT_EQ(s->ConfirmedInput(1, 2)[0], 7);
}

TEST(RollbackSession, DisconnectedPlayerIsZeroAndUnblocksTheWindow) {
    auto s = Two(0, 0, 2);
    MixGame g;
    for (int t = 0; t < 4; ++t) {
        s->AddLocalInput(0, In(1));
        g.Run(*s, s->AdvanceFrame());
    }
    EXPECT_EQ(s->CurrentFrame(), 2);
    s->AddRemoteInput(1, 0, In(3));  // frame 0 was predicted 0, is 3: rollback next tick
    s->DisconnectPlayer(1);
    auto ev = s->TakeEvents();
    ASSERT_FALSE(ev.empty());
    EXPECT_EQ(ev.back().kind, RollbackEvent::Kind::e_disconnected);
    EXPECT_EQ(ev.back().frame, 1);
    EXPECT_EQ(s->AddRemoteInput(1, 1, In(3)), InputResult::e_disconnected);
    const auto reqs = s->AdvanceFrame();
    EXPECT_EQ(std::get<LoadState>(reqs[0]).frame, 0);  // frame 0's prediction (0) was wrong
    for (const auto& r : reqs)
        if (const auto* a = std::get_if<AdvanceRequest>(&r); a && a->frame >= 1) {
            EXPECT_EQ(a->status[1], InputStatus::e_disconnected);
        }
    g.Run(*s, reqs);
    for (int t = 0; t < 5; ++t) {
        s->AddLocalInput(0, In(1));
        g.Run(*s, s->AdvanceFrame());
    }
    EXPECT_EQ(s->CurrentFrame(), 8);
    EXPECT_EQ(s->ConfirmedFrame(), 8);
}

// Two sessions wired by hand with a delay of `lag` ticks between them.
struct Pair {
    std::unique_ptr<RollbackSession> s[2];
    MixGame g[2];
    std::map<int32_t, uint64_t> finals[2];
    std::vector<RollbackEvent> events[2];

    Pair(uint32_t window, uint32_t interval) {
        s[0] = Two(0, 1, window, interval);
        s[1] = Two(1, 1, window, interval);
    }
    void Run(int ticks, int lag, uint64_t seed) {
        uint64_t r = seed;
        std::vector<std::deque<std::pair<int64_t, std::pair<int32_t, std::vector<uint8_t>>>>> flight(2);
        std::vector<std::deque<std::pair<int64_t, std::pair<int32_t, uint64_t>>>> hashFlight(2);
        // The input-delay frames (empty inputs) travel like any other.
        for (int i = 0; i < 2; ++i)
            for (int32_t f = 0; f < s[i]->ReceivedFrame(static_cast<uint32_t>(i)); ++f) {
                const auto one = s[i]->ConfirmedInput(static_cast<uint32_t>(i), f);
                flight[i].push_back({lag, {f, std::vector<uint8_t>(one.begin(), one.end())}});
            }
        for (int t = 0; t < ticks; ++t) {
            for (int i = 0; i < 2; ++i) {
                RollbackSession& me = *s[i];
                while (!flight[1 - i].empty() && flight[1 - i].front().first <= t) {
                    const auto& [f, b] = flight[1 - i].front().second;
                    me.AddRemoteInput(static_cast<uint32_t>(1 - i), f, b);
                    flight[1 - i].pop_front();
                }
                while (!hashFlight[1 - i].empty() && hashFlight[1 - i].front().first <= t) {
                    me.AddRemoteHash(static_cast<uint32_t>(1 - i), hashFlight[1 - i].front().second.first,
                                     hashFlight[1 - i].front().second.second);
                    hashFlight[1 - i].pop_front();
                }
                const int32_t f = me.ReceivedFrame(static_cast<uint32_t>(i));
                r = r * 6364136223846793005ull + 1442695040888963407ull;
                // Inputs change now and then, so predictions are sometimes wrong.
                std::vector<uint8_t> in = In((r >> 60) < 3 ? static_cast<uint8_t>(r >> 40) : 1);
                if (me.AddLocalInput(static_cast<uint32_t>(i), in) == InputResult::e_ok)
                    flight[i].push_back({t + lag, {f, in}});
                g[i].Run(me, me.AdvanceFrame());
                for (const auto& [hf, h] : me.FinalHashes())
                    if (finals[i].emplace(hf, h).second) hashFlight[i].push_back({t + lag, {hf, h}});
                for (auto& e : me.TakeEvents())
                    if (e.kind == RollbackEvent::Kind::e_desync) events[i].push_back(e);
            }
        }
    }
};

TEST(RollbackSession, ConfirmedHashesAgreeAndNoFalseDesync) {
    for (uint64_t seed : {1ull, 2ull, 3ull}) {
        SCOPED_TRACE(::testing::Message() << "seed=" << seed);
        Pair p(8, 1);
        p.Run(600, 4, seed);
        EXPECT_GT(p.s[0]->Stats().rollbacks + p.s[1]->Stats().rollbacks, 0u);
        size_t common = 0;
        for (const auto& [f, h] : p.finals[0]) {
            auto it = p.finals[1].find(f);
            if (it == p.finals[1].end()) continue;
            ++common;
            EXPECT_EQ(it->second, h) << "frame " << f;
        }
        EXPECT_GT(common, 500u);
        EXPECT_TRUE(p.events[0].empty());
        EXPECT_TRUE(p.events[1].empty());
    }
}

TEST(RollbackSession, ForcedDivergenceReportedOnceAtTheRightFrame) {
    Pair p(8, 10);
    p.g[1].corruptAt = 123;  // the state after frame 123 differs: the first compared frame is 130
    p.Run(600, 3, 7);
    for (int i = 0; i < 2; ++i) {
        ASSERT_EQ(p.events[i].size(), 1u) << "peer " << i;
        EXPECT_EQ(p.events[i][0].frame, 130);
        EXPECT_NE(p.events[i][0].localHash, p.events[i][0].remoteHash);
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
