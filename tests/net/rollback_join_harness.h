#pragma once
// The spectator test harness: two players of vertical_stack on SimNet, a host (player 0)
// feeding a spectator that joins late from a snapshot or follows from frame 0, with link
// cuts between the players or from the host to the spectator, and the host leaving.
// Shared by rollback_spectator_test.cpp and rollback_interrupt_test.cpp.

#include <cstdint>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"
#include "rollback_harness.h"

namespace lockbox::net::rbtest {

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
    int64_t hostLeaveTick = -1;  ///< the host (player 0) calls Leave then and stops

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
    uint64_t chunkDatagrams = 0;  ///< host chunk datagrams, resends included
    uint64_t joinMicros = 0;      ///< first join request to the checked snapshot
    /// First join request to the moment the spectator has stepped every frame the host had
    /// confirmed when the snapshot was handed out (the backlog of the transfer).
    uint64_t catchUpMicros = 0;
    bool restoreFailed = false;
    std::map<int32_t, uint64_t> spectatorHashes;  ///< every frame the spectator reached
    int32_t firstSpectatorFrame = -1;             ///< the first frame the spectator stepped
    uint64_t refusedSnapshots = 0;
    std::vector<std::pair<int64_t, SpectatorEvent>> spectatorEvents;  ///< (tick, event)
    bool hostAliveAtEnd = false;
};

inline JoinResult RunJoin(const JoinSpec& spec) {
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
            if (spec.listed)
                cfg.spectators.push_back(specEnd.Index());
            else
                cfg.maxLateSpectators = 1;
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
        // A host that left never finishes the match: 3 s past it is all a test looks at.
        if (spec.hostLeaveTick >= 0 && tick > spec.hostLeaveTick + 180) break;
    }
    out.chunkDatagrams = out.peers[0].net->Stats().snapshotChunksSent;
    return out;
}

// The spectator's state at every frame it reached equals the players' final state there.
inline size_t ExpectSpectatorAgrees(const JoinResult& r) {
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

inline void ExpectPlayersAgree(const JoinSpec& spec, const JoinResult& r) {
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

}  // namespace lockbox::net::rbtest
