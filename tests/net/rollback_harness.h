#pragma once
// A peer-to-peer rollback match on a SimNet for the rollback tests: N peers, each with its own
// replay::SceneGame world, RollbackSession, WorldGameAdapter and RollbackPeer, one local
// player each with seeded scripted inputs. The virtual clock moves one 60 Hz tick (16,666 us)
// per loop; every run is bounded in ticks.

#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ForwardingTransport.h"
#include "NudgeGame.h"
#include "lockbox/net/RelayServer.h"
#include "lockbox/net/RelayedTransport.h"
#include "lockbox/net/RollbackBudgetGuard.h"
#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackSpectator.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/SimNet.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net::rbtest {

inline constexpr uint64_t kTickMicros = 16666;

/// A peer leaving the match at `tick`: gracefully (RbDisconnect through RollbackPeer::Leave,
/// then it stops) or abruptly (its machine goes down: it stops sending and receiving).
struct RbExit {
    uint32_t peer = 0;
    int64_t tick = 0;
    bool graceful = false;
};

/// From `tick` on, peer `from` no longer reaches peer `to` (its sends to it vanish; the other
/// direction still works): a half-broken link, or a leaver whose last inputs reach some
/// survivors and not others.
struct RbLinkCut {
    uint32_t from = 0;
    uint32_t to = 0;
    int64_t tick = 0;
};

/// A Transport that forwards to another one, except sends to the peers in `blocked`.
class CutTransport : public ForwardingTransport {
public:
    using ForwardingTransport::ForwardingTransport;
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override {
        if (std::find(blocked.begin(), blocked.end(), peer) != blocked.end()) return true;  // lost on the way
        return ForwardingTransport::Send(peer, bytes, delivery);
    }
    std::vector<PeerId> blocked;
};

/// One cell of the impairment matrix, and the match settings.
struct RbSpec {
    uint64_t seed = 1;
    uint32_t peers = 2;
    uint32_t rttMs = 0;     ///< each direction gets rttMs / 2 of fixed latency
    uint32_t lossPct = 0;   ///< Bernoulli loss per direction
    uint32_t jitterMs = 0;  ///< extra one-way delay, uniform in [0, jitterMs]
    int32_t frames = 600;   ///< frames every peer must reach and confirm
    uint32_t inputDelay = 1;
    uint32_t window = 8;
    uint32_t desyncInterval = 10;
    uint32_t startSkewTicks = 2;  ///< peer i starts i * skew ticks late
    /// When not empty: peer i starts at startTicks[i] instead (-1: never). Until then its
    /// machine is down (datagrams to it vanish) and its RollbackPeer does not exist yet.
    std::vector<int64_t> startTicks;
    uint64_t startTimeoutMicros = RollbackPeerConfig{}.startTimeoutMicros;
    int32_t steadyFromTick = 240;  ///< frame-advantage samples from this tick on
    int32_t nudgePeer = -1;        ///< forced divergence: this peer's state moves at nudgeFrame
    int32_t nudgeFrame = -1;
    uint32_t fastPeerExtraEvery = 0;  ///< > 0: peer 0's clock is fast by one tick in this many
    bool spectator = false;           ///< a spectator endpoint watches through peer 0
    bool timeSync = true;             ///< false: WaitThisTick is ignored
    bool relayed = false;             ///< peers (and the spectator) reach each other through a RelayServer
    int32_t downPeer = -1;            ///< this peer's machine goes down at downAtTick
    int64_t downAtTick = -1;
    std::vector<RbExit> exits;        ///< peers leaving during the match
    std::vector<RbLinkCut> linkCuts;  ///< one-way link cuts
    std::string scene = "vertical_stack";
    /// > 0: every peer runs a RollbackBudgetGuard with this budget (settle and lowering
    /// periods from guardConfig), fed a synthetic cost of guardFrameMicros per frame a tick
    /// steps (the virtual clock has no real CPU time), and applies its delay.
    uint32_t guardBudgetMicros = 0;
    uint32_t guardFrameMicros = 1000;
    RollbackBudgetConfig guardConfig;
    /// (tick, RTT ms): from that tick on every link has this RTT (loss and jitter unchanged).
    std::vector<std::pair<int64_t, uint32_t>> rttChanges;

    /// True once peer `i` has left (downPeer or an exit) at `tick`.
    bool Gone(uint32_t i, int64_t tick) const {
        if (static_cast<int32_t>(i) == downPeer && tick >= downAtTick) return true;
        for (const RbExit& e : exits)
            if (e.peer == i && tick >= e.tick) return true;
        return false;
    }

    /// The tick peer `i` starts at (-1: never).
    int64_t StartTick(uint32_t i) const { return i < startTicks.size() ? startTicks[i] : int64_t{startSkewTicks} * i; }

    std::string Describe() const {
        std::ostringstream s;
        s << "seed=" << seed << " peers=" << peers << " rtt=" << rttMs << "ms loss=" << lossPct
          << "% jitter=" << jitterMs << "ms frames=" << frames << " delay=" << inputDelay
          << (relayed ? " relayed" : "");
        for (const RbExit& e : exits)
            s << " exit(" << e.peer << "@" << e.tick << (e.graceful ? ",leave" : ",down") << ")";
        for (const RbLinkCut& c : linkCuts) s << " cut(" << c.from << "->" << c.to << "@" << c.tick << ")";
        for (size_t i = 0; i < startTicks.size(); ++i) s << " start" << i << "@" << startTicks[i];
        return s.str();
    }
};

/// The budget guard's test link: `rttMs`, 30 ms jitter, 5 % loss, no input delay; with
/// `guarded`, a 4 ms budget on a synthetic cost of 1 ms per frame stepped.
inline RbSpec SlowLinkSpec(uint64_t seed, uint32_t peers, uint32_t rttMs, int32_t frames, bool guarded) {
    RbSpec spec;
    spec.seed = seed;
    spec.peers = peers;
    spec.rttMs = rttMs;
    spec.jitterMs = 30;
    spec.lossPct = 5;
    spec.frames = frames;
    spec.inputDelay = 0;
    if (guarded) {
        spec.guardBudgetMicros = 4000;
        spec.guardFrameMicros = 1000;
    }
    return spec;
}

/// The forced-divergence game shared with the lockstep tests (NudgeGame.h).
using RbNudgeGame = lockbox::net::test_games::NudgeGame;

struct RbPeer {
    std::unique_ptr<replay::SceneGame> scene;
    std::unique_ptr<RbNudgeGame> game;
    std::unique_ptr<RollbackSession> session;
    std::unique_ptr<WorldGameAdapter> adapter;
    std::unique_ptr<RollbackPeer> net;
    std::unique_ptr<replay::ScriptedInputs> inputs;
    std::map<int32_t, uint64_t> finals;  // frame -> final hash
    std::vector<RollbackEvent> events;
    bool executeFailed = false;
    bool finalChanged = false;               // a frame's final hash changed after it was final
    std::map<uint32_t, int64_t> frozenTick;  // player -> tick this peer froze it
    std::map<uint32_t, int64_t> cutTick;     // player -> tick this peer cut it
    std::vector<uint8_t> pending;            // the drawn local input not taken yet
    bool hasPending = false;
    std::vector<uint8_t> accepted;        // local inputs the session took, in order
    std::vector<uint8_t> confirmedLocal;  // the local player's confirmed inputs, frame 0 on
    std::unique_ptr<RollbackBudgetGuard> guard;
    std::vector<std::pair<int64_t, uint32_t>> rollbackCosts;  // (tick, guardFrameMicros per frame stepped)
    uint32_t maxDelay = 0;                                    // guard runs: the largest delay applied
};

struct RbResult {
    std::vector<RbPeer> peers;
    int64_t ticks = 0;
    bool finished = false;                        ///< every peer reached and confirmed `frames`
    std::vector<int32_t> spread;                  ///< per steady tick: max - min current frame
    std::map<int32_t, uint64_t> spectatorHashes;  ///< frame -> the spectator's state hash
    int32_t spectatorFrames = 0;
    std::vector<uint64_t> wireBytesSent;  ///< per peer, IPv4 + UDP headers included
    uint64_t relayForwarded = 0;          ///< datagrams the relay forwarded (relayed only)
    int32_t SpreadP95() const {
        if (spread.empty()) return 0;
        std::vector<int32_t> s = spread;
        std::sort(s.begin(), s.end());
        return s[(s.size() * 95 + 99) / 100 - 1];
    }
    uint64_t Rollbacks() const {
        uint64_t n = 0;
        for (const RbPeer& p : peers) n += p.session->Stats().rollbacks;
        return n;
    }
};

/// Plays one match; bounded to frames * 6 + 1200 ticks.
inline RbResult RunRbMatch(const RbSpec& spec) {
    RbResult out;
    SimNet net(spec.seed);
    LinkProfile link;
    link.latencyMicros = spec.rttMs * 500u;
    link.jitterMicros = spec.jitterMs * 1000u;
    link.lossPpm = spec.lossPct * 10000u;
    std::vector<SimEndpoint*> ends;
    for (uint32_t i = 0; i < spec.peers; ++i) ends.push_back(&net.AddEndpoint());
    SimEndpoint* specEnd = spec.spectator ? &net.AddEndpoint() : nullptr;
    net.SetAllLinks(link);
    // Relayed: every member (peers, then the spectator) holds one slot of a relay on its own
    // endpoint and addresses the others by slot; each link then has two hops.
    std::unique_ptr<RelayServer> relay;
    std::vector<std::unique_ptr<RelayedTransport>> viaRelay;
    if (spec.relayed) {
        SimEndpoint& relayEnd = net.AddEndpoint();
        const uint32_t slots = spec.peers + (specEnd != nullptr ? 1u : 0u);
        RelayServerConfig rc;
        rc.matchId = 77;
        for (uint32_t m = 0; m < slots; ++m) rc.tokens.push_back(spec.seed * 31 + m);
        relay = std::make_unique<RelayServer>(relayEnd, rc);
        for (uint32_t m = 0; m < slots; ++m) {
            SimEndpoint& end = m < spec.peers ? *ends[m] : *specEnd;
            viaRelay.push_back(std::make_unique<RelayedTransport>(
                end, RelayedTransportConfig{relayEnd.Index(), 77, m, slots, rc.tokens[m]}));
        }
    }
    // Member m's transport and the PeerId the others reach it by. Peers send through a
    // CutTransport so single links can be cut (linkCuts).
    auto rawLinkOf = [&](uint32_t m) -> Transport& {
        if (spec.relayed) return *viaRelay[m];
        return m < spec.peers ? static_cast<Transport&>(*ends[m]) : *specEnd;
    };
    std::vector<std::unique_ptr<CutTransport>> cuttable;
    for (uint32_t m = 0; m < spec.peers; ++m) cuttable.push_back(std::make_unique<CutTransport>(rawLinkOf(m)));
    auto linkOf = [&](uint32_t m) -> Transport& {
        return m < spec.peers ? static_cast<Transport&>(*cuttable[m]) : rawLinkOf(m);
    };
    auto addressOf = [&](uint32_t m) -> PeerId {
        if (spec.relayed) return m;
        return m < spec.peers ? ends[m]->Index() : specEnd->Index();
    };
    out.peers.resize(spec.peers);
    std::vector<RollbackPeerConfig> peerConfigs(spec.peers);
    std::unique_ptr<replay::SceneGame> specGame;
    std::unique_ptr<RollbackSpectator> spectator;
    if (specEnd != nullptr) {
        specGame = std::make_unique<replay::SceneGame>(spec.scene);
        RollbackSpectatorConfig sc;
        sc.matchId = 77;
        sc.players = spec.peers;
        sc.inputBytes = replay::SceneInput::kBytes;
        sc.host = addressOf(0);
        spectator = std::make_unique<RollbackSpectator>(linkOf(spec.peers), sc);
    }
    for (uint32_t i = 0; i < spec.peers; ++i) {
        RbPeer& p = out.peers[i];
        p.scene = std::make_unique<replay::SceneGame>(spec.scene);
        p.game = std::make_unique<RbNudgeGame>(*p.scene);
        if (static_cast<int32_t>(i) == spec.nudgePeer) p.game->nudgeFrame = spec.nudgeFrame;
        p.session = RollbackSessionBuilder()
                        .Players(spec.peers)
                        .InputBytes(replay::SceneInput::kBytes)
                        .LocalPlayer(i)
                        .PredictionWindow(spec.window)
                        .InputDelay(spec.inputDelay)
                        .DesyncInterval(spec.desyncInterval)
                        .Build();
        const auto& info = p.scene->info();
        p.adapter = std::make_unique<WorldGameAdapter>(
            p.scene->world(), *p.game,
            WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                              static_cast<uint32_t>(info.positionIterations)});
        RollbackPeerConfig& cfg = peerConfigs[i];
        cfg.matchId = 77;
        cfg.startTimeoutMicros = spec.startTimeoutMicros;
        for (uint32_t j = 0; j < spec.peers; ++j)
            if (j != i) cfg.remotes.push_back(RollbackRemote{addressOf(j), {j}});
        if (i == 0 && specEnd != nullptr) cfg.spectators.push_back(addressOf(spec.peers));
        // A peer that starts late is made when it starts (its start timeout runs from then).
        if (spec.StartTick(i) == 0) p.net = std::make_unique<RollbackPeer>(*p.session, linkOf(i), cfg);
        if (!spec.startTicks.empty() && spec.StartTick(i) != 0) ends[i]->SetDown(true);
        p.inputs = std::make_unique<replay::ScriptedInputs>(spec.seed * 1000 + i, 1);
        if (spec.guardBudgetMicros > 0) {
            RollbackBudgetConfig gc = spec.guardConfig;
            gc.budgetMicros = spec.guardBudgetMicros;
            p.guard = std::make_unique<RollbackBudgetGuard>(gc, spec.inputDelay);
            p.maxDelay = spec.inputDelay;
        }
    }
    const int64_t limit = int64_t{spec.frames} * 6 + 1200;
    std::vector<uint8_t> input;
    for (int64_t tick = 0; tick < limit; ++tick) {
        bool done = true;
        if (relay) relay->Poll();
        for (const auto& [at, rtt] : spec.rttChanges)
            if (at == tick) {
                link.latencyMicros = rtt * 500u;
                net.SetAllLinks(link);
            }
        for (const RbLinkCut& c : spec.linkCuts)
            if (c.tick == tick && c.from < spec.peers && c.to < spec.peers)
                cuttable[c.from]->blocked.push_back(addressOf(c.to));
        for (uint32_t i = 0; i < spec.peers; ++i) {
            RbPeer& p = out.peers[i];
            for (const RbExit& e : spec.exits)
                if (e.peer == i && e.tick == tick && e.graceful && p.net) p.net->Leave();
            if (spec.Gone(i, tick)) {
                ends[i]->SetDown(true);
                continue;
            }
            if (spec.StartTick(i) < 0 || tick < spec.StartTick(i)) {
                done = false;
                continue;
            }
            if (!p.net) {
                ends[i]->SetDown(false);
                p.net = std::make_unique<RollbackPeer>(*p.session, linkOf(i), peerConfigs[i]);
            }
            RollbackSession& s = *p.session;
            // Peer 0 with a fast clock runs one extra tick every fastPeerExtraEvery ticks.
            const int runs = (i == 0 && spec.fastPeerExtraEvery > 0 && tick % spec.fastPeerExtraEvery == 0) ? 2 : 1;
            for (int run = 0; run < runs; ++run) {
                p.net->Poll();
                const bool wait = p.net->WaitThisTick() && spec.timeSync;
                if (!wait) {
                    // A drawn input waits until the session takes it, so without a budget
                    // guard frame f always gets the f-th draw whatever the waits. Peers keep
                    // playing past `frames` until every peer has confirmed it.
                    if (!p.hasPending) {
                        p.inputs->Next(p.pending);
                        p.hasPending = true;
                    }
                    const InputResult added = s.AddLocalInput(i, p.pending);
                    if (added != InputResult::e_alreadyAdded) {
                        if (added == InputResult::e_ok)
                            p.accepted.insert(p.accepted.end(), p.pending.begin(), p.pending.end());
                        p.hasPending = false;
                    }
                    const uint64_t resimBefore = s.Stats().framesResimulated;
                    const auto reqs = s.AdvanceFrame();
                    if (!p.adapter->Execute(s, reqs)) p.executeFailed = true;
                    const auto depth = static_cast<uint32_t>(s.Stats().framesResimulated - resimBefore);
                    const uint32_t micros = (depth + 1) * spec.guardFrameMicros;
                    if (depth > 0) p.rollbackCosts.emplace_back(tick, micros);
                    if (p.guard) {
                        // The guard says what the others' delay should be (their inputs
                        // arriving late is what makes this peer roll back); each peer uses
                        // the largest delay asked of it.
                        if (p.guard->Record(depth, micros)) p.net->AskInputDelay(p.guard->Delay());
                        const uint32_t delay = std::max(spec.inputDelay, p.net->RemoteDelayWish());
                        if (delay != s.InputDelay()) s.SetInputDelay(delay);
                        p.maxDelay = std::max(p.maxDelay, delay);
                    }
                }
                p.net->Flush();
            }
            for (const auto& [f, h] : s.FinalHashes()) {
                auto [it, fresh] = p.finals.emplace(f, h);
                if (!fresh && it->second != h) p.finalChanged = true;
            }
            for (const RollbackEvent& e : s.TakeEvents()) p.events.push_back(e);
            const int32_t confirmedEnd = std::min(s.ConfirmedFrame(), s.ReceivedFrame(i));
            for (auto f = static_cast<int32_t>(p.confirmedLocal.size() / replay::SceneInput::kBytes); f < confirmedEnd;
                 ++f) {
                const auto in = s.ConfirmedInput(i, f);
                if (in.empty()) break;
                p.confirmedLocal.insert(p.confirmedLocal.end(), in.begin(), in.end());
            }
            for (uint32_t q = 0; q < spec.peers; ++q) {
                if (s.FrozenFrame(q) >= 0) p.frozenTick.emplace(q, tick);
                if (s.CutFrame(q) >= 0) p.cutTick.emplace(q, tick);
            }
            if (s.ConfirmedFrame() < spec.frames) done = false;
        }
        if (spectator) {
            spectator->Poll();
            int32_t f = 0;
            const auto& info = specGame->info();
            while (spectator->Next(f, input)) {
                specGame->Apply(specGame->world(), f, input);
                specGame->world().Step(Fixed::FromRatio(1, info.hz), info.velocityIterations, info.positionIterations);
                if ((f + 1) % static_cast<int32_t>(spec.desyncInterval) == 0) {
                    // The peers' hash: the world hash folded with the (empty) user state.
                    out.spectatorHashes[f + 1] = specGame->world().Hash();
                }
                out.spectatorFrames = f + 1;
            }
            spectator->Flush();
            if (out.spectatorFrames < spec.frames) done = false;
        }
        if (tick >= spec.steadyFromTick) {
            int32_t lo = INT32_MAX, hi = INT32_MIN;
            bool running = true;
            for (uint32_t i = 0; i < spec.peers; ++i) {
                if (static_cast<int32_t>(i) == spec.downPeer || spec.Gone(i, tick) || !out.peers[i].net) continue;
                const RbPeer& p = out.peers[i];
                lo = std::min(lo, p.session->CurrentFrame());
                hi = std::max(hi, p.session->CurrentFrame());
                if (p.session->CurrentFrame() >= spec.frames) running = false;
            }
            if (running) out.spread.push_back(hi - lo);
        }
        if (relay) {
            relay->Poll();  // forwards this tick's datagrams without a tick's wait
            out.relayForwarded = relay->Stats().forwarded;
        }
        net.Advance(kTickMicros);
        out.ticks = tick + 1;
        out.wireBytesSent.assign(spec.peers, 0);
        for (uint32_t i = 0; i < spec.peers; ++i) out.wireBytesSent[i] = ends[i]->Stats().wireBytesSent;
        if (done) {
            out.finished = true;
            break;
        }
    }
    return out;
}

/// Frames whose final hash two peers both know, and whether they all agree.
inline size_t CompareFinals(const RbPeer& a, const RbPeer& b, int32_t& firstMismatch) {
    size_t common = 0;
    firstMismatch = -1;
    for (const auto& [f, h] : a.finals) {
        auto it = b.finals.find(f);
        if (it == b.finals.end()) continue;
        ++common;
        if (it->second != h && firstMismatch < 0) firstMismatch = f;
    }
    return common;
}

/// Compares the spectator's hashes with peer 0's final hashes (failures name the frame and
/// `spec`); returns how many frames both know.
inline size_t CompareSpectator(const RbSpec& spec, const RbResult& r) {
    size_t common = 0;
    for (const auto& [f, h] : r.spectatorHashes) {
        auto it = r.peers[0].finals.find(f);
        if (it == r.peers[0].finals.end()) continue;
        ++common;
        EXPECT_EQ(it->second, h) << spec.Describe() << " frame " << f;
    }
    return common;
}

// What every match must satisfy; `spec` is printed with every failure (it holds the seed).
// Returns the fewest compared frames of any pair of peers (SIZE_MAX with one peer).
inline size_t ExpectHealthy(const RbSpec& spec, const RbResult& r) {
    size_t compared = SIZE_MAX;
    SCOPED_TRACE(spec.Describe());
    EXPECT_TRUE(r.finished) << "ticks=" << r.ticks;
    for (size_t i = 0; i < r.peers.size(); ++i) {
        const RbPeer& p = r.peers[i];
        EXPECT_FALSE(p.executeFailed) << "peer " << i;
        EXPECT_FALSE(p.finalChanged) << "peer " << i;
        for (const RollbackEvent& e : p.events)
            EXPECT_NE(e.kind, RollbackEvent::Kind::e_desync) << "peer " << i << " false desync at " << e.frame;
        for (size_t j = i + 1; j < r.peers.size(); ++j) {
            int32_t mismatch = -1;
            const size_t common = CompareFinals(p, r.peers[j], mismatch);
            EXPECT_EQ(mismatch, -1) << "peers " << i << "," << j;
            // Nearly every compared frame up to `frames` is known on both sides.
            EXPECT_GE(common, static_cast<size_t>(spec.frames / static_cast<int32_t>(spec.desyncInterval)) * 8 / 10)
                << "peers " << i << "," << j;
            compared = std::min(compared, common);
        }
    }
    // One-way latency above the input delay forces predictions, and some of them are wrong.
    if (spec.rttMs * 500u > spec.inputDelay * kTickMicros) {
        EXPECT_GT(r.Rollbacks(), 0u);
    }
    EXPECT_LE(r.SpreadP95(), 1);
    return compared;
}

/// Nothing peer `p`'s player meant is lost (what SetInputDelay promises): its confirmed input
/// stream, runs of equal inputs collapsed, is what the session took from it, runs collapsed;
/// only the unconfirmed tail may be missing.
inline void ExpectNoInputLost(const RbPeer& p) {
    const size_t bytes = replay::SceneInput::kBytes;
    auto collapsed = [&](const std::vector<uint8_t>& flat) {
        std::vector<std::vector<uint8_t>> out;
        for (size_t k = 0; k + bytes <= flat.size(); k += bytes) {
            std::vector<uint8_t> row(flat.begin() + static_cast<std::ptrdiff_t>(k),
                                     flat.begin() + static_cast<std::ptrdiff_t>(k + bytes));
            if (out.empty() || out.back() != row) out.push_back(std::move(row));
        }
        return out;
    };
    const auto confirmed = collapsed(p.confirmedLocal);
    const auto taken = collapsed(p.accepted);
    ASSERT_GE(taken.size(), confirmed.size());
    EXPECT_GE(confirmed.size() + 2, taken.size());
    EXPECT_TRUE(std::equal(confirmed.begin(), confirmed.end(), taken.begin()));
}

}  // namespace lockbox::net::rbtest
