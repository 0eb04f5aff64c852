// Lockstep matches on SimNet: a representative subset of the impairment
// matrix (the whole matrix is in heavy/lockstep_matrix_test.cpp). Each cell asserts equal
// final hashes, a moving world, no desync and the upstream bandwidth budget.

#include <gtest/gtest.h>

#include "LockstepHarness.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"

namespace lockbox::net::testing {
namespace LOCKBOX_TEST_FILE {

MatchSpec Cell(uint64_t seed, uint32_t clients, uint32_t rtt, uint32_t lossPpm, bool bursts, uint32_t jitter) {
    MatchSpec s;
    s.seed = seed;
    s.clients = clients;
    s.rttMs = rtt;
    s.lossPpm = lossPpm;
    s.bursts = bursts;
    s.jitterMs = jitter;
    return s;
}

TEST(LockstepMatch, PerfectNetworkTwoClients) { RunMatrixCell(Cell(11, 2, 0, 0, false, 0)); }
TEST(LockstepMatch, Rtt50Loss5FourClients) { RunMatrixCell(Cell(12, 4, 50, 50'000, false, 0)); }
TEST(LockstepMatch, Rtt150Jitter30TwoClients) { RunMatrixCell(Cell(13, 2, 150, 0, false, 30)); }
TEST(LockstepMatch, Rtt150Loss20FourClients) { RunMatrixCell(Cell(14, 4, 150, 200'000, false, 0)); }
TEST(LockstepMatch, Rtt300BurstsEightClients) { RunMatrixCell(Cell(15, 8, 300, 0, true, 0)); }
TEST(LockstepMatch, Rtt300Loss5Jitter30EightClients) { RunMatrixCell(Cell(16, 8, 300, 50'000, false, 30)); }
TEST(LockstepMatch, Rtt0Loss20Jitter30EightClients) { RunMatrixCell(Cell(17, 8, 0, 200'000, false, 30)); }
TEST(LockstepMatch, Rtt50BurstsJitter30TwoClients) { RunMatrixCell(Cell(18, 2, 50, 0, true, 30)); }

TEST(LockstepMatch, AuthoritativeServerAgrees) {
    MatchSpec s = Cell(19, 3, 50, 50'000, false, 10);
    s.authoritative = true;
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(s.frames, 120'000));
    ASSERT_TRUE(m.RunUntil([&] { return m.server().SimulatedFrames() >= s.frames; }, 10'000));
    for (size_t i = 1; i < m.players(); ++i) EXPECT_EQ(m.player(i).hashAtStop, m.player(0).hashAtStop);
    EXPECT_EQ(m.CountServerEvents(ServerEvent::Kind::e_desync), 0u);
}

TEST(LockstepMatch, FixedDelayIsUsed) {
    MatchSpec s = Cell(20, 2, 50, 0, false, 0);
    s.serverDelay = 7;
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(100, 60'000));
    for (size_t i = 0; i < m.players(); ++i) EXPECT_EQ(m.player(i).client->InputDelay(), 7u);
}

TEST(LockstepMatch, AutomaticDelayFollowsRtt) {
    MatchSpec s = Cell(21, 2, 150, 0, false, 0);
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(30, 60'000));
    for (size_t i = 0; i < m.players(); ++i) {
        // 150 ms RTT at 60 Hz: ceil(150000 / 16666) + 1 = 10 frames with no jitter; the 1 ms
        // update period can add a millisecond or two to each sample, hence 11.
        EXPECT_GE(m.player(i).client->InputDelay(), 10u);
        EXPECT_LE(m.player(i).client->InputDelay(), 11u);
        EXPECT_GE(m.player(i).client->RttMicros(), 150'000u);
        EXPECT_LE(m.player(i).client->RttMicros(), 170'000u);
    }
}

// The confirmed-frame hook records a replay with Recorder::AppendConfirmed (what the demo
// does), and the replay verifies against a fresh world.
TEST(LockstepMatch, ConfirmedFramesRecordAVerifiableReplay) {
    MatchSpec s = Cell(22, 2, 50, 50'000, false, 10);
    SCOPED_TRACE(s.Describe());
    Match m(s);
    Player& p = m.player(0);
    replay::MemorySink sink;
    replay::RecorderConfig rc = p.game.Config(2);
    rc.keyframeInterval = 120;
    replay::Recorder recorder(p.game.world(), p.game, sink, rc);
    ASSERT_TRUE(recorder.Begin().ok());
    p.client->SetConfirmedFrameHook(
        [&](int32_t f, std::span<const uint8_t> inputs, uint64_t worldHash, const b2World& world) {
            EXPECT_EQ(f, recorder.Frames());
            recorder.AppendConfirmed(inputs, worldHash, &world);
        });
    ASSERT_TRUE(m.RunToFrame(s.frames, 60'000));
    ASSERT_TRUE(recorder.Finish().ok());
    replay::ReplayFile file;
    ASSERT_TRUE(replay::ParseReplay(sink.bytes(), file).ok());
    replay::SceneGame fresh(s.scene);
    replay::Player player(file, fresh.world(), fresh);
    const replay::VerifyResult v = player.Verify();
    EXPECT_TRUE(v.ok) << v.message;
    EXPECT_EQ(v.frames, recorder.Frames());
    EXPECT_EQ(v.finalHash, p.game.world().Hash());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::testing
