// Spectators that join a rollback match late from a snapshot, and refusal of bad snapshot
// chunk streams (docs/rollback.md "Spectators"). Every SimNet run is bounded in
// ticks and prints its seed on failure.

#include <xxhash.h>
#include <zstd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"
#include "rollback_join_harness.h"

namespace lockbox::net::rbtest {
namespace LOCKBOX_TEST_FILE {

class RollbackSpectatorSeeds : public ::testing::TestWithParam<uint64_t> {};

TEST_P(RollbackSpectatorSeeds, JoinsLateFromASnapshotOnALossyNet) {
    JoinSpec spec;
    spec.seed = GetParam();
    SCOPED_TRACE(spec.Describe());
    const JoinResult r = RunJoin(spec);
    ASSERT_TRUE(r.finished) << "ticks=" << r.ticks;
    ExpectPlayersAgree(spec, r);
    EXPECT_FALSE(r.restoreFailed);
    EXPECT_EQ(r.refusedSnapshots, 0u);
    // It joined at a confirmed frame near where the players were, not at frame 0.
    EXPECT_GE(r.snapshotFrame, 150);
    EXPECT_LE(r.snapshotFrame, 260);
    EXPECT_EQ(r.firstSpectatorFrame, r.snapshotFrame);
    const size_t common = ExpectSpectatorAgrees(r);
    EXPECT_GE(common, static_cast<size_t>(spec.frames - r.snapshotFrame));
    std::printf(
        "[ figures ] late join %s: snapshot frame %d, %llu bytes, %llu chunk datagrams, %llu ms to the "
        "snapshot, %llu ms to catch up, %zu hashes compared\n",
        spec.Describe().c_str(), r.snapshotFrame, static_cast<unsigned long long>(r.snapshotBytes),
        static_cast<unsigned long long>(r.chunkDatagrams), static_cast<unsigned long long>(r.joinMicros / 1000),
        static_cast<unsigned long long>(r.catchUpMicros / 1000), common);
}

INSTANTIATE_TEST_SUITE_P(Seeds, RollbackSpectatorSeeds, ::testing::Values(2024u, 11u, 12u));

// A stranger admitted through maxLateSpectators, on a worse net.
TEST(RollbackSpectator, UnlistedSpectatorJoinsThroughTheLateLimit) {
    JoinSpec spec;
    spec.seed = 77;
    spec.rttMs = 150;
    spec.lossPct = 20;
    spec.jitterMs = 0;
    spec.frames = 420;
    spec.joinTick = 230;
    spec.listed = false;
    SCOPED_TRACE(spec.Describe());
    const JoinResult r = RunJoin(spec);
    ASSERT_TRUE(r.finished) << "ticks=" << r.ticks;
    ExpectPlayersAgree(spec, r);
    EXPECT_FALSE(r.restoreFailed);
    EXPECT_GE(r.snapshotFrame, 150);
    EXPECT_EQ(r.peers[0].net->SpectatorCount(), 1u);
    EXPECT_GE(ExpectSpectatorAgrees(r), static_cast<size_t>(spec.frames - r.snapshotFrame));
    std::printf(
        "[ figures ] late join %s: snapshot frame %d, %llu bytes, %llu chunk datagrams, %llu ms to the "
        "snapshot, %llu ms to catch up\n",
        spec.Describe().c_str(), r.snapshotFrame, static_cast<unsigned long long>(r.snapshotBytes),
        static_cast<unsigned long long>(r.chunkDatagrams), static_cast<unsigned long long>(r.joinMicros / 1000),
        static_cast<unsigned long long>(r.catchUpMicros / 1000));
}

TEST(RollbackSpectator, SpectatorFromFrameZeroStillWorks) {
    JoinSpec spec;
    spec.seed = 31;
    spec.frames = 300;
    spec.joinTick = 0;
    spec.lateJoin = false;
    SCOPED_TRACE(spec.Describe());
    const JoinResult r = RunJoin(spec);
    ASSERT_TRUE(r.finished) << "ticks=" << r.ticks;
    ExpectPlayersAgree(spec, r);
    EXPECT_EQ(r.snapshotFrame, -1);
    EXPECT_EQ(r.firstSpectatorFrame, 0);
    EXPECT_EQ(r.chunkDatagrams, 0u);
    EXPECT_GE(ExpectSpectatorAgrees(r), static_cast<size_t>(spec.frames));
}

// A fake host on a SimNet feeds a late joiner hand-made chunk streams: a snapshot whose
// checksum does not match, a truncated stream, and malformed datagrams never reach the game;
// a good one after them does, byte for byte.
TEST(RollbackSpectator, BadSnapshotStreamsAreRefused) {
    const uint64_t seed = 5;
    SCOPED_TRACE("seed=5");
    SimNet net(seed);
    SimEndpoint& host = net.AddEndpoint();
    SimEndpoint& watcher = net.AddEndpoint();
    RollbackSpectatorConfig sc;
    sc.matchId = 3;
    sc.players = 2;
    sc.inputBytes = 8;
    sc.host = host.Index();
    sc.lateJoin = true;
    RollbackSpectator spectator(watcher, sc);
    const RollbackShape shape{2, 8};
    // The state (random bytes, so that its zstd frame also takes 3 chunks) and the frame the
    // chunks carry; the checksum is the state's.
    std::vector<uint8_t> blob(2500);
    uint64_t lcg = seed;
    for (uint8_t& b : blob) {
        lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
        b = static_cast<uint8_t>(lcg >> 56);
    }
    const uint64_t good = XXH3_64bits(blob.data(), blob.size());
    std::vector<uint8_t> wire(ZSTD_compressBound(blob.size()));
    wire.resize(ZSTD_compress(wire.data(), wire.size(), blob.data(), blob.size(), 1));
    ASSERT_GT(wire.size(), 2 * size_t{kRbSnapshotChunkBytes});
    ASSERT_LE(wire.size(), 3 * size_t{kRbSnapshotChunkBytes});
    RollbackDatagramWriter w;
    auto sendChunk = [&](int32_t frame, uint64_t checksum, uint32_t index, const std::vector<uint8_t>& data) {
        const size_t off = size_t{index} * kRbSnapshotChunkBytes;
        const size_t len = std::min<size_t>(kRbSnapshotChunkBytes, data.size() - off);
        RbSnapshotChunk c{frame, static_cast<uint32_t>(data.size()), checksum, index,
                          std::vector<uint8_t>(data.begin() + static_cast<std::ptrdiff_t>(off),
                                               data.begin() + static_cast<std::ptrdiff_t>(off + len))};
        w.Begin(RollbackHeader{kRollbackProtocolVersion, 3});
        ASSERT_TRUE(w.Add(c, shape));
        host.Send(watcher.Index(), w.Bytes());
    };
    // What the spectator asks for: its join attempt number.
    auto lastAttempt = [&]() {
        std::vector<Datagram> in;
        host.Poll(in);
        uint32_t attempt = 0;
        for (const Datagram& d : in) {
            RollbackHeader h;
            std::vector<RollbackMessage> msgs;
            if (DecodeRollbackDatagram(d.bytes, shape, h, msgs) != DecodeError::e_ok) continue;
            for (const auto& m : msgs)
                if (const auto* j = std::get_if<RbJoinRequest>(&m)) attempt = j->attempt;
        }
        return attempt;
    };
    auto step = [&]() {
        net.Advance(kTickMicros);
        spectator.Poll();
        spectator.Flush();
        net.Advance(kTickMicros);
    };
    int32_t frame = 0;
    std::vector<uint8_t> got, inputs;
    step();
    EXPECT_EQ(lastAttempt(), 1u);

    // 1. Every chunk, but the checksum is wrong: assembled, checked, dropped, asked again.
    for (uint32_t i = 0; i < 3; ++i) sendChunk(40, good ^ 1, i, wire);
    step();
    EXPECT_EQ(spectator.SnapshotsRefused(), 1u);
    EXPECT_FALSE(spectator.TakeSnapshot(frame, got));
    EXPECT_FALSE(spectator.Next(frame, inputs));
    EXPECT_EQ(spectator.State(), SpectatorState::e_joining);
    EXPECT_EQ(lastAttempt(), 2u);

    // 2. One flipped payload byte under the right checksum: refused the same way.
    std::vector<uint8_t> flipped = wire;
    flipped[1500] ^= 0x10;
    for (uint32_t i = 0; i < 3; ++i) sendChunk(41, good, i, flipped);
    step();
    EXPECT_EQ(spectator.SnapshotsRefused(), 2u);
    EXPECT_FALSE(spectator.TakeSnapshot(frame, got));

    // 3. A truncated stream (the last chunk never comes) and malformed datagrams: it waits.
    sendChunk(42, good, 0, wire);
    sendChunk(42, good, 1, wire);
    w.Begin(RollbackHeader{kRollbackProtocolVersion, 3});
    ASSERT_TRUE(w.Add(RbSnapshotChunk{42, static_cast<uint32_t>(wire.size()), good, 2,
                                      std::vector<uint8_t>(wire.begin() + 2048, wire.end())},
                      shape));
    std::vector<uint8_t> cut(w.Bytes().begin(), w.Bytes().end() - 10);  // payload cut short
    host.Send(watcher.Index(), cut);
    const uint64_t refusedBefore = spectator.Refused();
    for (int i = 0; i < 10; ++i) step();
    EXPECT_EQ(spectator.Refused(), refusedBefore + 1);
    EXPECT_EQ(spectator.State(), SpectatorState::e_joining);
    EXPECT_FALSE(spectator.TakeSnapshot(frame, got));
    EXPECT_EQ(spectator.SnapshotsRefused(), 2u);

    // 4. The missing chunk arrives: the snapshot is complete, checked and handed out once.
    sendChunk(42, good, 2, wire);
    step();
    ASSERT_TRUE(spectator.TakeSnapshot(frame, got));
    EXPECT_EQ(frame, 42);
    EXPECT_EQ(got, blob);
    EXPECT_FALSE(spectator.TakeSnapshot(frame, got));
    EXPECT_EQ(spectator.State(), SpectatorState::e_following);
    EXPECT_EQ(spectator.ConsumedFrame(), 42);
    // A resend after a lost ack is acked again (else the host would never start the stream).
    lastAttempt();
    sendChunk(42, good, 1, wire);
    step();
    {
        std::vector<Datagram> in;
        host.Poll(in);
        bool acked = false;
        for (const Datagram& d : in) {
            RollbackHeader h;
            std::vector<RollbackMessage> msgs;
            if (DecodeRollbackDatagram(d.bytes, shape, h, msgs) != DecodeError::e_ok) continue;
            for (const auto& m : msgs)
                if (const auto* a = std::get_if<RbSnapshotAck>(&m)) acked = acked || (a->frame == 42 && a->index == 1);
        }
        EXPECT_TRUE(acked);
    }
    // A snapshot that is not a WorldGameAdapter image is refused by the restore path.
    replay::SceneGame game("vertical_stack");
    EXPECT_FALSE(WorldGameAdapter::RestoreSnapshot(game.world(), game, got));
    EXPECT_FALSE(WorldGameAdapter::RestoreSnapshot(game.world(), game, std::vector<uint8_t>{1, 2}));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::rbtest
