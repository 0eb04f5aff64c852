// The figures of docs/net.md "Measured figures", printed from SimNet runs: per-peer bandwidth
// up and down at 0 % and 10 % loss, the time from a divergence to the desync event, and the
// time a late joiner takes to be admitted. Asserts behaviour only (each run finishes); the
// printed numbers are virtual-clock figures, so they are the same on every machine.

#include <cstdio>

#include <gtest/gtest.h>

#include "../LockstepHarness.h"

namespace lockbox::net::testing {
namespace LOCKBOX_TEST_FILE {

TEST(LockstepFigures, BandwidthPerPeer) {
    for (uint32_t loss : {0u, 100'000u}) {
        for (uint32_t rtt : {0u, 50u, 150u, 300u}) {
            MatchSpec s;
            s.seed = 900 + rtt + loss;
            s.clients = 4;
            s.rttMs = rtt;
            s.lossPpm = loss;
            s.frames = 1200;
            SCOPED_TRACE(s.Describe());
            Match m(s);
            ASSERT_TRUE(m.RunToFrame(120, 60'000));
            std::vector<TransportStats> c0;
            for (size_t i = 0; i < m.players(); ++i) c0.push_back(m.player(i).endpoint.Stats());
            const TransportStats s0 = m.net().Endpoint(0).Stats();
            const uint64_t t0 = m.net().NowMicros();
            const int32_t f0 = m.player(0).client->Frame();
            ASSERT_TRUE(m.RunToFrame(s.frames, 600'000));
            const uint64_t us = m.net().NowMicros() - t0;
            uint64_t up = 0, upMax = 0, dgrams = 0;
            for (size_t i = 0; i < m.players(); ++i) {
                const uint64_t b = m.player(i).endpoint.Stats().wireBytesSent - c0[i].wireBytesSent;
                up += b;
                upMax = std::max(upMax, b);
                dgrams += m.player(i).endpoint.Stats().datagramsSent - c0[i].datagramsSent;
            }
            const uint64_t down = m.net().Endpoint(0).Stats().wireBytesSent - s0.wireBytesSent;
            const double secs = static_cast<double>(us) / 1e6;
            std::printf(
                "[figures] 4 clients, rtt %3u ms, loss %2u %%: up %.1f kbit/s/peer (max %.1f), down %.1f kbit/s/peer, "
                "%.1f datagrams/s/peer up, %.1f frames/s, delay %u\n",
                rtt, loss / 10'000, up * 8 / secs / 1000 / 4, upMax * 8 / secs / 1000, down * 8 / secs / 1000 / 4,
                dgrams / secs / 4, (m.player(0).client->Frame() - f0) / secs, m.player(0).client->InputDelay());
        }
    }
}

TEST(LockstepFigures, DesyncDetectionTime) {
    for (uint32_t interval : {1u, 30u}) {
        for (uint32_t rtt : {50u, 150u}) {
            MatchSpec s;
            s.seed = 950 + rtt + interval;
            s.clients = 4;
            s.rttMs = rtt;
            s.hashInterval = interval;
            s.frames = 400;
            SCOPED_TRACE(s.Describe());
            Match m(s);
            const int32_t kFrame = 200;
            m.player(2).nudge.nudgeFrame = kFrame;
            uint64_t steppedAt = 0;
            ASSERT_TRUE(m.RunUntil(
                [&] {
                    if (steppedAt == 0 && m.player(2).client->Frame() > kFrame) steppedAt = m.net().NowMicros();
                    return m.CountServerEvents(ServerEvent::Kind::e_desync) > 0;
                },
                60'000));
            int32_t frame = -1;
            for (const auto& e : m.serverEvents())
                if (e.kind == ServerEvent::Kind::e_desync) frame = e.frame;
            std::printf(
                "[figures] desync: interval %2u, rtt %3u ms: event %.0f ms after the divergent frame was stepped "
                "(named frame %d, diverged at %d)\n",
                interval, rtt, (m.net().NowMicros() - steppedAt) / 1000.0, frame, kFrame);
        }
    }
}

TEST(LockstepFigures, LateJoinTime) {
    for (bool authoritative : {false, true}) {
        for (uint32_t rtt : {50u, 150u}) {
            MatchSpec s;
            s.seed = 970 + rtt;
            s.clients = 3;
            s.extraSlots = 1;
            s.rttMs = rtt;
            s.hashInterval = 30;
            s.frames = 900;
            s.authoritative = authoritative;
            s.scene = "pyramid20";
            SCOPED_TRACE(s.Describe());
            Match m(s);
            ASSERT_TRUE(m.RunToFrame(600, 120'000));
            const uint64_t t0 = m.net().NowMicros();
            Player& joiner = m.AddPlayer();
            uint64_t loadedAt = 0;
            ASSERT_TRUE(m.RunUntil(
                [&] {
                    if (loadedAt == 0 && joiner.client->State() == ClientState::e_catchingUp)
                        loadedAt = m.net().NowMicros();
                    return joiner.client->State() == ClientState::e_running;
                },
                30'000));
            const uint64_t admittedAt = m.net().NowMicros();
            const size_t blob = LockstepClient::SnapshotBlob(m.player(0).game.world(), m.player(0).game).size();
            ASSERT_TRUE(m.RunToFrame(s.frames, 60'000));
            EXPECT_EQ(joiner.hashAtStop, m.player(0).hashAtStop);
            std::printf(
                "[figures] late join (%s, pyramid20, %zu-byte snapshot), rtt %3u ms: snapshot loaded after %.0f ms, "
                "admitted after %.0f ms\n",
                authoritative ? "authoritative" : "relay", blob, rtt, (loadedAt - t0) / 1000.0,
                (admittedAt - t0) / 1000.0);
        }
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::testing
