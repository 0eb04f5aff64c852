// LatencyTransport: its rates over many datagrams, one schedule per seed, reordering and
// duplication, and a rollback match through it on SimNet that still agrees on its hashes.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/LatencyTransport.h"
#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/SimNet.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

/// One delivery: when, and which datagram (its sequence number in the payload).
using Schedule = std::vector<std::pair<uint64_t, uint32_t>>;

/// Endpoint 0 sends `count` numbered datagrams to endpoint 1, one every 1 ms, on a perfect
/// SimNet link; endpoint 1 reads through a LatencyTransport polled every 1 ms.
Schedule RunLink(uint64_t seed, const LatencyProfile& profile, uint32_t count, LatencyStats* stats = nullptr) {
    SimNet net(7);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LatencyTransport late(b, profile, seed);
    Schedule out;
    std::vector<Datagram> got;
    const uint64_t drain = uint64_t{profile.latencyMicros} + profile.jitterMicros + profile.reorderDelayMicros;
    for (uint64_t t = 0; t < count + drain / 1000 + 2; ++t) {
        if (t < count) {
            const auto n = static_cast<uint32_t>(t);
            const uint8_t bytes[4] = {static_cast<uint8_t>(n), static_cast<uint8_t>(n >> 8),
                                      static_cast<uint8_t>(n >> 16), static_cast<uint8_t>(n >> 24)};
            EXPECT_TRUE(a.Send(b.Index(), bytes));
        }
        got.clear();
        late.Poll(got);
        for (const Datagram& d : got) {
            EXPECT_EQ(d.peer, a.Index());
            EXPECT_EQ(d.bytes.size(), 4u);
            const uint32_t n = d.bytes[0] | d.bytes[1] << 8 | d.bytes[2] << 16 | uint32_t{d.bytes[3]} << 24;
            out.emplace_back(late.NowMicros(), n);
        }
        net.Advance(1000);
    }
    EXPECT_EQ(late.Held(), 0u);
    if (stats != nullptr) *stats = late.Impairments();
    return out;
}

TEST(LatencyTransport, NoImpairmentPassesEverythingAtOnce) {
    const Schedule s = RunLink(1, LatencyProfile{}, 100);
    ASSERT_EQ(s.size(), 100u);
    for (uint32_t i = 0; i < 100; ++i) {
        EXPECT_EQ(s[i].second, i);
        EXPECT_EQ(s[i].first, uint64_t{i} * 1000);
    }
}

TEST(LatencyTransport, RatesAreMetOverManyDatagrams) {
    LatencyProfile p;
    p.latencyMicros = 30000;
    p.jitterMicros = 10000;
    p.lossPermille = 100;
    p.duplicatePermille = 50;
    p.reorderPermille = 20;
    constexpr uint32_t kCount = 20000;
    LatencyStats st;
    const Schedule s = RunLink(42, p, kCount, &st);
    EXPECT_EQ(st.received, kCount);
    EXPECT_EQ(st.delivered, s.size());
    EXPECT_EQ(st.received + st.duplicated, st.delivered + st.lost);
    // Binomial with n = 20,000: 5 standard deviations either side.
    EXPECT_NEAR(static_cast<double>(st.lost), 2000.0, 5 * 42.4);  // p = 0.1
    const double kept = static_cast<double>(kCount - st.lost);
    EXPECT_NEAR(static_cast<double>(st.duplicated), kept * 0.05, 5 * 29.4);
    EXPECT_NEAR(static_cast<double>(st.reordered), kept * 0.02, 5 * 18.8);
    // Every delivery is due between latency and latency + jitter (+ the reorder hold-back)
    // after its send, rounded up to the 1 ms poll.
    uint64_t sumDelay = 0;
    for (const auto& [when, n] : s) {
        const uint64_t delay = when - uint64_t{n} * 1000;
        EXPECT_GE(delay, p.latencyMicros);
        EXPECT_LE(delay, uint64_t{p.latencyMicros} + p.jitterMicros + p.reorderDelayMicros + 1000);
        sumDelay += delay;
    }
    // Mean delay: latency + jitter / 2, plus 1 ms granularity at most, plus the reordered 2 %.
    const double mean = static_cast<double>(sumDelay) / static_cast<double>(s.size());
    EXPECT_GT(mean, 34000.0);
    EXPECT_LT(mean, 37000.0);
}

TEST(LatencyTransport, SameSeedSameScheduleOtherSeedAnother) {
    LatencyProfile p;
    p.latencyMicros = 5000;
    p.jitterMicros = 8000;
    p.lossPermille = 50;
    p.duplicatePermille = 50;
    p.reorderPermille = 50;
    const Schedule first = RunLink(9, p, 2000);
    EXPECT_EQ(first, RunLink(9, p, 2000));
    EXPECT_NE(first, RunLink(10, p, 2000));
}

TEST(LatencyTransport, ReordersAndDuplicates) {
    LatencyProfile p;
    p.latencyMicros = 2000;
    p.duplicatePermille = 100;
    p.reorderPermille = 100;
    p.reorderDelayMicros = 5000;
    const Schedule s = RunLink(3, p, 1000);
    uint32_t overtaken = 0, copies = 0;
    std::vector<uint32_t> seen(1000, 0);
    uint32_t highest = 0;
    for (const auto& [when, n] : s) {
        if (n < highest) ++overtaken;
        highest = std::max(highest, n);
        ++seen[n];
    }
    for (uint32_t c : seen) {
        EXPECT_GE(c, 1u);  // no loss configured
        EXPECT_LE(c, 2u);
        if (c == 2) ++copies;
    }
    EXPECT_GT(overtaken, 50u);
    EXPECT_GT(copies, 50u);
}

TEST(LatencyTransport, DisconnectForgetsHeldDatagrams) {
    SimNet net(1);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LatencyProfile p;
    p.latencyMicros = 10000;
    LatencyTransport late(b, p, 1);
    const uint8_t one[1] = {1};
    ASSERT_TRUE(a.Send(b.Index(), one));
    std::vector<Datagram> got;
    EXPECT_EQ(late.Poll(got), 0u);
    EXPECT_EQ(late.Held(), 1u);
    EXPECT_EQ(late.NextDueMicros(), 10000u);
    late.Disconnect(a.Index());
    EXPECT_EQ(late.Held(), 0u);
    EXPECT_EQ(late.Impairments().forgotten, 1u);
    net.Advance(20000);
    EXPECT_EQ(late.Poll(got), 0u);
    // Sends pass straight through, and the stats count what was handed out.
    ASSERT_TRUE(late.Send(a.Index(), one));
    EXPECT_EQ(late.Stats().datagramsSent, 1u);
    EXPECT_EQ(late.Stats().datagramsReceived, 0u);
}

// Two peers on SimNet, each reading through a LatencyTransport (40 ms, 10 ms jitter, 5 % loss,
// duplicates and reordering): the match runs, rolls back, and every final hash agrees.
TEST(LatencyTransport, RollbackMatchThroughItAgrees) {
    constexpr int32_t kFrames = 180;
    SimNet net(5);
    LatencyProfile p;
    p.latencyMicros = 40000;
    p.jitterMicros = 10000;
    p.lossPermille = 50;
    p.duplicatePermille = 20;
    p.reorderPermille = 20;
    struct Side {
        std::unique_ptr<LatencyTransport> transport;
        std::unique_ptr<replay::SceneGame> game;
        std::unique_ptr<RollbackSession> session;
        std::unique_ptr<WorldGameAdapter> adapter;
        std::unique_ptr<RollbackPeer> peer;
        std::unique_ptr<replay::ScriptedInputs> script;
        std::vector<uint8_t> input;
        bool pending = false;
    } sides[2];
    SimEndpoint* ends[2] = {&net.AddEndpoint(), &net.AddEndpoint()};
    for (uint32_t i = 0; i < 2; ++i) {
        Side& s = sides[i];
        s.transport = std::make_unique<LatencyTransport>(*ends[i], p, 100 + i);
        s.game = std::make_unique<replay::SceneGame>("vertical_stack");
        ASSERT_TRUE(s.game->ok());
        s.session = RollbackSessionBuilder()
                        .Players(2)
                        .InputBytes(replay::SceneInput::kBytes)
                        .LocalPlayer(i)
                        .InputDelay(1)
                        .DesyncInterval(10)
                        .Build();
        ASSERT_NE(s.session, nullptr);
        const auto& info = s.game->info();
        s.adapter = std::make_unique<WorldGameAdapter>(
            s.game->world(), *s.game,
            WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                              static_cast<uint32_t>(info.positionIterations)});
        RollbackPeerConfig cfg;
        cfg.remotes.push_back(RollbackRemote{ends[1 - i]->Index(), {1 - i}});
        s.peer = std::make_unique<RollbackPeer>(*s.session, *s.transport, cfg);
        s.script = std::make_unique<replay::ScriptedInputs>(77 + i, 1);
    }
    for (int tick = 0; tick < kFrames * 4; ++tick) {
        bool done = true;
        for (uint32_t i = 0; i < 2; ++i) {
            Side& s = sides[i];
            s.peer->Poll();
            if (!s.peer->WaitThisTick()) {
                if (!s.pending) s.script->Next(s.input);
                s.pending = s.session->AddLocalInput(i, s.input) == InputResult::e_alreadyAdded;
                const auto reqs = s.session->AdvanceFrame();
                ASSERT_TRUE(s.adapter->Execute(*s.session, reqs));
            }
            s.peer->Flush();
            for (const RollbackEvent& e : s.session->TakeEvents())
                ASSERT_NE(e.kind, RollbackEvent::Kind::e_desync) << "frame " << e.frame;
            done = done && s.session->ConfirmedFrame() >= kFrames;
        }
        if (done) break;
        net.Advance(16666);
    }
    uint32_t compared = 0;
    for (const auto& [f, h] : sides[0].session->FinalHashes())
        for (const auto& [g, k] : sides[1].session->FinalHashes())
            if (f == g) {
                EXPECT_EQ(h, k) << "frame " << f;
                ++compared;
            }
    EXPECT_GE(sides[0].session->ConfirmedFrame(), kFrames);
    EXPECT_GE(sides[1].session->ConfirmedFrame(), kFrames);
    EXPECT_GT(compared, 0u);
    EXPECT_GT(sides[0].session->Stats().hashesCompared + sides[1].session->Stats().hashesCompared, 10u);
    EXPECT_GT(sides[0].session->Stats().rollbacks + sides[1].session->Stats().rollbacks, 0u);
    EXPECT_GT(sides[0].transport->Impairments().lost, 0u);
    EXPECT_GT(sides[1].transport->Impairments().duplicated, 0u);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
