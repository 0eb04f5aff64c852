// lockbox_server_load: drives matches against a running lockbox_server from another process,
// for the load, soak and flood figures of docs/deploy.md.
//
// Lockstep (--kind lockstep): each client has its own UDP socket and token; without --scene it
// plays a one-body world that every input pushes (the state hash depends on every input at
// almost no simulation cost, so the server's relay work is what is measured); with --scene it
// plays that library scene (an authoritative server simulates the same one). Rollback (--kind
// rollback): each client is a RollbackPeer through the server's relay playing --scene (default
// vertical_stack) at its tick rate, optionally with spectators taking the spectator slots in
// turn (--spectators), and with loss and jitter on every client's receive side (--loss,
// --jitter, LatencyTransport). With --light no client simulates a scene: each plays an empty
// world whose state is a checksum of the inputs it applied, so the load generator's own cost
// stays small while the server's work is unchanged (an authoritative server still steps its
// scene; lockstep clients then report no hashes, as theirs would never match the server's).
// Clients are split over --threads threads by match. --flood adds
// a thread sending junk, copied, forged, expired and reused-token datagrams from many source
// ports. At the end it reports whether every match's clients (and every spectator) agree.

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/net/LatencyTransport.h"
#include "lockbox/net/LockstepClient.h"
#include "lockbox/net/RelayWire.h"
#include "lockbox/net/RelayedTransport.h"
#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackSpectator.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/StateHash.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/net/admission/AdmissionTransport.h"
#include "lockbox/replay/Game.h"
#include "lockbox/replay/SceneGame.h"
#include "lockbox_admission/TokenAuthority.h"
#include "lockbox_cli/OptionReader.h"

namespace {

using namespace lockbox;
using Clock = std::chrono::steady_clock;

constexpr const char* kUsage =
    "usage: lockbox_server_load --port N --key-file FILE [options]\n"
    "  --host HOST         the server's numeric address (default 127.0.0.1)\n"
    "  --port N            the server's UDP port (required)\n"
    "  --key-file FILE     the server's token key (required)\n"
    "  --kind KIND         lockstep or rollback (must match the server's --match-kind; default\n"
    "                      lockstep)\n"
    "  --scene NAME        the library scene the clients play (lockstep default: a one-body\n"
    "                      world; rollback default: vertical_stack; 8 input bytes either way)\n"
    "  --matches M         matches to play, 1 .. 10000 (default 10)\n"
    "  --players P         clients per match, 1 .. 64 (must match the server's; default 4)\n"
    "  --first-match ID    id of the first match (default 1)\n"
    "  --seconds S         how long to play, 1 .. 3600 (default 10)\n"
    "  --threads T         client threads, 1 .. 64 (default 1)\n"
    "  --spectators N      rollback: spectator slots per match (the server's\n"
    "                      --spectators-per-match); each is taken in turn by spectators that\n"
    "                      watch 3 .. 6 s and leave (default 0)\n"
    "  --loss PERMILLE     rollback: datagrams every client loses on receipt, 0 .. 500 (default 0)\n"
    "  --jitter MS         rollback: extra receive delay, uniform in 0 .. MS, 0 .. 500 (default 0)\n"
    "  --flood N           datagrams a second of junk, copied, forged, expired and reused tokens\n"
    "                      sent to the server while the matches play (from 2 s on; against\n"
    "                      127.0.0.1 from 127.0.0.2 .. 127.0.0.9), 0 .. 1000000 (default 0)\n"
    "  --flood-ports N     source ports of the flood, 1 .. 1024 (default 64)\n"
    "  --light             clients simulate no scene: an empty world whose state is a checksum\n"
    "                      of the inputs applied (a match's clients still compare it); lockstep\n"
    "                      clients send no hash reports, rollback peers compare theirs as usual.\n"
    "                      For capacity runs: the server's work is the same, the clients' is not\n"
    "  --stagger           start each match at its own phase within a 60 Hz frame, as matches\n"
    "                      that began independently would, rather than all in step\n"
    "  --input-delay N     lockstep: the clients' input delay in frames, 1 .. 255; 0: from the\n"
    "                      RTT; -1: the server's (default -1)\n"
    "  --steady-world      rollback: half of the scripted spawns become destroys, so the world\n"
    "                      keeps a handful of spawned bodies instead of gaining about 4 a second\n";

struct Options {
    std::string host = "127.0.0.1", keyFile, kind = "lockstep", scene;
    uint16_t port = 0;
    uint32_t matches = 10, players = 4, firstMatch = 1, seconds = 10, threads = 1, spectators = 0;
    uint32_t lossPermille = 0, jitterMs = 0, flood = 0, floodPorts = 64;
    bool light = false, stagger = false, steadyWorld = false;
    int32_t inputDelay = -1;
};

uint64_t UnixNow() {
    return static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count());
}

// One body pushed by every player's input byte.
class PushGame : public replay::Game {
public:
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        (void)frame;
        b2Body* body = world.GetBodyList();
        if (body == nullptr) return;
        int32 push = 0;
        for (uint8 b : inputs) push += b & 3;
        body->ApplyLinearImpulse(b2Vec2(Fixed(push - 3), Fixed(0)), body->GetWorldCenter());
    }
};

// A light client's game (--light): no bodies; its state is a running checksum of every input
// it applied with its frame, saved and loaded with the world, so the clients of a match that
// applied the same inputs to the same states hash alike, and a rollback restores it.
class InputChecksum : public replay::Game {
public:
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        (void)world;
        m_sum = (m_sum ^ static_cast<uint32_t>(frame)) * 0x100000001b3ull;
        for (uint8 b : inputs) m_sum = (m_sum ^ b) * 0x100000001b3ull;
    }
    void SaveUserState(std::vector<uint8>& out) const override {
        out.resize(8);
        for (size_t i = 0; i < 8; ++i) out[i] = static_cast<uint8>(m_sum >> (8 * i));
    }
    void LoadUserState(std::span<const uint8> in) override {
        if (in.size() != 8) return;
        m_sum = 0;
        for (size_t i = 0; i < 8; ++i) m_sum |= uint64_t{in[i]} << (8 * i);
    }

private:
    uint64_t m_sum = 0xcbf29ce484222325ull;
};

// What a rollback peer or spectator simulates: the library scene, or with --light an empty
// world and an InputChecksum stepped at 60 Hz.
struct ClientWorld {
    std::unique_ptr<replay::SceneGame> scene;
    std::unique_ptr<b2World> empty;
    InputChecksum checksum;

    ClientWorld(const Options& o, const std::string& defaultScene) {
        if (o.light)
            empty = std::make_unique<b2World>(b2Vec2(Fixed(0), Fixed(0)));
        else
            scene = std::make_unique<replay::SceneGame>(o.scene.empty() ? defaultScene : o.scene);
    }
    b2World& world() { return scene ? scene->world() : *empty; }
    replay::Game& game() { return scene ? static_cast<replay::Game&>(*scene) : checksum; }
    WorldStepSettings step() const {
        if (!scene) return {};
        const auto& info = scene->info();
        return {static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                static_cast<uint32_t>(info.positionIterations)};
    }
};

// What every client needs to reach the server: its socket and its token's envelope.
struct Link {
    std::unique_ptr<net::UdpTransport> udp;
    std::unique_ptr<net::LatencyTransport> impaired;
    std::unique_ptr<net::admission::AdmissionTransport> admission;
    net::PeerId server = net::kNoPeer;

    bool Open(const Options& o, const admission::TokenSigner& signer, uint32_t match, uint32_t slot, uint64_t seed,
              bool impair) {
        std::string error;
        udp = net::UdpTransport::Open(o.host.find(':') == std::string::npos ? "0.0.0.0" : "::", 0, &error);
        if (!udp) {
            std::fprintf(stderr, "lockbox_server_load: %s\n", error.c_str());
            return false;
        }
        server = udp->AddPeer(o.host, o.port, &error);
        net::Transport* inner = udp.get();
        if (impair && (o.lossPermille != 0 || o.jitterMs != 0)) {
            net::LatencyProfile profile;
            profile.lossPermille = o.lossPermille;
            profile.jitterMicros = o.jitterMs * 1000;
            impaired = std::make_unique<net::LatencyTransport>(*udp, profile, seed);
            inner = impaired.get();
        }
        admission::AdmissionToken t;
        t.matchId = match;
        t.slot = static_cast<uint8_t>(slot);
        t.clientId = uint64_t{match} * 100 + slot;
        t.expiresAt = UnixNow() + 600;
        t.nonce = admission::NewNonce();
        admission = std::make_unique<net::admission::AdmissionTransport>(*inner, server, signer.Sign(t));
        return true;
    }
};

struct LockstepClient {
    Link link;
    std::unique_ptr<b2World> ownWorld;
    PushGame push;
    InputChecksum checksum;
    std::unique_ptr<replay::SceneGame> scene;
    std::unique_ptr<replay::ScriptedInputs> scripted;
    std::unique_ptr<net::LockstepClient> session;
    uint32_t counter = 0;
    Clock::duration startAfter{};  // --stagger: the match's phase
};

struct RollbackClient {
    Link link;
    std::unique_ptr<net::RelayedTransport> relayed;
    std::unique_ptr<ClientWorld> game;
    std::unique_ptr<net::WorldGameAdapter> adapter;
    std::unique_ptr<net::RollbackSession> session;
    std::unique_ptr<net::RollbackPeer> peer;
    std::unique_ptr<replay::ScriptedInputs> inputs;
    std::vector<uint8_t> pending, snapshot;
    uint32_t slot = 0;
    int64_t ticks = 0;
    Clock::duration startAfter{};  // --stagger: the match's phase
};

struct Spectator {
    Link link;
    std::unique_ptr<net::RelayedTransport> relayed;
    std::unique_ptr<ClientWorld> game;
    std::unique_ptr<net::RollbackSpectator> session;
    std::map<int32_t, uint64_t> hashes;
    int32_t frames = 0;
    Clock::time_point nextFlush;
};

// A spectator slot: spectators in turn, each watching a while, then a pause (the server frees
// the slot after 2 s of silence).
struct SpectatorSlot {
    uint32_t slot = 0;
    std::unique_ptr<Spectator> now;
    Clock::time_point leaveAt, nextAt;
    uint32_t sessions = 0;
};

struct Totals {
    uint32_t agreed = 0, disagreed = 0, notComparable = 0;
    int32_t minFrame = INT32_MAX, maxFrame = 0;
    uint32_t spectatorSessions = 0, spectatorsAgreed = 0, spectatorsDisagreed = 0, spectatorsUnchecked = 0;
    uint64_t rollbackFrames = 0;
};

class Worker {
public:
    Worker(const Options& o, const admission::TokenSigner& signer, std::vector<uint32_t> matches)
        : m_o(o), m_signer(signer), m_matches(std::move(matches)), m_rng(m_matches.empty() ? 1 : m_matches[0]) {}

    bool Open() {
        for (uint32_t m : m_matches)
            for (uint32_t s = 0; s < m_o.players; ++s)
                if (!(m_o.kind == "rollback" ? OpenRollback(m, s) : OpenLockstep(m, s))) return false;
        if (m_o.kind == "rollback")
            for (uint32_t m : m_matches)
                for (uint32_t k = 0; k < m_o.spectators; ++k) {
                    SpectatorSlot slot;
                    slot.slot = m_o.players + k;
                    slot.nextAt = Clock::now() + std::chrono::milliseconds(500 + 300 * k);
                    m_slots.push_back({m, std::move(slot)});
                }
        return true;
    }

    void Run(Clock::time_point end) {
        const auto start = Clock::now();
        std::vector<uint8_t> input(8);
        while (Clock::now() < end) {
            const auto elapsed = Clock::now() - start;
            for (auto& c : m_lockstep) {
                if (elapsed < c->startAfter) continue;
                c->session->Update();
                while (c->session->WantsInput()) {
                    if (c->scripted) {
                        c->scripted->Next(input);
                    } else {
                        c->counter = c->counter * 1664525u + 1013904223u;
                        for (size_t i = 0; i < input.size(); ++i)
                            input[i] = static_cast<uint8_t>(c->counter >> (i * 3));
                    }
                    if (!c->session->SubmitLocalInput(input)) break;
                }
            }
            for (auto& c : m_rollback)
                if (elapsed >= c->startAfter) StepRollback(*c, elapsed - c->startAfter, true);
            for (auto& [match, slot] : m_slots) StepSpectatorSlot(match, slot);
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        // No more inputs: what is confirmed reaches every client.
        const auto settle = Clock::now();
        while (Clock::now() - settle < std::chrono::seconds(3)) {
            for (auto& c : m_lockstep) c->session->Update();
            for (auto& c : m_rollback) StepRollback(*c, Clock::now() - start - c->startAfter, false);
            for (auto& [match, slot] : m_slots)
                if (slot.now) StepSpectator(*slot.now);
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    }

    void Report(Totals& t) {
        const uint32_t p = m_o.players;
        for (size_t m = 0; m < m_matches.size(); ++m) {
            if (m_o.kind == "rollback") {
                // Every pair of peers agrees on every final hash both hold.
                bool same = true, compared = false;
                std::map<int32_t, uint64_t> first;
                for (const auto& [f, h] : m_rollback[m * p]->session->FinalHashes()) first[f] = h;
                for (uint32_t s = 0; s < p; ++s) {
                    const auto& c = *m_rollback[m * p + s];
                    t.minFrame = std::min(t.minFrame, c.session->ConfirmedFrame());
                    t.maxFrame = std::max(t.maxFrame, c.session->ConfirmedFrame());
                    t.rollbackFrames += c.session->Stats().framesResimulated;
                    for (const auto& [f, h] : c.session->FinalHashes()) {
                        const auto it = first.find(f);
                        if (it == first.end()) continue;
                        compared = compared || s > 0;
                        same = same && it->second == h;
                    }
                    for (const auto& [f, h] : c.session->FinalHashes()) m_finals[m_matches[m]][f] = h;
                }
                if (!same)
                    ++t.disagreed;
                else if (!compared)
                    ++t.notComparable;
                else
                    ++t.agreed;
                continue;
            }
            bool sameFrame = true, sameHash = true;
            const auto& first = m_lockstep[m * p]->session;
            for (uint32_t s = 0; s < p; ++s) {
                const auto& c = m_lockstep[m * p + s]->session;
                t.minFrame = std::min(t.minFrame, c->Frame());
                t.maxFrame = std::max(t.maxFrame, c->Frame());
                sameFrame = sameFrame && c->Frame() == first->Frame();
                sameHash = sameHash && c->LastHash() == first->LastHash();
            }
            if (!sameFrame || first->Frame() <= 0)
                ++t.notComparable;
            else if (sameHash)
                ++t.agreed;
            else
                ++t.disagreed;
        }
        for (auto& [match, slot] : m_slots)
            if (slot.now) Retire(match, slot);
        t.spectatorSessions += m_spectatorSessions;
        t.spectatorsAgreed += m_spectatorsAgreed;
        t.spectatorsDisagreed += m_spectatorsDisagreed;
        t.spectatorsUnchecked += m_spectatorsUnchecked;
        for (auto& c : m_lockstep) c->session->Leave();
        for (auto& c : m_rollback) c->peer->Leave();
    }

private:
    // With --stagger a match starts at its own phase within one 60 Hz frame, as matches that
    // began independently would: the server then gets their frames spread over the frame
    // rather than all in the same few turns of its loop. Spread by a multiplicative hash.
    Clock::duration PhaseOf(uint32_t match) const {
        if (!m_o.stagger) return {};
        return std::chrono::microseconds(uint64_t{match} * 10'007 % 16'667);
    }

    bool OpenLockstep(uint32_t match, uint32_t slot) {
        auto c = std::make_unique<LockstepClient>();
        if (!c->link.Open(m_o, m_signer, match, slot, match * 131 + slot, false)) return false;
        b2World* world = nullptr;
        replay::Game* game = nullptr;
        net::ClientConfig config;
        config.inputDelay = m_o.inputDelay;
        if (m_o.light) {
            // No scene and no hash reports: an authoritative server's hash is of its scene.
            c->ownWorld = std::make_unique<b2World>(b2Vec2(Fixed(0), Fixed(0)));
            world = c->ownWorld.get();
            game = &c->checksum;
            config.reportHashes = false;
            if (!m_o.scene.empty())
                c->scripted = std::make_unique<replay::ScriptedInputs>(uint64_t{match} * 7919 + slot, 1);
        } else if (m_o.scene.empty()) {
            c->ownWorld = std::make_unique<b2World>(b2Vec2(Fixed(0), Fixed(0)));
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            b2CircleShape circle;
            circle.m_radius = Fixed(1);
            c->ownWorld->CreateBody(&bd)->CreateFixture(&circle, Fixed(1));
            world = c->ownWorld.get();
            game = &c->push;
        } else {
            c->scene = std::make_unique<replay::SceneGame>(m_o.scene);
            c->scripted = std::make_unique<replay::ScriptedInputs>(uint64_t{match} * 7919 + slot, 1);
            world = &c->scene->world();
            game = c->scene.get();
        }
        c->session = std::make_unique<net::LockstepClient>(*c->link.admission, c->link.server, config, *world, *game);
        c->counter = match * 7919 + slot * 104729;
        c->startAfter = PhaseOf(match);
        m_lockstep.push_back(std::move(c));
        return true;
    }

    bool OpenRollback(uint32_t match, uint32_t slot) {
        auto c = std::make_unique<RollbackClient>();
        if (!c->link.Open(m_o, m_signer, match, slot, match * 131 + slot, true)) return false;
        const uint32_t slots = m_o.players + m_o.spectators;
        c->relayed = std::make_unique<net::RelayedTransport>(
            *c->link.admission, net::RelayedTransportConfig{c->link.server, match, slot, slots, 0, 100000});
        c->game = std::make_unique<ClientWorld>(m_o, "vertical_stack");
        c->adapter = std::make_unique<net::WorldGameAdapter>(c->game->world(), c->game->game(), c->game->step());
        c->session = net::RollbackSessionBuilder()
                         .Players(m_o.players)
                         .InputBytes(replay::SceneInput::kBytes)
                         .LocalPlayer(slot)
                         .InputDelay(2)
                         .DesyncInterval(30)
                         .Build();
        net::RollbackPeerConfig cfg;
        cfg.matchId = match;
        for (uint32_t j = 0; j < m_o.players; ++j)
            if (j != slot) cfg.remotes.push_back(net::RollbackRemote{j, {j}});
        if (slot == 0) {
            cfg.maxLateSpectators = m_o.spectators;
            cfg.lateSpectatorTimeoutMicros = 1'000'000;
        }
        c->peer = std::make_unique<net::RollbackPeer>(*c->session, *c->relayed, cfg);
        c->inputs = std::make_unique<replay::ScriptedInputs>(uint64_t{match} * 1000 + slot, 1);
        c->slot = slot;
        c->startAfter = PhaseOf(match);
        m_rollback.push_back(std::move(c));
        return true;
    }

    // --steady-world: half of the script's spawns (those with an odd x) become destroys, so
    // the spawned bodies come and go instead of piling up. The script spawns on 1.2 % of a
    // player's frames and destroys on 0.4 %, so an 8-player match's world gains about 4
    // bodies a second, thousands over a 10-minute soak, which every peer, spectator and the
    // server's replay simulate; with 0.6 % spawns and 1.0 % destroys a handful stay.
    static void SteadyWorld(std::vector<uint8_t>& input) {
        replay::SceneInput in = replay::SceneInput::Decode(input.data());
        const bool spawn = in.action == replay::e_actSpawnBox || in.action == replay::e_actSpawnCircle;
        if (!spawn || (in.a & 1) == 0) return;
        in = replay::SceneInput{};
        in.action = replay::e_actDestroy;
        in.pick = static_cast<uint8_t>(input[2]);
        in.Encode(input.data());
    }

    // One tick of a rollback peer when its 60 Hz clock says so; otherwise only its socket.
    void StepRollback(RollbackClient& c, Clock::duration elapsed, bool play) {
        const int64_t due = std::chrono::duration_cast<std::chrono::microseconds>(elapsed).count() * 60 / 1'000'000;
        c.peer->Poll();
        if (c.ticks >= due) return;  // one datagram per remote per tick, as a game sends
        {
            ++c.ticks;
            if (!c.peer->WaitThisTick() || !play) {
                if (play) {
                    if (c.pending.empty()) {
                        c.inputs->Next(c.pending);
                        if (m_o.steadyWorld) SteadyWorld(c.pending);
                    }
                    if (c.session->AddLocalInput(c.slot, c.pending) != net::InputResult::e_alreadyAdded)
                        c.pending.clear();
                }
                if (play) (void)c.adapter->Execute(*c.session, c.session->AdvanceFrame());
                int32_t f = 0;
                if (c.peer->SnapshotWanted() && c.adapter->ConfirmedSnapshot(*c.session, f, c.snapshot))
                    (void)c.peer->OfferSnapshot(f, c.snapshot);
            }
        }
        c.peer->Flush();
    }

    void StepSpectator(Spectator& s) {
        s.session->Poll();
        int32_t f = 0;
        std::vector<uint8_t> bytes;
        if (s.session->TakeSnapshot(f, bytes) &&
            net::WorldGameAdapter::RestoreSnapshot(s.game->world(), s.game->game(), bytes))
            s.frames = f;
        while (s.session->Next(f, bytes)) {
            AdvanceWorldFrame(s.game->world(), s.game->game(), f, bytes, s.game->step());
            s.frames = f + 1;
            if (s.frames % 30 == 0) s.hashes[s.frames] = net::FoldedStateHash(s.game->world(), s.game->game());
        }
        // Acknowledgements at the game's tick rate, not at the loop's.
        if (Clock::now() < s.nextFlush) return;
        s.nextFlush = Clock::now() + std::chrono::microseconds(16'667);
        s.session->Flush();
    }

    void StepSpectatorSlot(uint32_t match, SpectatorSlot& slot) {
        const auto now = Clock::now();
        if (slot.now) {
            StepSpectator(*slot.now);
            if (now >= slot.leaveAt) {
                Retire(match, slot);
                slot.nextAt = now + std::chrono::milliseconds(200);  // asks while the slot is still held
            }
            return;
        }
        if (now < slot.nextAt) return;
        auto s = std::make_unique<Spectator>();
        if (!s->link.Open(m_o, m_signer, match, slot.slot, match * 977 + slot.sessions, true)) return;
        const uint32_t slots = m_o.players + m_o.spectators;
        s->relayed = std::make_unique<net::RelayedTransport>(
            *s->link.admission, net::RelayedTransportConfig{s->link.server, match, slot.slot, slots, 0, 100000});
        s->game = std::make_unique<ClientWorld>(m_o, "vertical_stack");
        net::RollbackSpectatorConfig sc;
        sc.matchId = match;
        sc.players = m_o.players;
        sc.inputBytes = replay::SceneInput::kBytes;
        sc.host = 0;
        sc.lateJoin = true;
        s->session = std::make_unique<net::RollbackSpectator>(*s->relayed, sc);
        slot.now = std::move(s);
        slot.leaveAt = now + std::chrono::milliseconds(3000 + m_rng() % 3000);
        ++slot.sessions;
        ++m_spectatorSessions;
    }

    // A spectator leaves: its hashes are checked against its match's peers' now.
    void Retire(uint32_t match, SpectatorSlot& slot) {
        Spectator& s = *slot.now;
        std::map<int32_t, uint64_t> peers;
        const uint32_t p = m_o.players;
        for (size_t m = 0; m < m_matches.size(); ++m)
            if (m_matches[m] == match)
                for (uint32_t i = 0; i < p; ++i)
                    for (const auto& [f, h] : m_rollback[m * p + i]->session->FinalHashes()) peers[f] = h;
        for (const auto& [f, h] : m_finals[match]) peers.emplace(f, h);
        bool same = true, compared = false;
        for (const auto& [f, h] : s.hashes) {
            const auto it = peers.find(f);
            if (it == peers.end()) continue;
            compared = true;
            same = same && it->second == h;
        }
        if (!same)
            ++m_spectatorsDisagreed;
        else if (compared)
            ++m_spectatorsAgreed;
        else
            ++m_spectatorsUnchecked;
        slot.now.reset();
    }

    const Options& m_o;
    const admission::TokenSigner& m_signer;
    std::vector<uint32_t> m_matches;
    std::mt19937 m_rng;
    std::vector<std::unique_ptr<LockstepClient>> m_lockstep;
    std::vector<std::unique_ptr<RollbackClient>> m_rollback;
    std::vector<std::pair<uint32_t, SpectatorSlot>> m_slots;
    std::map<uint32_t, std::map<int32_t, uint64_t>> m_finals;  // match -> the peers' final hashes seen
    uint32_t m_spectatorSessions = 0, m_spectatorsAgreed = 0, m_spectatorsDisagreed = 0, m_spectatorsUnchecked = 0;
};

// The flood: random junk, copies of one real client's first datagram (a reused token), forged
// and expired tokens, from `ports` source sockets, at `rate` datagrams a second.
struct FloodResult {
    uint64_t sent = 0;
    uint64_t answered = 0;  // datagrams the server sent to a flood socket: must stay 0
};

FloodResult Flood(const Options& o, const admission::TokenSigner& signer, Clock::time_point end) {
    std::vector<std::unique_ptr<net::UdpTransport>> sockets;
    std::vector<net::PeerId> server;
    std::string error;
    for (uint32_t i = 0; i < o.floodPorts; ++i) {
        // Against a server on 127.0.0.1 the flood comes from eight other loopback addresses,
        // so the per-address rate limit sees the flood apart from the clients.
        const std::string bind = o.host == "127.0.0.1"                   ? "127.0.0." + std::to_string(2 + i % 8)
                                 : o.host.find(':') == std::string::npos ? "0.0.0.0"
                                                                         : "::";
        auto udp = net::UdpTransport::Open(bind, 0, &error);
        if (!udp) break;
        server.push_back(udp->AddPeer(o.host, o.port, &error));
        sockets.push_back(std::move(udp));
    }
    if (sockets.empty()) return {};
    std::mt19937_64 rng(12345);
    const auto envelope = [](const admission::TokenBytes& token) {
        const uint8_t hello[8] = {1, 2, 3, 4, 5, 6, 7, 8};
        std::vector<uint8_t> out;
        net::admission::WriteEnvelope(out, token, hello);
        return out;
    };
    admission::AdmissionToken t;
    t.matchId = o.firstMatch + o.matches;  // a match nobody plays: the first copy creates it
    t.slot = 0;
    t.clientId = 99;
    t.expiresAt = UnixNow() + 600;
    t.nonce = 0xF100D;
    const std::vector<uint8_t> reused = envelope(signer.Sign(t));  // valid once, then a copy
    t.expiresAt = UnixNow() - 10;
    const std::vector<uint8_t> expired = envelope(signer.Sign(t));
    admission::TokenBytes forgedToken = signer.Sign(t);
    forgedToken[40] ^= 0x55;
    const std::vector<uint8_t> forged = envelope(forgedToken);
    std::vector<uint8_t> junk(96);
    uint64_t sent = 0;
    // The clients are admitted first (their address shares nothing with the flood's, but a
    // loaded machine admits them faster without it).
    std::this_thread::sleep_for(std::chrono::seconds(2));
    const auto start = Clock::now();
    std::vector<net::Datagram> sink;
    uint64_t answered = 0;
    while (Clock::now() < end) {
        const auto elapsed = std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count();
        const uint64_t due = static_cast<uint64_t>(elapsed) * o.flood / 1'000'000;
        while (sent < due) {
            const size_t i = sent % sockets.size();
            switch (sent % 4) {
                case 0:
                    for (auto& b : junk) b = static_cast<uint8_t>(rng());
                    sockets[i]->Send(server[i], junk);
                    break;
                case 1: sockets[i]->Send(server[i], reused); break;
                case 2: sockets[i]->Send(server[i], forged); break;
                default: sockets[i]->Send(server[i], expired); break;
            }
            ++sent;
        }
        for (auto& s : sockets) {
            sink.clear();
            s->Poll(sink);  // the server must answer none of it
            answered += sink.size();
        }
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    return {sent, answered};
}

}  // namespace

int main(int argc, char** argv) {
    cli::OptionReader args("lockbox_server_load", argc, argv);
    Options o;
    while (args.Next()) {
        if (args.Is("--host"))
            args.Text(o.host);
        else if (args.Is("--port"))
            args.Int(1, 65535, o.port);
        else if (args.Is("--key-file"))
            args.Text(o.keyFile);
        else if (args.Is("--kind"))
            args.Choice({"lockstep", "rollback"}, o.kind);
        else if (args.Is("--scene"))
            args.Text(o.scene);
        else if (args.Is("--matches"))
            args.Int(1, 10000, o.matches);
        else if (args.Is("--players"))
            args.Int(1, 64, o.players);
        else if (args.Is("--first-match"))
            args.Int(0, 4000000000LL, o.firstMatch);
        else if (args.Is("--seconds"))
            args.Int(1, 3600, o.seconds);
        else if (args.Is("--threads"))
            args.Int(1, 64, o.threads);
        else if (args.Is("--spectators"))
            args.Int(0, net::kRelayMaxSlots - 2, o.spectators);
        else if (args.Is("--loss"))
            args.Int(0, 500, o.lossPermille);
        else if (args.Is("--jitter"))
            args.Int(0, 500, o.jitterMs);
        else if (args.Is("--flood"))
            args.Int(0, 1000000, o.flood);
        else if (args.Is("--flood-ports"))
            args.Int(1, 1024, o.floodPorts);
        else if (args.Is("--light"))
            o.light = true;
        else if (args.Is("--stagger"))
            o.stagger = true;
        else if (args.Is("--steady-world"))
            o.steadyWorld = true;
        else if (args.Is("--input-delay"))
            args.Int(-1, 255, o.inputDelay);
        else
            args.Unknown();
    }
    if (!args.Failed() && (o.port == 0 || o.keyFile.empty())) args.Refuse("--port and --key-file are required");
    if (!args.Failed() && o.kind == "rollback" && (o.players < 2 || o.players + o.spectators > net::kRelayMaxSlots))
        args.Refuse("--kind rollback needs --players of at least 2 and at most 64 slots with --spectators");
    if (!args.Failed() && !o.scene.empty() && !replay::SceneGame(o.scene).ok())
        args.Refuse("--scene " + o.scene + " is not a library scene");
    if (args.Failed()) return args.Fail(kUsage);
    std::ifstream in(o.keyFile);
    std::stringstream text;
    text << in.rdbuf();
    const auto key = admission::ParseKeyHex(text.str());
    if (!key) {
        std::fprintf(stderr, "lockbox_server_load: %s does not hold a key\n", o.keyFile.c_str());
        return 2;
    }
    const admission::TokenSigner signer(*key);
    const uint32_t threads = std::min(o.threads, o.matches);
    std::vector<std::unique_ptr<Worker>> workers;
    for (uint32_t w = 0; w < threads; ++w) {
        std::vector<uint32_t> ids;
        for (uint32_t m = w; m < o.matches; m += threads) ids.push_back(o.firstMatch + m);
        workers.push_back(std::make_unique<Worker>(o, signer, std::move(ids)));
        if (!workers.back()->Open()) return 1;
    }
    const auto end = Clock::now() + std::chrono::seconds(o.seconds);
    std::vector<std::thread> running;
    for (auto& w : workers) running.emplace_back([&w, end] { w->Run(end); });
    FloodResult floodResult;
    std::thread flood;
    if (o.flood > 0) flood = std::thread([&] { floodResult = Flood(o, signer, end); });
    for (auto& t : running) t.join();
    if (flood.joinable()) flood.join();
    Totals t;
    for (auto& w : workers) w->Report(t);
    if (t.minFrame == INT32_MAX) t.minFrame = 0;
    std::printf(
        "{\"kind\":\"%s\",\"matches\":%u,\"players\":%u,\"seconds\":%u,\"threads\":%u,\"min_frame\":%d,"
        "\"max_frame\":%d,\"agreed\":%u,\"disagreed\":%u,\"not_comparable_or_not_started\":%u,"
        "\"frames_resimulated\":%llu,\"spectator_sessions\":%u,\"spectators_agreed\":%u,"
        "\"spectators_disagreed\":%u,\"spectators_unchecked\":%u,\"flood_sent\":%llu,\"flood_answered\":%llu}\n",
        o.kind.c_str(), o.matches, o.players, o.seconds, threads, t.minFrame, t.maxFrame, t.agreed, t.disagreed,
        t.notComparable, static_cast<unsigned long long>(t.rollbackFrames), t.spectatorSessions, t.spectatorsAgreed,
        t.spectatorsDisagreed, t.spectatorsUnchecked, static_cast<unsigned long long>(floodResult.sent),
        static_cast<unsigned long long>(floodResult.answered));
    return floodResult.answered == 0 && t.disagreed == 0 && t.spectatorsDisagreed == 0 && t.notComparable == 0 &&
                   t.minFrame > 0
               ? 0
               : 1;
}
