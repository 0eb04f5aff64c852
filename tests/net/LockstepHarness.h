#pragma once
// A lockstep match on a SimNet for the net tests: one server endpoint (index 0) and N client
// endpoints, each client with its own replay::SceneGame world and seeded scripted inputs. The
// virtual clock moves 1 ms per step; every run is bounded in virtual time.

#include <cstdint>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "NudgeGame.h"
#include "lockbox/net/LockstepClient.h"
#include "lockbox/net/LockstepServer.h"
#include "lockbox/net/SimNet.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net::testing {

using NudgeGame = lockbox::net::test_games::NudgeGame;

/// One cell of the impairment matrix, and the match settings.
struct MatchSpec {
    uint64_t seed = 1;
    uint32_t clients = 2;
    uint32_t rttMs = 0;     ///< round trip: each direction gets rttMs / 2 of fixed latency
    uint32_t lossPpm = 0;   ///< Bernoulli loss per direction
    bool bursts = false;    ///< Gilbert-Elliott bursts (enter 2 %, leave 25 %, 75 % loss inside)
    uint32_t jitterMs = 0;  ///< extra one-way delay, uniform in [0, jitterMs]
    int32_t frames = 300;   ///< frames every client must reach
    uint32_t hashInterval = 30;
    uint32_t serverDelay = 0;  ///< 0: automatic delay on every client
    bool authoritative = false;
    uint32_t extraSlots = 0;  ///< slots beyond `clients`, for late joiners (the match starts without them)
    std::string scene = "vertical_stack";

    std::string Describe() const {
        std::ostringstream s;
        s << "seed=" << seed << " clients=" << clients << " rtt=" << rttMs << "ms loss=" << lossPpm / 10000.0
          << "% bursts=" << bursts << " jitter=" << jitterMs << "ms frames=" << frames;
        return s.str();
    }
    LinkProfile Link() const {
        LinkProfile p;
        p.latencyMicros = rttMs * 500u;
        p.jitterMicros = jitterMs * 1000u;
        p.lossPpm = lossPpm;
        if (bursts) {
            p.burstEnterPpm = 20'000;
            p.burstLeavePpm = 250'000;
            p.burstLossPpm = 750'000;
        }
        return p;
    }
};

/// One client with its world, game and inputs.
struct Player {
    Player(SimNet& net, const MatchSpec& spec, uint32_t index, ClientConfig config)
        : endpoint(net.AddEndpoint()), game(spec.scene), nudge(game), inputs(spec.seed * 1000 + index, 1) {
        client = std::make_unique<LockstepClient>(endpoint, 0, config, game.world(), nudge);
        client->SetConfirmedFrameHook([this](int32_t f, std::span<const uint8_t>, uint64_t, const b2World&) {
            if (f == stopFrame - 1) hashAtStop = client->LastHash();
        });
    }
    SimEndpoint& endpoint;
    replay::SceneGame game;
    NudgeGame nudge;
    replay::ScriptedInputs inputs;
    std::unique_ptr<LockstepClient> client;
    std::vector<ClientEvent> events;
    int32_t stopFrame = 0;
    uint64_t hashAtStop = 0;
    bool paused = false;  ///< a test stops calling Update (a frozen process)
    std::vector<uint8_t> scratch;
};

/// The whole match.
class Match {
public:
    explicit Match(const MatchSpec& spec, ServerConfig serverConfig = {}, ClientConfig clientConfig = {})
        : m_spec(spec), m_net(spec.seed), m_serverEndpoint(m_net.AddEndpoint()) {
        m_net.SetAllLinks(spec.Link());
        serverConfig.playerCount = spec.clients + spec.extraSlots;
        serverConfig.startPlayers = spec.clients;
        serverConfig.hashInterval = spec.hashInterval;
        serverConfig.inputDelay = spec.serverDelay;
        serverConfig.tokenSeed = spec.seed;
        if (spec.authoritative) {
            m_authGame = std::make_unique<replay::SceneGame>(spec.scene);
            serverConfig.world = &m_authGame->world();
            serverConfig.game = m_authGame.get();
        }
        m_server = std::make_unique<LockstepServer>(m_serverEndpoint, serverConfig);
        m_clientConfig = clientConfig;
        for (uint32_t i = 0; i < spec.clients; ++i) AddPlayer();
    }

    /// A new client (a late joiner when the match runs).
    Player& AddPlayer(ClientConfig config) {
        m_players.push_back(std::make_unique<Player>(m_net, m_spec, static_cast<uint32_t>(m_players.size()), config));
        m_players.back()->stopFrame = m_spec.frames;
        return *m_players.back();
    }
    Player& AddPlayer() { return AddPlayer(m_clientConfig); }

    /// One millisecond: the clock moves, then the server and every client update.
    void Step() {
        m_net.Advance(1000);
        m_server->Update();
        for (auto& e : m_server->TakeEvents()) m_serverEvents.push_back(std::move(e));
        for (auto& p : m_players) {
            if (p->paused) continue;
            p->client->Update();
            while (p->client->WantsInput()) {
                p->inputs.Next(p->scratch);
                if (!p->client->SubmitLocalInput(p->scratch)) break;
            }
            for (auto& e : p->client->TakeEvents()) p->events.push_back(e);
        }
    }
    /// Steps until `done` is true or `maxMillis` virtual milliseconds pass; false on timeout.
    template <class Done>
    bool RunUntil(Done done, uint64_t maxMillis) {
        for (uint64_t i = 0; i < maxMillis; ++i) {
            if (done()) return true;
            Step();
        }
        return done();
    }
    /// Steps until every running client has stepped `frame` frames.
    bool RunToFrame(int32_t frame, uint64_t maxMillis) {
        return RunUntil(
            [&] {
                for (auto& p : m_players)
                    if (!p->paused && p->client->State() != ClientState::e_closed && p->client->Frame() < frame)
                        return false;
                return true;
            },
            maxMillis);
    }

    SimNet& net() { return m_net; }
    LockstepServer& server() { return *m_server; }
    Player& player(size_t i) { return *m_players[i]; }
    size_t players() const { return m_players.size(); }
    std::vector<ServerEvent>& serverEvents() { return m_serverEvents; }
    size_t CountServerEvents(ServerEvent::Kind kind) const {
        size_t n = 0;
        for (const auto& e : m_serverEvents) n += e.kind == kind ? 1u : 0u;
        return n;
    }
    replay::SceneGame* authGame() { return m_authGame.get(); }
    const MatchSpec& spec() const { return m_spec; }

private:
    MatchSpec m_spec;
    SimNet m_net;
    SimEndpoint& m_serverEndpoint;
    std::unique_ptr<replay::SceneGame> m_authGame;
    std::unique_ptr<LockstepServer> m_server;
    ClientConfig m_clientConfig;
    std::vector<std::unique_ptr<Player>> m_players;
    std::vector<ServerEvent> m_serverEvents;
};

/// Upstream budget per peer for a loss rate (docs/net.md "Measured figures"): 32 kbit/s at
/// no loss, scaled linearly to 2x at 10 % loss, and 3x (96 kbit/s) for 20 % and bursts.
inline uint64_t UpBudgetBitsPerSecond(const MatchSpec& s) {
    if (s.bursts || s.lossPpm > 100'000) return 96'000;
    return 32'000 + 32'000ull * s.lossPpm / 100'000;
}

/// Runs one matrix cell and checks it: every client reaches spec.frames with the same hash,
/// the world moved, no desync, and each client's upstream stays within budget.
inline void RunMatrixCell(const MatchSpec& spec) {
    SCOPED_TRACE(spec.Describe());
    Match m(spec);
    replay::SceneGame fresh(spec.scene);
    const uint64_t initial = LockstepClient::StateHash(fresh.world(), fresh);
    // Bandwidth is measured over the steady part: from frame 60 (handshake done) to the end.
    ASSERT_TRUE(m.RunToFrame(60, 60'000)) << "no progress to frame 60";
    std::vector<uint64_t> bytes0, time0;
    for (size_t i = 0; i < m.players(); ++i) bytes0.push_back(m.player(i).endpoint.Stats().wireBytesSent);
    const uint64_t t0 = m.net().NowMicros();
    ASSERT_TRUE(m.RunToFrame(spec.frames, 600'000)) << "match did not finish";
    const uint64_t seconds_us = m.net().NowMicros() - t0;
    const uint64_t want = m.player(0).hashAtStop;
    for (size_t i = 0; i < m.players(); ++i) {
        Player& p = m.player(i);
        EXPECT_EQ(p.hashAtStop, want) << "client " << i;
        EXPECT_NE(p.hashAtStop, 0u) << "client " << i;
        const uint64_t bits = (p.endpoint.Stats().wireBytesSent - bytes0[i]) * 8;
        const uint64_t bps = seconds_us == 0 ? 0 : bits * 1'000'000 / seconds_us;
        EXPECT_LE(bps, UpBudgetBitsPerSecond(spec)) << "client " << i << " upstream bits/s";
    }
    EXPECT_NE(want, initial) << "the world did not move";
    EXPECT_EQ(m.CountServerEvents(ServerEvent::Kind::e_desync), 0u);
    EXPECT_EQ(m.server().Stats().desyncFrames, 0u);
}

}  // namespace lockbox::net::testing
