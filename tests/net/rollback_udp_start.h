#pragma once
// Rollback peers over real UDP sockets on 127.0.0.1, each started at its own offset (its port
// is closed until then, so the others' datagrams vanish as they would to a machine not running
// yet). Shared by the fast test (two peers, a short delay) and the heavy one (two peers 3 s
// apart and a third 1 s later).

#include <algorithm>
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
    std::vector<UdpStartSide> sides;
    double seconds = 0;  ///< wall time of the run, the delays included
};

/// Builds one side of a UDP match on `transport`: the vertical_stack game, its session for
/// slot `slot` of `others.size() + 1` players, the adapter with the scene's step settings, the
/// peer (`others`: the PeerIds of the other slots in slot order; match `matchId`) and the
/// scripted inputs. `S` has the members of UdpStartSide it fills.
template <class S>
inline void BuildUdpSide(S& s, uint32_t slot, Transport& transport, const std::vector<PeerId>& others,
                         uint32_t matchId) {
    const uint32_t players = static_cast<uint32_t>(others.size()) + 1;
    s.game = std::make_unique<replay::SceneGame>("vertical_stack");
    s.session = RollbackSessionBuilder()
                    .Players(players)
                    .InputBytes(8)
                    .LocalPlayer(slot)
                    .InputDelay(1)
                    .DesyncInterval(5)
                    .Build();
    const auto& info = s.game->info();
    s.adapter = std::make_unique<WorldGameAdapter>(
        s.game->world(), *s.game,
        WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                          static_cast<uint32_t>(info.positionIterations)});
    RollbackPeerConfig cfg;
    cfg.matchId = matchId;
    for (uint32_t j = 0, k = 0; j < players; ++j)
        if (j != slot) cfg.remotes.push_back(RollbackRemote{others[k++], {j}});
    s.peer = std::make_unique<RollbackPeer>(*s.session, transport, cfg);
    s.script = std::make_unique<replay::ScriptedInputs>(matchId * 1000 + slot, 1);
}

/// Side i starts `startAfter[i]` after the run begins; all play to `frames` confirmed frames.
/// Bounded by the latest start plus 20 wall seconds.
inline void RunUdpStaggered(UdpStartResult& out, const std::vector<std::chrono::milliseconds>& startAfter,
                            int32_t frames) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const uint32_t n = static_cast<uint32_t>(startAfter.size());
    std::string error;
    std::vector<uint16_t> ports(n);
    out.sides.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        auto probe = UdpTransport::Open("127.0.0.1", 0, &error);
        ASSERT_NE(probe, nullptr) << error;
        ports[i] = probe->LocalPort();
        if (startAfter[i].count() == 0) out.sides[i].transport = std::move(probe);  // else closed until it starts
    }
    auto start = [&](uint32_t i) {
        UdpStartSide& s = out.sides[i];
        for (int attempt = 0; !s.transport && attempt < 100; ++attempt) {
            s.transport = UdpTransport::Open("127.0.0.1", ports[i], &error);
            if (!s.transport) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        ASSERT_NE(s.transport, nullptr) << error;
        std::vector<PeerId> others;
        for (uint32_t j = 0; j < n; ++j) {
            if (j == i) continue;
            others.push_back(s.transport->AddPeer("127.0.0.1", ports[j], &error));
            ASSERT_NE(others.back(), kNoPeer) << error;
        }
        BuildUdpSide(s, i, *s.transport, others, 32);
    };
    auto latest = std::chrono::milliseconds(0);
    for (const auto& d : startAfter) latest = std::max(latest, d);
    const auto deadline = t0 + latest + std::chrono::seconds(20);
    std::vector<uint8_t> input;
    while (!out.done && Clock::now() < deadline) {
        out.done = true;
        for (uint32_t i = 0; i < n; ++i) {
            UdpStartSide& s = out.sides[i];
            if (!s.peer && Clock::now() >= t0 + startAfter[i]) start(i);
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

/// Every side ran (one e_running each, nobody cut, timed out or desynced) and agrees with side
/// 0 on every final hash both know, `frames` included.
inline void ExpectUdpStartedTogether(const UdpStartResult& r, int32_t frames) {
    EXPECT_TRUE(r.done) << "after " << r.seconds << " s";
    ASSERT_FALSE(r.sides.empty());
    for (uint32_t i = 0; i < r.sides.size(); ++i) {
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
    for (uint32_t i = 1; i < r.sides.size(); ++i) {
        size_t common = 0;
        for (const auto& [f, h] : r.sides[0].finals) {
            auto it = r.sides[i].finals.find(f);
            if (it == r.sides[i].finals.end()) continue;
            ++common;
            EXPECT_EQ(it->second, h) << "side " << i << ", frame " << f;
        }
        EXPECT_GE(common, 10u) << "side " << i;
    }
}

}  // namespace lockbox::net::rbtest
