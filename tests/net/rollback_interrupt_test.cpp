// Interruptions (docs/rollback.md "Interruptions"): a player's link to the other player cut
// for 1 s or 3 s (interrupted, then resumed or disconnected), and a spectator's link to its
// host cut or its host leaving (interrupted, lost, resumed). Every SimNet run is bounded in
// ticks and prints its seed on failure.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "rollback_join_harness.h"

namespace lockbox::net::rbtest {
namespace LOCKBOX_TEST_FILE {

// A clean 50 ms RTT link (no loss, no jitter), so event times are exact.
JoinSpec QuietSpec(uint64_t seed, int32_t frames, int64_t joinTick) {
    JoinSpec spec;
    spec.seed = seed;
    spec.rttMs = 50;
    spec.lossPct = 0;
    spec.jitterMs = 0;
    spec.frames = frames;
    spec.joinTick = joinTick;
    return spec;
}

// Two players whose link is cut from 2 s to `cutToMicros`; no spectator.
JoinSpec CutSpec(uint64_t seed, uint64_t cutToMicros) {
    JoinSpec spec = QuietSpec(seed, 360, -1);
    spec.cutFromMicros = 2'000'000;
    spec.cutToMicros = cutToMicros;
    return spec;
}

// A peer's events after the start phase other than window stalls, in order.
std::vector<RollbackEvent::Kind> ConnectionEvents(const JoinResult& r, size_t peer) {
    std::vector<RollbackEvent::Kind> kinds;
    bool running = false;
    for (const RollbackEvent& e : r.peers[peer].events) {
        if (e.kind == RollbackEvent::Kind::e_running) {
            running = true;
            continue;
        }
        if (running && e.kind != RollbackEvent::Kind::e_waiting) kinds.push_back(e.kind);
    }
    EXPECT_TRUE(running) << "peer " << peer << " never ran";
    return kinds;
}

// A 1 s cut between the players: both raise interrupted, then resumed, nobody disconnects
// and the hashes still agree. A 3 s cut: interrupted, then disconnected.
TEST(RollbackInterrupt, ShortCutInterruptsThenResumes) {
    const JoinSpec spec = CutSpec(606, 3'000'000);
    SCOPED_TRACE(spec.Describe());
    const JoinResult r = RunJoin(spec);
    ASSERT_TRUE(r.finished) << "ticks=" << r.ticks;
    ExpectPlayersAgree(spec, r);
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(ConnectionEvents(r, i), (std::vector<RollbackEvent::Kind>{RollbackEvent::Kind::e_interrupted,
                                                                            RollbackEvent::Kind::e_resumed}))
            << "peer " << i;
        EXPECT_TRUE(r.peers[i].net->RemoteAlive(0));
        EXPECT_FALSE(r.peers[i].net->RemoteInterrupted(0));
    }
}

TEST(RollbackInterrupt, LongCutInterruptsThenDisconnects) {
    const JoinSpec spec = CutSpec(607, 5'000'000);
    SCOPED_TRACE(spec.Describe());
    const JoinResult r = RunJoin(spec);
    ASSERT_TRUE(r.finished) << "ticks=" << r.ticks;
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(ConnectionEvents(r, i), (std::vector<RollbackEvent::Kind>{RollbackEvent::Kind::e_interrupted,
                                                                            RollbackEvent::Kind::e_disconnected}))
            << "peer " << i;
        EXPECT_FALSE(r.peers[i].net->RemoteAlive(0));
        EXPECT_FALSE(r.peers[i].executeFailed);
    }
}

// The spectator side of interruptions: a spectator from frame 0 whose host goes silent.
JoinSpec HostCutSpec(uint64_t seed, uint64_t cutToMicros) {
    JoinSpec spec = QuietSpec(seed, 600, 0);
    spec.lateJoin = false;
    spec.hostCutFromMicros = 3'000'000;
    spec.hostCutToMicros = cutToMicros;
    return spec;
}

std::vector<SpectatorEvent::Kind> SpectatorKinds(const JoinResult& r) {
    std::vector<SpectatorEvent::Kind> kinds;
    for (const auto& [tick, e] : r.spectatorEvents) kinds.push_back(e.kind);
    return kinds;
}

// Microseconds from the start of the host's silence to an event's tick.
uint64_t SinceCut(const JoinSpec& spec, int64_t tick) {
    return static_cast<uint64_t>(tick) * kTickMicros - spec.hostCutFromMicros;
}

TEST(SpectatorInterrupt, ShortSilenceInterruptsThenResumes) {
    using K = SpectatorEvent::Kind;
    const JoinSpec spec = HostCutSpec(701, 4'000'000);  // 1 s
    SCOPED_TRACE(spec.Describe());
    const JoinResult r = RunJoin(spec);
    ASSERT_TRUE(r.finished) << "ticks=" << r.ticks;
    ASSERT_EQ(SpectatorKinds(r), (std::vector<K>{K::e_interrupted, K::e_resumed}));
    // Reported after the 500 ms timeout (plus the last datagram's flight), and resumed once
    // the link is back.
    EXPECT_GT(SinceCut(spec, r.spectatorEvents[0].first), 500'000u);
    EXPECT_LT(SinceCut(spec, r.spectatorEvents[0].first), 600'000u);
    EXPECT_GE(SinceCut(spec, r.spectatorEvents[1].first), 1'000'000u);
    EXPECT_TRUE(r.hostAliveAtEnd);
    EXPECT_GT(ExpectSpectatorAgrees(r), 500u);  // it caught up on every frame of the silence
}

TEST(SpectatorInterrupt, LongSilenceLosesTheHostUntilItIsHeardAgain) {
    using K = SpectatorEvent::Kind;
    const JoinSpec spec = HostCutSpec(702, 6'000'000);  // 3 s, past the 2 s timeout
    SCOPED_TRACE(spec.Describe());
    const JoinResult r = RunJoin(spec);
    ASSERT_TRUE(r.finished) << "ticks=" << r.ticks;
    ASSERT_EQ(SpectatorKinds(r), (std::vector<K>{K::e_interrupted, K::e_hostLost, K::e_resumed}));
    EXPECT_GT(SinceCut(spec, r.spectatorEvents[1].first), 2'000'000u);
    EXPECT_TRUE(r.hostAliveAtEnd);
    EXPECT_GT(ExpectSpectatorAgrees(r), 500u);
}

TEST(SpectatorInterrupt, AHostThatLeavesIsLostAtOnce) {
    using K = SpectatorEvent::Kind;
    JoinSpec spec = HostCutSpec(703, 0);
    spec.hostLeaveTick = 240;
    SCOPED_TRACE(spec.Describe());
    const JoinResult r = RunJoin(spec);
    // The host's RbDisconnect arrives a one-way trip later: no 2 s wait, no resume after.
    ASSERT_EQ(SpectatorKinds(r), (std::vector<K>{K::e_hostLost}));
    EXPECT_LE(r.spectatorEvents[0].first, spec.hostLeaveTick + 3);
    EXPECT_FALSE(r.hostAliveAtEnd);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::rbtest
