// The start phase (docs/rollback.md, "The start phase"): peers started seconds apart, in any
// order, wait for a round trip with every remote before frame 0 and then play the same match;
// a peer that never appears is named when the start timeout expires, and nobody plays on
// against its zero inputs. SimNet, virtual time: every run is bounded in ticks.

#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "rollback_harness.h"

namespace lockbox::net::rbtest {
namespace LOCKBOX_TEST_FILE {

constexpr int64_t kTicksPerSecond = 60;

int Count(const RbPeer& p, RollbackEvent::Kind kind) {
    return static_cast<int>(
        std::count_if(p.events.begin(), p.events.end(), [kind](const RollbackEvent& e) { return e.kind == kind; }));
}

// Peers started at `startTicks`, 240 frames of vertical_stack over a 50 ms RTT link with
// jitter and loss.
RbSpec StaggeredSpec(uint64_t seed, std::vector<int64_t> startTicks) {
    RbSpec spec;
    spec.seed = seed;
    spec.peers = static_cast<uint32_t>(startTicks.size());
    spec.rttMs = 50;
    spec.jitterMs = 10;
    spec.lossPct = 5;
    spec.frames = 240;
    spec.startTicks = std::move(startTicks);
    // Time sync is judged once everyone plays.
    spec.steadyFromTick = *std::max_element(spec.startTicks.begin(), spec.startTicks.end()) + kTicksPerSecond;
    return spec;
}

void ExpectStartedTogether(const RbSpec& spec, const RbResult& r) {
    ExpectHealthy(spec, r);
    // The last compared frame every peer is sure to have made final before the run stopped.
    const int32_t last = (spec.frames / static_cast<int32_t>(spec.desyncInterval) - 1) * spec.desyncInterval;
    for (size_t i = 0; i < r.peers.size(); ++i) {
        const RbPeer& p = r.peers[i];
        SCOPED_TRACE(::testing::Message() << spec.Describe() << " peer " << i);
        ASSERT_NE(p.net, nullptr);
        EXPECT_EQ(p.net->State(), RollbackPeerState::e_running);
        EXPECT_EQ(Count(p, RollbackEvent::Kind::e_synchronized), static_cast<int>(spec.peers) - 1);
        EXPECT_EQ(Count(p, RollbackEvent::Kind::e_running), 1);
        EXPECT_EQ(Count(p, RollbackEvent::Kind::e_disconnected), 0);
        EXPECT_EQ(Count(p, RollbackEvent::Kind::e_startTimeout), 0);
        // The match's final hash at frame `last` is the same on every peer.
        ASSERT_TRUE(p.finals.count(last)) << "no final hash of frame " << last;
        EXPECT_EQ(p.finals.at(last), r.peers[0].finals.at(last));
        // Every frame of this peer's player is its own confirmed input: nothing was cut.
        EXPECT_FALSE(p.session->IsDisconnected(static_cast<uint32_t>((i + 1) % r.peers.size())));
    }
}

// Two peers 3 s apart, in either order, and a third 1 s after both.
TEST(RollbackStart, PeersStartedSecondsApartPlayTheSameMatch) {
    const int64_t s3 = 3 * kTicksPerSecond, s4 = 4 * kTicksPerSecond;
    const RbSpec firstThenSecond = StaggeredSpec(801, {0, s3, s4});
    const RbResult a = RunRbMatch(firstThenSecond);
    ExpectStartedTogether(firstThenSecond, a);
    const RbSpec secondThenFirst = StaggeredSpec(801, {s3, 0, s4});
    const RbResult b = RunRbMatch(secondThenFirst);
    ExpectStartedTogether(secondThenFirst, b);
    // Same seed, same scripted inputs per frame: whoever came first, it is the same match.
    const int32_t last = 230;
    EXPECT_EQ(a.peers[0].finals.at(last), b.peers[0].finals.at(last));
}

// The start phase changes nothing once the match runs: a match whose peers start 3 s apart
// ends in the same states as one whose peers start together.
TEST(RollbackStart, ALateStartDoesNotChangeTheMatch) {
    RbSpec together = StaggeredSpec(802, {0, 0});
    together.rttMs = 0;
    together.jitterMs = 0;
    together.lossPct = 0;
    RbSpec apart = together;
    apart.startTicks = {0, 3 * kTicksPerSecond};
    apart.steadyFromTick = 4 * kTicksPerSecond;
    const RbResult a = RunRbMatch(together);
    const RbResult b = RunRbMatch(apart);
    ExpectStartedTogether(together, a);
    ExpectStartedTogether(apart, b);
    for (const auto& [frame, hash] : a.peers[0].finals) {
        if (b.peers[0].finals.count(frame)) {
            EXPECT_EQ(b.peers[0].finals.at(frame), hash) << "frame " << frame;
        }
    }
}

// Peer 2 never appears: peers 0 and 1 synchronize with each other, wait, and at the start
// timeout name it (their remote index 1), leave and never advance.
TEST(RollbackStart, APeerThatNeverAppearsIsNamedAtTheStartTimeout) {
    RbSpec spec = StaggeredSpec(803, {0, 30, -1});
    spec.frames = 100;
    spec.startTimeoutMicros = 5'000'000;
    const RbResult r = RunRbMatch(spec);
    EXPECT_FALSE(r.finished);
    for (uint32_t i = 0; i < 2; ++i) {
        const RbPeer& p = r.peers[i];
        SCOPED_TRACE(::testing::Message() << "peer " << i);
        ASSERT_NE(p.net, nullptr);
        EXPECT_EQ(p.net->State(), RollbackPeerState::e_startFailed);
        EXPECT_TRUE(p.net->RemoteSynchronized(0));
        EXPECT_FALSE(p.net->RemoteSynchronized(1));
        EXPECT_EQ(Count(p, RollbackEvent::Kind::e_synchronized), 1);
        EXPECT_EQ(Count(p, RollbackEvent::Kind::e_running), 0);
        EXPECT_EQ(Count(p, RollbackEvent::Kind::e_disconnected), 0);
        ASSERT_EQ(Count(p, RollbackEvent::Kind::e_startTimeout), 1);
        for (const RollbackEvent& e : p.events) {
            if (e.kind == RollbackEvent::Kind::e_startTimeout) {
                EXPECT_EQ(e.player, 1u);  // the remote index of peer 2
            }
        }
        EXPECT_EQ(p.session->CurrentFrame(), 0);
        EXPECT_EQ(p.session->Stats().framesAdvanced, 0u);
    }
    EXPECT_EQ(r.peers[2].net, nullptr);
}

// A remote heard late is not timed out meanwhile: the 2 s disconnect timeout does not run
// before the match, so a remote that appears after 8 s (below the default 10 s start
// timeout) still plays.
TEST(RollbackStart, NoDisconnectTimerBeforeTheMatch) {
    RbSpec spec = StaggeredSpec(804, {8 * kTicksPerSecond, 0});
    spec.frames = 120;
    const RbResult r = RunRbMatch(spec);
    ExpectStartedTogether(spec, r);
    for (const RbPeer& p : r.peers) EXPECT_EQ(Count(p, RollbackEvent::Kind::e_interrupted), 0);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::rbtest
