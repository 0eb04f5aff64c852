#pragma once
// Two rollback peers over real UDP sockets on 127.0.0.1, the second started `delay` after the
// first (its port is closed until then, so the first one's datagrams vanish as they would to
// a machine not running yet). Shared by the fast test (a short delay) and the heavy one (3 s).

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net::rbtest {

struct UdpStartSide {
    std::unique_ptr<UdpTransport> transport;
    std::unique_ptr<replay::SceneGame> game;
    std::unique_ptr<RollbackSession> session;
    std::unique_ptr<WorldGameAdapter> adapter;
    std::unique_ptr<RollbackPeer> peer;
    std::unique_ptr<replay::ScriptedInputs> script;
    std::map<int32_t, uint64_t> finals;
    std::vector<RollbackEvent> events;
    bool failed = false;
};

struct UdpStartResult {
    bool done = false;
    UdpStartSide sides[2];
    double seconds = 0;  ///< wall time of the run, the delay included
};

/// Builds one side of a UDP match on `transport`: the vertical_stack game, its session for
/// slot `slot` of 2, the adapter with the scene's step settings, the peer (remote `other`,
/// match `matchId`) and the scripted inputs. `S` has the members of UdpStartSide it fills.
template <class S>
inline void BuildUdpSide(S& s, uint32_t slot, Transport& transport, PeerId other, uint32_t matchId) {
    s.game = std::make_unique<replay::SceneGame>("vertical_stack");
    s.session =
        RollbackSessionBuilder().Players(2).InputBytes(8).LocalPlayer(slot).InputDelay(1).DesyncInterval(5).Build();
    const auto& info = s.game->info();
    s.adapter = std::make_unique<WorldGameAdapter>(
        s.game->world(), *s.game,
        WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                          static_cast<uint32_t>(info.positionIterations)});
    RollbackPeerConfig cfg;
    cfg.matchId = matchId;
    cfg.remotes.push_back(RollbackRemote{other, {1 - slot}});
    s.peer = std::make_unique<RollbackPeer>(*s.session, transport, cfg);
    s.script = std::make_unique<replay::ScriptedInputs>(matchId * 1000 + slot, 1);
}

/// Side `lateSide` (0 or 1) starts `delay` after the other; both play to `frames` confirmed
/// frames. Bounded by the delay plus 20 wall seconds.
inline void RunUdpStaggered(UdpStartResult& out, uint32_t lateSide, std::chrono::milliseconds delay, int32_t frames) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    std::string error;
    uint16_t ports[2] = {};
    for (auto& side : out.sides) {
        side.transport = UdpTransport::Open("127.0.0.1", 0, &error);
        ASSERT_NE(side.transport, nullptr) << error;
    }
    for (uint32_t i = 0; i < 2; ++i) ports[i] = out.sides[i].transport->LocalPort();
    out.sides[lateSide].transport.reset();  // closed until the late side starts

    auto start = [&](uint32_t i) {
        UdpStartSide& s = out.sides[i];
        for (int attempt = 0; !s.transport && attempt < 100; ++attempt) {
            s.transport = UdpTransport::Open("127.0.0.1", ports[i], &error);
            if (!s.transport) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        ASSERT_NE(s.transport, nullptr) << error;
        const PeerId other = s.transport->AddPeer("127.0.0.1", ports[1 - i], &error);
        ASSERT_NE(other, kNoPeer) << error;
        BuildUdpSide(s, i, *s.transport, other, 32);
    };
    start(1 - lateSide);
    const auto deadline = t0 + delay + std::chrono::seconds(20);
    std::vector<uint8_t> input;
    while (!out.done && Clock::now() < deadline) {
        if (!out.sides[lateSide].peer && Clock::now() >= t0 + delay) start(lateSide);
        out.done = true;
        for (uint32_t i = 0; i < 2; ++i) {
            UdpStartSide& s = out.sides[i];
            if (!s.peer) {
                out.done = false;
                continue;
            }
            s.peer->Poll();
            if (s.session->ReceivedFrame(i) <= s.session->CurrentFrame() + 1) {
                s.script->Next(input);
                s.session->AddLocalInput(i, input);
            }
            if (!s.adapter->Execute(*s.session, s.session->AdvanceFrame())) s.failed = true;
            s.peer->Flush();
            for (const auto& [f, h] : s.session->FinalHashes()) s.finals[f] = h;
            for (const RollbackEvent& e : s.session->TakeEvents()) s.events.push_back(e);
            if (s.session->ConfirmedFrame() < frames || !s.finals.count(frames)) out.done = false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Both sides ran (one e_running each, nobody cut, timed out or desynced) and agree on every
/// final hash both know, `frames` included.
inline void ExpectUdpStartedTogether(const UdpStartResult& r, int32_t frames) {
    EXPECT_TRUE(r.done) << "after " << r.seconds << " s";
    for (uint32_t i = 0; i < 2; ++i) {
        const UdpStartSide& s = r.sides[i];
        SCOPED_TRACE(::testing::Message() << "side " << i);
        ASSERT_NE(s.peer, nullptr);
        EXPECT_EQ(s.peer->State(), RollbackPeerState::e_running);
        EXPECT_FALSE(s.failed);
        int running = 0;
        for (const RollbackEvent& e : s.events) {
            running += e.kind == RollbackEvent::Kind::e_running ? 1 : 0;
            EXPECT_NE(e.kind, RollbackEvent::Kind::e_desync);
            EXPECT_NE(e.kind, RollbackEvent::Kind::e_disconnected);
            EXPECT_NE(e.kind, RollbackEvent::Kind::e_startTimeout);
        }
        EXPECT_EQ(running, 1);
        EXPECT_TRUE(s.finals.count(frames)) << "no final hash of frame " << frames;
    }
    size_t common = 0;
    for (const auto& [f, h] : r.sides[0].finals) {
        auto it = r.sides[1].finals.find(f);
        if (it == r.sides[1].finals.end()) continue;
        ++common;
        EXPECT_EQ(it->second, h) << "frame " << f;
    }
    EXPECT_GE(common, 10u);
}

}  // namespace lockbox::net::rbtest
