// The front door and the matches of lockbox_server (MatchHost.h).
#include "MatchHost.h"

#include <algorithm>
#include <chrono>

#include "lockbox/net/RelayServer.h"
#include "lockbox/net/RelayWire.h"
#include "lockbox/net/RollbackProtocol.h"
#include "lockbox/net/admission/AdmissionTransport.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::server {

using admission::Refusal;
using net::Datagram;
using net::PeerId;

const char* DropName(Drop drop) noexcept {
    switch (drop) {
        case Drop::e_rateLimited: return "rate_limited";
        case Drop::e_noToken: return "no_token";
        case Drop::e_serverFull: return "server_full";
        case Drop::e_draining: return "draining";
        case Drop::e_strayEnvelope: return "stray_envelope";
        case Drop::e_peerBandwidth: return "peer_bandwidth";
        case Drop::e_wrongSlot: return "wrong_slot";
        case Drop::e_slotTaken: return "slot_taken";
        case Drop::e_count: break;
    }
    return "unknown";
}

const char* MatchKindName(MatchKind kind) noexcept {
    switch (kind) {
        case MatchKind::e_lockstepRelay: return "lockstep-relay";
        case MatchKind::e_lockstepAuthoritative: return "lockstep-authoritative";
        case MatchKind::e_rollbackRelay: return "rollback-relay";
    }
    return "unknown";
}

namespace {

// Frames of rollback inputs the recorder keeps ahead of the first frame it still misses: the
// peers' prediction window is far smaller, and the bound keeps a peer from filling memory.
constexpr int32_t kRollbackRecordAhead = 1024;

constexpr size_t kUpdateSamples = 4096;
// Refusal lines per second in the log at most: a flood must not turn into a flood of lines
// (every refusal is still counted in the metrics).
constexpr uint32_t kRefusalLinesPerSecond = 20;

// The source address without its port ("127.0.0.1:4000" -> "127.0.0.1", "[::1]:4000" -> "[::1]").
std::string HostOf(const std::string& address) {
    const size_t colon = address.rfind(':');
    return colon == std::string::npos ? address : address.substr(0, colon);
}

// FNV-1a of the address: the presenter's name in the replay cache.
uint64_t AddressKey(const std::string& address) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (char c : address) h = (h ^ static_cast<uint8_t>(c)) * 0x100000001b3ull;
    return h;
}

const char* EventName(net::ServerEvent::Kind kind) {
    using K = net::ServerEvent::Kind;
    switch (kind) {
        case K::e_joined: return "joined";
        case K::e_started: return "started";
        case K::e_interrupted: return "interrupted";
        case K::e_resumed: return "resumed";
        case K::e_disconnected: return "disconnected";
        case K::e_admitted: return "late_join_admitted";
        case K::e_joinFailed: return "late_join_failed";
        case K::e_desync: return "desync";
        case K::e_spoofedInput: return "spoofed_input";
    }
    return "unknown";
}

}  // namespace

// One match's view of the socket: datagrams the front door routed to it, and sends that go
// through the front door's checks.
class MatchHost::MatchTransport final : public net::Transport {
public:
    MatchTransport(MatchHost& host, uint32_t matchId) : m_host(host), m_matchId(matchId) {}

    bool Send(PeerId peer, std::span<const uint8_t> bytes, net::Delivery) override {
        if (!m_host.SendFor(m_matchId, peer, bytes)) {
            ++m_stats.sendFailures;
            return false;
        }
        ++m_stats.datagramsSent;
        m_stats.payloadBytesSent += bytes.size();
        m_stats.wireBytesSent += bytes.size() + net::UdpTransport::kIpv4Overhead;
        return true;
    }
    size_t Poll(std::vector<Datagram>& out) override {
        const size_t n = m_inbox.size();
        for (Datagram& d : m_inbox) out.push_back(std::move(d));
        m_inbox.clear();
        return n;
    }
    uint64_t NowMicros() const override { return m_host.m_socket->NowMicros(); }
    const net::TransportStats& Stats() const noexcept override { return m_stats; }

    void Deliver(PeerId peer, std::span<const uint8_t> bytes) {
        ++m_stats.datagramsReceived;
        m_stats.payloadBytesReceived += bytes.size();
        m_inbox.push_back(Datagram{peer, std::vector<uint8_t>(bytes.begin(), bytes.end())});
    }

private:
    MatchHost& m_host;
    uint32_t m_matchId;
    std::vector<Datagram> m_inbox;
    net::TransportStats m_stats;
};

struct MatchHost::Match {
    uint32_t id = 0;
    uint64_t createdMicros = 0;
    std::map<PeerId, int32_t> admitted;  // peer -> the slot its token names
    std::unique_ptr<MatchTransport> transport;
    // Lockstep kinds: the session's server; authoritative: with the scene's world to simulate.
    std::unique_ptr<replay::SceneGame> authority;
    std::unique_ptr<net::LockstepServer> server;
    // Rollback relay: the relay, and the inputs each slot sent for frames not yet recorded.
    std::unique_ptr<net::RelayServer> relay;
    std::map<int32_t, std::vector<uint8_t>> pendingInputs;  // frame -> every slot's input
    std::map<int32_t, uint64_t> pendingSlots;               // frame -> bit mask of slots present
    std::vector<uint64_t> lastHeard;                        // slot -> when its holder last sent (0: never)
    std::vector<PeerId> holder;                             // slot -> the peer seated there (relay)
    uint32_t players = 0;
    std::vector<std::vector<net::RollbackMessage>> scratch;
    int32_t sharedFrames = 0;  // the rollback peers have all inputs before this frame
    // The replay: the scene's world stepped through every confirmed frame.
    std::unique_ptr<replay::SceneGame> game;
    std::unique_ptr<replay::FileSink> sink;
    std::unique_ptr<replay::Recorder> recorder;
    std::string replayPath;
    int32_t recorded = 0;

    ~Match() {
        // The server and relay talk through the transport: they go first.
        server.reset();
        relay.reset();
    }
    bool Started() const {
        if (server) return server->Started();
        return std::all_of(lastHeard.begin(), lastHeard.begin() + players, [](uint64_t t) { return t != 0; });
    }
    int32_t Frames() const { return server ? server->ConfirmedFrames() : sharedFrames; }
};

MatchHost::MatchHost(std::unique_ptr<net::UdpTransport> socket, HostConfig config, JsonLog& log)
    : m_socket(std::move(socket)),
      m_config(std::move(config)),
      m_log(log),
      m_verifier(m_config.key, m_config.replayCacheSize, m_config.tokenMaxLifetimeSeconds),
      m_limiter(m_config.rateLimitPerSecond, m_config.rateLimitBurst) {
    m_updateMicros.reserve(kUpdateSamples);
}

MatchHost::~MatchHost() = default;

uint64_t MatchHost::UnixNow() const {
    if (m_config.unixNow) return m_config.unixNow();
    return static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count());
}

void MatchHost::Update() {
    const auto start = std::chrono::steady_clock::now();
    const uint64_t now = m_socket->NowMicros();
    m_inbox.clear();
    m_socket->Poll(m_inbox);
    for (Datagram& d : m_inbox) {
        ++m_stats.datagramsIn;
        m_stats.bytesIn += d.bytes.size();
        Route(d);
    }
    for (PeerId peer : m_forget)
        if (m_peers.count(peer) == 0) m_socket->Disconnect(peer);
    m_forget.clear();
    std::vector<uint32_t> ids;
    for (auto& [id, match] : m_matches) ids.push_back(id);
    for (uint32_t id : ids) UpdateMatch(*m_matches.at(id), now);
    const auto spent = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start);
    const auto micros = static_cast<uint32_t>(std::min<int64_t>(spent.count(), 0xFFFFFFFF));
    if (m_updateMicros.size() < kUpdateSamples)
        m_updateMicros.push_back(micros);
    else
        m_updateMicros[m_updateNext] = micros;
    m_updateNext = (m_updateNext + 1) % kUpdateSamples;
}

void MatchHost::Route(Datagram& d) {
    const auto it = m_peers.find(d.peer);
    if (it == m_peers.end()) return Admit(d, m_socket->NowMicros());
    Peer& p = it->second;
    const auto match = m_matches.find(p.matchId);
    if (match == m_matches.end()) return;
    std::span<const uint8_t> payload = d.bytes;
    if (net::admission::LooksLikeEnvelope(payload)) {
        // The client's first datagrams are resent until the server answers: the same token
        // again is fine, any other is not.
        net::admission::Envelope env;
        if (!net::admission::ParseEnvelope(payload, env)) {
            ++m_stats.dropped[static_cast<size_t>(Drop::e_strayEnvelope)];
            return;
        }
        if (!std::equal(env.token.begin(), env.token.end(), p.token.begin(), p.token.end())) {
            if (!Rebind(d, env.token)) ++m_stats.dropped[static_cast<size_t>(Drop::e_strayEnvelope)];
            return;
        }
        payload = env.payload;
    } else {
        p.handshakeDone = true;
    }
    if (!WithinBandwidth(p, d.bytes.size(), m_socket->NowMicros())) {
        ++m_stats.dropped[static_cast<size_t>(Drop::e_peerBandwidth)];
        return;
    }
    if (!p.handshakeDone) p.bytesIn += d.bytes.size();
    Deliver(*match->second, d.peer, p, payload);
}

void MatchHost::Deliver(Match& m, PeerId peer, const Peer& p, std::span<const uint8_t> payload) {
    if (m.relay) {
        // The relay knows members by the slot they claim; the token decided which one.
        const auto frame = net::ParseRelayFrame(payload);
        const auto slot = static_cast<size_t>(p.slot);
        const uint64_t now = std::max<uint64_t>(1, m_socket->NowMicros());
        if (frame && frame->kind == net::RelayKind::e_join) {
            if (frame->slot != p.slot) {
                ++m_stats.dropped[static_cast<size_t>(Drop::e_wrongSlot)];
                return;
            }
            const PeerId old = m.holder[slot];
            if (old != peer && old != net::kNoPeer) {
                // Spectators take a slot in turn: the next is seated once the last fell silent
                // (its host forgets it by then, so the newcomer's join is a fresh one).
                if (now - std::min(now, m.lastHeard[slot]) < m_config.match.disconnectMicros) {
                    ++m_stats.dropped[static_cast<size_t>(Drop::e_slotTaken)];
                    return;
                }
                m.admitted.erase(old);
                m_peers.erase(old);
                m_socket->Disconnect(old);
            }
            m.holder[slot] = peer;
        }
        if (frame && m.holder[slot] == peer) {
            m.lastHeard[slot] = now;
            if (frame->kind == net::RelayKind::e_toSlot) RecordRollbackInputs(m, p.slot, frame->payload);
        }
    }
    m.transport->Deliver(peer, payload);
}

uint64_t MatchHost::BytesPerSecondOf(const Peer& p) const {
    // A budget per stream the client sends: a lockstep client sends to the server only; a
    // rollback peer sends to every other player through the relay, and slot 0 also to every
    // spectator slot (it hosts the spectators); a spectator answers its host only.
    const uint64_t perStream = m_config.peerBytesPerSecond;
    if (m_config.kind != MatchKind::e_rollbackRelay) return perStream;
    const uint32_t players = m_config.match.playerCount;
    if (p.slot < 0 || static_cast<uint32_t>(p.slot) >= players) return perStream;
    uint64_t streams = std::max<uint32_t>(players, 2) - 1;
    if (p.slot == 0 && m_config.spectatorsPerMatch > 0) {
        if (m_config.spectatorHostBytesPerSecond) return *m_config.spectatorHostBytesPerSecond;
        streams += m_config.spectatorsPerMatch;
    }
    return perStream * streams;
}

bool MatchHost::WithinBandwidth(Peer& p, size_t bytes, uint64_t nowMicros) const {
    const uint64_t rate = BytesPerSecondOf(p);
    if (rate == 0) return true;
    // Credit in byte-microseconds: one second's worth at most, refilled at `rate`.
    const uint64_t capacity = rate * 1'000'000;
    if (p.creditTime == 0) {
        p.credit = capacity;
    } else if (nowMicros > p.creditTime) {
        p.credit = std::min(capacity, p.credit + (nowMicros - p.creditTime) * rate);
    }
    p.creditTime = std::max<uint64_t>(1, nowMicros);
    const uint64_t cost = uint64_t{bytes} * 1'000'000;
    if (cost > p.credit) return false;
    p.credit -= cost;
    return true;
}

void MatchHost::RecordRollbackInputs(Match& m, int32_t slot, std::span<const uint8_t> payload) {
    if (!m.recorder) return;
    const net::RollbackShape shape{m_config.match.playerCount, m_config.match.inputBytes};
    net::RollbackHeader header;
    if (m.scratch.empty()) m.scratch.resize(1);
    std::vector<net::RollbackMessage>& messages = m.scratch.front();
    if (net::DecodeRollbackDatagram(payload, shape, header, messages) != net::DecodeError::e_ok) return;
    if (header.matchId != m.id) return;
    const size_t inputBytes = m_config.match.inputBytes;
    const uint64_t everyone = (m_config.match.playerCount >= 64 ? ~0ull : (1ull << m_config.match.playerCount) - 1);
    for (const net::RollbackMessage& message : messages) {
        const auto* run = std::get_if<net::RbInputs>(&message);
        // A peer speaks for its own slot only: inputs it relays for others are ignored.
        if (run == nullptr || run->player != slot) continue;
        const auto count = static_cast<int32_t>(run->bytes.size() / inputBytes);
        for (int32_t i = 0; i < count; ++i) {
            const int32_t f = run->firstFrame + i;
            if (f < m.sharedFrames || f >= m.sharedFrames + kRollbackRecordAhead) continue;
            uint64_t& present = m.pendingSlots[f];
            if ((present >> slot) & 1) continue;
            present |= 1ull << slot;
            std::vector<uint8_t>& row = m.pendingInputs[f];
            row.resize(m_config.match.playerCount * inputBytes);
            std::copy_n(run->bytes.begin() + static_cast<ptrdiff_t>(i * inputBytes), inputBytes,
                        row.begin() + static_cast<ptrdiff_t>(static_cast<size_t>(slot) * inputBytes));
        }
    }
    // Every frame whose inputs all arrived, in order, goes to the replay.
    while (!m.pendingSlots.empty() && m.pendingSlots.begin()->first == m.sharedFrames &&
           m.pendingSlots.begin()->second == everyone) {
        m.recorder->Advance(m.pendingInputs.begin()->second);
        m.pendingSlots.erase(m.pendingSlots.begin());
        m.pendingInputs.erase(m.pendingInputs.begin());
        ++m.sharedFrames;
        m.recorded = m.sharedFrames;
    }
}

bool MatchHost::Rebind(Datagram& d, std::span<const uint8_t> tokenBytes) {
    // One UDP address is one socket at a time, so another token from an admitted address means
    // the admitted client's socket closed and its port went to a new one: on a client host
    // that opens and closes sockets (spectators come and go), the next socket may get the same
    // port while the relay still binds it to the departed client's slot. The newcomer takes the
    // address over. Only with a token that is valid and was never presented before (an old
    // datagram of the departed client cannot take the address back), and only in rollback
    // relays, whose members come and go by slot; a lockstep session keeps its own seats.
    if (m_config.kind != MatchKind::e_rollbackRelay) return false;
    net::admission::AdmissionToken token;
    if (m_verifier.Check(tokenBytes, UnixNow(), token) != Refusal::e_none || m_verifier.Used(token)) return false;
    const Peer& old = m_peers.at(d.peer);
    m_log.Event("rebound")
        .Num("match", old.matchId)
        .Int("slot", old.slot)
        .Num("new_match", token.matchId)
        .Num("new_slot", token.slot)
        .Str("peer", old.address);
    ++m_stats.rebound;
    Forget(d.peer);
    Admit(d, m_socket->NowMicros());
    return true;
}

void MatchHost::Forget(PeerId peer) {
    const auto it = m_peers.find(peer);
    if (it == m_peers.end()) return;
    const auto match = m_matches.find(it->second.matchId);
    if (match != m_matches.end()) {
        Match& m = *match->second;
        m.admitted.erase(peer);
        if (m.relay) {
            (void)m.relay->Release(peer);
            for (PeerId& holder : m.holder)
                if (holder == peer) holder = net::kNoPeer;
        }
    }
    m_peers.erase(it);
}

void MatchHost::Refuse(PeerId peer, const std::string& address, const char* reason, bool isToken, size_t index) {
    if (isToken)
        ++m_stats.refusedTokens[index];
    else
        ++m_stats.dropped[index];
    // Forget the sender once this poll's datagrams are routed (its later datagrams in the same
    // poll carry the same PeerId): its PeerId goes back to the socket's table.
    m_forget.push_back(peer);
    const uint64_t second = m_socket->NowMicros() / 1'000'000;
    if (second != m_refusalLogSecond) {
        m_refusalLogSecond = second;
        m_refusalLogged = 0;
    }
    if (++m_refusalLogged <= kRefusalLinesPerSecond)
        m_log.Event(isToken ? "token_refused" : "datagram_dropped").Str("reason", reason).Str("peer", address);
}

void MatchHost::Admit(Datagram& d, uint64_t nowMicros) {
    const std::string address = m_socket->PeerAddress(d.peer);
    if (!m_limiter.Allow(HostOf(address), nowMicros))
        return Refuse(d.peer, address, DropName(Drop::e_rateLimited), false, static_cast<size_t>(Drop::e_rateLimited));
    net::admission::Envelope env;
    if (!net::admission::ParseEnvelope(d.bytes, env))
        return Refuse(d.peer, address, DropName(Drop::e_noToken), false, static_cast<size_t>(Drop::e_noToken));
    const uint64_t unixNow = UnixNow();
    net::admission::AdmissionToken token;
    Refusal refusal = m_verifier.Check(env.token, unixNow, token);
    if (refusal == Refusal::e_none) {
        const bool listed = m_config.matchIds.empty() || std::find(m_config.matchIds.begin(), m_config.matchIds.end(),
                                                                   token.matchId) != m_config.matchIds.end();
        const uint32_t slots = m_config.match.playerCount +
                               (m_config.kind == MatchKind::e_rollbackRelay ? m_config.spectatorsPerMatch : 0);
        if (!listed || m_ended.count(token.matchId) != 0 || token.slot >= slots) refusal = Refusal::e_wrongMatch;
    }
    if (refusal != Refusal::e_none)
        return Refuse(d.peer, address, admission::RefusalName(refusal).data(), true, static_cast<size_t>(refusal));
    if (m_draining)
        return Refuse(d.peer, address, DropName(Drop::e_draining), false, static_cast<size_t>(Drop::e_draining));
    const bool exists = m_matches.count(token.matchId) != 0;
    if (m_peers.size() >= m_config.maxPlayers || (!exists && m_matches.size() >= m_config.maxMatches))
        return Refuse(d.peer, address, DropName(Drop::e_serverFull), false, static_cast<size_t>(Drop::e_serverFull));
    // Only now is the nonce remembered: a refused token does not use up its nonce.
    refusal = m_verifier.Consume(token, AddressKey(address), unixNow);
    if (refusal != Refusal::e_none)
        return Refuse(d.peer, address, admission::RefusalName(refusal).data(), true, static_cast<size_t>(refusal));
    Match* m = exists ? m_matches.at(token.matchId).get() : CreateMatch(token.matchId, nowMicros);
    Peer p;
    p.matchId = token.matchId;
    p.slot = token.slot;
    std::copy(env.token.begin(), env.token.end(), p.token.begin());
    p.bytesIn = d.bytes.size();
    p.address = address;
    const Peer& seated = m_peers[d.peer] = p;
    m->admitted[d.peer] = token.slot;
    ++m_stats.admitted;
    m_log.Event("admitted")
        .Num("match", token.matchId)
        .Num("slot", token.slot)
        .Num("client", token.clientId)
        .Str("peer", address);
    Deliver(*m, d.peer, seated, env.payload);
}

bool MatchHost::SendFor(uint32_t matchId, PeerId peer, std::span<const uint8_t> bytes) {
    const auto it = m_peers.find(peer);
    if (it == m_peers.end() || it->second.matchId != matchId) return false;
    Peer& p = it->second;
    if (!p.handshakeDone) {
        // No amplification: before the handshake completes a sender gets at most what it sent.
        if (p.bytesOut + bytes.size() > p.bytesIn) {
            ++m_stats.heldBeforeHandshake;
            return false;
        }
        p.bytesOut += bytes.size();
    }
    if (!m_socket->Send(peer, bytes)) return false;
    ++m_stats.datagramsOut;
    m_stats.bytesOut += bytes.size();
    return true;
}

MatchHost::Match* MatchHost::CreateMatch(uint32_t id, uint64_t nowMicros) {
    auto m = std::make_unique<Match>();
    m->id = id;
    m->createdMicros = nowMicros;
    m->transport = std::make_unique<MatchTransport>(*this, id);
    if (m_config.kind == MatchKind::e_rollbackRelay) {
        // The front door already bound every member to its token's slot (a join for another
        // slot never reaches the relay), so the relay's own slot secrets are not needed.
        net::RelayServerConfig rc;
        rc.matchId = id;
        const uint32_t slots = std::max<uint32_t>(2, m_config.match.playerCount + m_config.spectatorsPerMatch);
        rc.tokens.assign(slots, 0);
        m->relay = std::make_unique<net::RelayServer>(*m->transport, std::move(rc));
        m->lastHeard.assign(slots, 0);
        m->holder.assign(slots, net::kNoPeer);
        m->players = m_config.match.playerCount;
    } else {
        net::ServerConfig config = m_config.match;
        Match* raw = m.get();
        config.admittedSlot = [raw](PeerId peer) {
            const auto it = raw->admitted.find(peer);
            return it == raw->admitted.end() ? -1 : it->second;
        };
        config.tokenSeed = (static_cast<uint64_t>(id) << 20) ^ nowMicros;
        if (m_config.kind == MatchKind::e_lockstepAuthoritative) {
            // The server's own world, apart from the replay's: the two step independently.
            m->authority = std::make_unique<replay::SceneGame>(m_config.scene);
            if (m->authority->ok()) {
                config.world = &m->authority->world();
                config.game = m->authority.get();
            }
        }
        m->server = std::make_unique<net::LockstepServer>(*m->transport, std::move(config));
    }
    if (!m_config.replayDir.empty()) {
        m->game = std::make_unique<replay::SceneGame>(m_config.scene);
        if (m->game->ok()) {
            m->replayPath = m_config.replayDir + "/match-" + std::to_string(id) + ".lbr";
            m->sink = std::make_unique<replay::FileSink>(m->replayPath);
            replay::RecorderConfig rc = m->game->Config(static_cast<uint16>(m_config.match.playerCount));
            rc.inputBytes = static_cast<uint16>(m_config.match.inputBytes);
            rc.hashInterval = m_config.match.hashInterval;
            if (!m->relay) {
                // Lockstep clients step with the session's settings, so the replay does too;
                // rollback peers step with the scene's own (WorldGameAdapter).
                rc.tickRate = static_cast<uint16>(m_config.match.tickRate);
                rc.velocityIterations = 8;
                rc.positionIterations = 3;
            }
            m->recorder = std::make_unique<replay::Recorder>(m->game->world(), *m->game, *m->sink, rc);
            m->recorder->Begin();
        }
    }
    ++m_stats.matchesCreated;
    m_log.Event("match_created")
        .Num("match", id)
        .Str("kind", MatchKindName(m_config.kind))
        .Num("players", m_config.match.playerCount);
    auto [it, inserted] = m_matches.emplace(id, std::move(m));
    return it->second.get();
}

void MatchHost::UpdateMatch(Match& m, uint64_t nowMicros) {
    if (m.relay) {
        m.relay->Poll();
        // A relay sees no session: a match ends when every member fell silent.
        bool anyLive = false;
        for (uint32_t s = 0; s < m.players; ++s)
            anyLive = anyLive || (m.lastHeard[s] != 0 &&
                                  nowMicros - std::min(nowMicros, m.lastHeard[s]) < m_config.match.disconnectMicros);
        if (m.Started() && !anyLive) return EndMatch(m.id, "players_left");
        if (!m.Started() && nowMicros > m.createdMicros && nowMicros - m.createdMicros > m_config.startTimeoutMicros)
            return EndMatch(m.id, "start_timeout");
        return;
    }
    m.server->Update();
    for (const net::ServerEvent& e : m.server->TakeEvents()) {
        if (e.kind == net::ServerEvent::Kind::e_desync) ++m_stats.desyncs;
        if (e.kind == net::ServerEvent::Kind::e_admitted) ++m_stats.lateJoins;
        const auto peer = m_peers.find(e.peer);
        m_log.Event(EventName(e.kind))
            .Num("match", m.id)
            .Int("slot", e.slot)
            .Int("frame", e.frame)
            .Str("peer", peer == m_peers.end() ? std::string() : peer->second.address);
    }
    if (m.recorder) {
        while (m.recorded < m.server->ConfirmedFrames()) {
            const std::span<const uint8_t> inputs = m.server->ConfirmedInputs(m.recorded);
            if (inputs.empty()) break;
            m.recorder->Advance(inputs);
            ++m.recorded;
        }
    }
    bool anyLive = false;
    for (uint32_t s = 0; s < m_config.match.playerCount; ++s) {
        const auto st = m.server->Slot(s).state;
        anyLive = anyLive || (st != net::SlotInfo::State::e_free && st != net::SlotInfo::State::e_disconnected);
    }
    if (m.server->Started() && !anyLive) return EndMatch(m.id, "players_left");
    if (!m.server->Started() && nowMicros > m.createdMicros &&
        nowMicros - m.createdMicros > m_config.startTimeoutMicros)
        return EndMatch(m.id, "start_timeout");
}

void MatchHost::EndMatch(uint32_t id, const char* why) {
    const auto it = m_matches.find(id);
    if (it == m_matches.end()) return;
    Match& m = *it->second;
    if (m.recorder) {
        replay::Error e = m.recorder->Finish();
        const bool closed = m.sink->Close();
        if (e.ok() && closed) {
            ++m_stats.replaysWritten;
            m_log.Event("replay_written").Num("match", id).Int("frames", m.recorded).Str("path", m.replayPath);
        } else {
            ++m_stats.replayFailures;
            m_log.Event("replay_failed").Num("match", id).Str("path", m.replayPath);
        }
    }
    m_log.Event("match_ended").Num("match", id).Str("why", why).Int("frames", m.Frames());
    for (const auto& [peer, slot] : m.admitted) {
        m_peers.erase(peer);
        m_socket->Disconnect(peer);
    }
    m_ended[id] = UnixNow();
    // A match id is refused while a token for it could still be valid, then forgotten.
    const uint64_t now = UnixNow();
    for (auto e = m_ended.begin(); e != m_ended.end();) {
        if (now - e->second > m_config.tokenMaxLifetimeSeconds)
            e = m_ended.erase(e);
        else
            ++e;
    }
    ++m_stats.matchesEnded;
    m_matches.erase(it);
}

const net::LockstepServer* MatchHost::LockstepOf(uint32_t id) const {
    const auto it = m_matches.find(id);
    return it == m_matches.end() ? nullptr : it->second->server.get();
}

void MatchHost::BeginDrain() {
    if (m_draining) return;
    m_draining = true;
    m_log.Event("draining").Num("matches", m_matches.size()).Num("players", m_peers.size());
}

void MatchHost::CloseAll() {
    std::vector<uint32_t> ids;
    for (auto& [id, match] : m_matches) ids.push_back(id);
    for (uint32_t id : ids) {
        if (m_matches.at(id)->server) m_matches.at(id)->server->Close();
        EndMatch(id, "server_closing");
    }
}

}  // namespace lockbox::server
