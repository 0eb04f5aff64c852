// Spectators that join a rollback match late from a snapshot, refusal of bad snapshot chunk
// streams, and the interrupted / resumed events (issue 11, docs/rollback.md "Spectators" and
// "Interruptions"). Every SimNet run is bounded in ticks and prints its seed on failure.

#include <gtest/gtest.h>

#include <cstdint>
#include <algorithm>
#include <cstdio>
#include <string>
#include <sstream>
#include <map>
#include <memory>
#include <vector>

#include <xxhash.h>
#include <zstd.h>

#include "lockbox/lockbox.h"
#include "rollback_harness.h"

namespace lockbox::net::rbtest {
namespace {

struct JoinSpec {
    uint64_t seed = 1;
    uint32_t rttMs = 50;
    uint32_t lossPct = 5;
    uint32_t jitterMs = 30;
    int32_t frames = 480;        ///< frames every player confirms and the spectator simulates
    int64_t joinTick = 200;      ///< the spectator's first tick (-1: no spectator)
    bool lateJoin = true;        ///< false: the spectator is listed and starts at frame 0
    bool listed = true;          ///< false: the host admits it through maxLateSpectators
    uint64_t cutFromMicros = 0;  ///< both directions between the players drop in [from, to)
    uint64_t cutToMicros = 0;
    uint64_t hostCutFromMicros = 0;  ///< the host -> spectator direction drops in [from, to)
    uint64_t hostCutToMicros = 0;
    int64_t hostLeaveTick = -1;      ///< the host (player 0) calls Leave then and stops

    std::string Describe() const {
        std::ostringstream s;
        s << "seed=" << seed << " rtt=" << rttMs << "ms loss=" << lossPct << "% jitter=" << jitterMs
          << "ms join tick=" << joinTick << " late=" << lateJoin;
        return s.str();
    }
};

struct JoinResult {
    std::vector<RbPeer> peers;
    bool finished = false;
    int64_t ticks = 0;
    int32_t snapshotFrame = -1;
    uint64_t snapshotBytes = 0;
    uint64_t chunkDatagrams = 0;       ///< host chunk datagrams, resends included
    uint64_t joinMicros = 0;           ///< first join request to the checked snapshot
    /// First join request to the moment the spectator has stepped every frame the host had
    /// confirmed when the snapshot was handed out (the backlog of the transfer).
    uint64_t catchUpMicros = 0;
    bool restoreFailed = false;
    std::map<int32_t, uint64_t> spectatorHashes;  ///< every frame the spectator reached
    int32_t firstSpectatorFrame = -1;  ///< the first frame the spectator stepped
    uint64_t refusedSnapshots = 0;
    std::vector<std::pair<int64_t, SpectatorEvent>> spectatorEvents;  ///< (tick, event)
    bool hostAliveAtEnd = false;
};

JoinResult RunJoin(const JoinSpec& spec) {
    JoinResult out;
    SimNet net(spec.seed);
    LinkProfile link;
    link.latencyMicros = spec.rttMs * 500u;
    link.jitterMicros = spec.jitterMs * 1000u;
    link.lossPpm = spec.lossPct * 10000u;
    SimEndpoint* ends[2] = {&net.AddEndpoint(), &net.AddEndpoint()};
    SimEndpoint& specEnd = net.AddEndpoint();
    net.SetAllLinks(link);
    if (spec.cutToMicros > spec.cutFromMicros) {
        net.Blackout(0, 1, spec.cutFromMicros, spec.cutToMicros);
        net.Blackout(1, 0, spec.cutFromMicros, spec.cutToMicros);
    }
    if (spec.hostCutToMicros > spec.hostCutFromMicros)
        net.Blackout(0, specEnd.Index(), spec.hostCutFromMicros, spec.hostCutToMicros);
    out.peers.resize(2);
    for (uint32_t i = 0; i < 2; ++i) {
        RbPeer& p = out.peers[i];
        p.scene = std::make_unique<replay::SceneGame>("vertical_stack");
        p.game = std::make_unique<RbNudgeGame>(*p.scene);
        p.session = RollbackSessionBuilder()
                        .Players(2)
                        .InputBytes(replay::SceneInput::kBytes)
                        .LocalPlayer(i)
                        .InputDelay(1)
                        .DesyncInterval(1)
                        .Build();
        const auto& info = p.scene->info();
        p.adapter = std::make_unique<WorldGameAdapter>(
            p.scene->world(), *p.game,
            WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                              static_cast<uint32_t>(info.positionIterations)});
        RollbackPeerConfig cfg;
        cfg.matchId = 9;
        cfg.remotes.push_back(RollbackRemote{ends[1 - i]->Index(), {1 - i}});
        if (i == 0 && spec.joinTick >= 0) {
            if (spec.listed) cfg.spectators.push_back(specEnd.Index());
            else cfg.maxLateSpectators = 1;
        }
        p.net = std::make_unique<RollbackPeer>(*p.session, *ends[i], cfg);
        p.inputs = std::make_unique<replay::ScriptedInputs>(spec.seed * 1000 + i, 1);
    }
    replay::SceneGame specGame("vertical_stack");
    WorldGameAdapter specHash(specGame.world(), specGame, WorldStepSettings{});
    RollbackSpectatorConfig sc;
    sc.matchId = 9;
    sc.players = 2;
    sc.inputBytes = replay::SceneInput::kBytes;
    sc.host = ends[0]->Index();
    sc.lateJoin = spec.lateJoin;
    std::unique_ptr<RollbackSpectator> spectator;
    uint64_t joinStart = 0;
    int32_t specFrame = 0;  // the frame the spectator's world is at
    int32_t backlogEnd = 0;
    const auto& sinfo = specGame.info();
    std::vector<uint8_t> input, snapshot;
    const int64_t limit = int64_t{spec.frames} * 6 + 1200;
    for (int64_t tick = 0; tick < limit && !out.finished; ++tick) {
        bool done = true;
        for (uint32_t i = 0; i < 2; ++i) {
            RbPeer& p = out.peers[i];
            RollbackSession& s = *p.session;
            if (i == 0 && spec.hostLeaveTick >= 0 && tick >= spec.hostLeaveTick) {
                if (tick == spec.hostLeaveTick) p.net->Leave();
                continue;
            }
            p.net->Poll();
            if (!p.net->WaitThisTick()) {
                if (s.ReceivedFrame(i) <= s.CurrentFrame() + 1) {
                    p.inputs->Next(input);
                    s.AddLocalInput(i, input);
                }
                if (!p.adapter->Execute(s, s.AdvanceFrame())) p.executeFailed = true;
            }
            // The request-based host side: the game hands the bytes of its newest final frame.
            if (p.net->SnapshotWanted()) {
                int32_t f = 0;
                if (p.adapter->ConfirmedSnapshot(s, f, snapshot)) p.net->OfferSnapshot(f, snapshot);
            }
            p.net->Flush();
            for (const auto& [f, h] : s.FinalHashes()) {
                auto [it, fresh] = p.finals.emplace(f, h);
                if (!fresh && it->second != h) p.finalChanged = true;
            }
            for (const RollbackEvent& e : s.TakeEvents()) p.events.push_back(e);
            if (s.ConfirmedFrame() < spec.frames) done = false;
        }
        if (spec.joinTick >= 0 && tick == spec.joinTick) {
            spectator = std::make_unique<RollbackSpectator>(specEnd, sc);
            joinStart = net.NowMicros();
        }
        if (spectator) {
            spectator->Poll();
            int32_t f = 0;
            if (spectator->TakeSnapshot(f, snapshot)) {
                out.snapshotFrame = specFrame = f;
                out.snapshotBytes = snapshot.size();
                out.joinMicros = net.NowMicros() - joinStart;
                backlogEnd = out.peers[0].session->ConfirmedFrame();
                if (!WorldGameAdapter::RestoreSnapshot(specGame.world(), specGame, snapshot)) out.restoreFailed = true;
                out.spectatorHashes[f] = specHash.StateHash();
            }
            while (spectator->Next(f, input)) {
                if (f != specFrame) out.restoreFailed = true;  // frames must follow the snapshot
                if (out.firstSpectatorFrame < 0) out.firstSpectatorFrame = f;
                specGame.Apply(specGame.world(), f, input);
                specGame.world().Step(Fixed::FromRatio(1, sinfo.hz), sinfo.velocityIterations,
                                      sinfo.positionIterations);
                specFrame = f + 1;
                out.spectatorHashes[specFrame] = specHash.StateHash();
            }
            spectator->Flush();
            for (const SpectatorEvent& e : spectator->TakeEvents()) out.spectatorEvents.emplace_back(tick, e);
            out.hostAliveAtEnd = spectator->HostAlive();
            if (out.catchUpMicros == 0 && out.snapshotFrame >= 0 && specFrame >= backlogEnd)
                out.catchUpMicros = net.NowMicros() - joinStart;
            out.refusedSnapshots = spectator->SnapshotsRefused();
            if (specFrame < spec.frames) done = false;
        } else if (spec.joinTick >= 0) {
            done = false;
        }
        net.Advance(kTickMicros);
        out.ticks = tick + 1;
        out.finished = done;
    }
    out.chunkDatagrams = out.peers[0].net->Stats().snapshotChunksSent;
    return out;
}

// The spectator's state at every frame it reached equals the players' final state there.
size_t ExpectSpectatorAgrees(const JoinResult& r) {
    size_t common = 0;
    for (const auto& [f, h] : r.spectatorHashes) {
        for (const RbPeer& p : r.peers) {
            auto it = p.finals.find(f);
            if (it == p.finals.end()) continue;
            ++common;
            EXPECT_EQ(it->second, h) << "frame " << f;
        }
    }
    return common;
}

void ExpectPlayersAgree(const JoinSpec& spec, const JoinResult& r) {
    for (size_t i = 0; i < r.peers.size(); ++i) {
        EXPECT_FALSE(r.peers[i].executeFailed) << "peer " << i;
        EXPECT_FALSE(r.peers[i].finalChanged) << "peer " << i;
        for (const RollbackEvent& e : r.peers[i].events)
            EXPECT_NE(e.kind, RollbackEvent::Kind::e_desync) << "peer " << i << " desync at " << e.frame;
    }
    int32_t mismatch = -1;
    EXPECT_GE(CompareFinals(r.peers[0], r.peers[1], mismatch), static_cast<size_t>(spec.frames) * 8 / 10);
    EXPECT_EQ(mismatch, -1);
}

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
    std::printf("[ figures ] late join %s: snapshot frame %d, %llu bytes, %llu chunk datagrams, %llu ms to the "
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
    std::printf("[ figures ] late join %s: snapshot frame %d, %llu bytes, %llu chunk datagrams, %llu ms to the "
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

// A peer's events other than window stalls, in order.
std::vector<RollbackEvent::Kind> ConnectionEvents(const JoinResult& r, size_t peer) {
    std::vector<RollbackEvent::Kind> kinds;
    for (const RollbackEvent& e : r.peers[peer].events)
        if (e.kind != RollbackEvent::Kind::e_waiting) kinds.push_back(e.kind);
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

}  // namespace
}  // namespace lockbox::net::rbtest
