#pragma once
// The heart of lockbox_server: one UDP socket, many matches behind it.
//
// The front door reads every datagram. A sender it has admitted is routed to its match (a
// LockstepServer, relaying or authoritative, or a RelayServer for rollback peers) through a
// MatchTransport, a Transport per match, after its per-peer bandwidth check. Any other sender is
// rate-limited per source address, then must present an admission token in an envelope
// (lockbox/net/admission/AdmissionTransport.h); a valid token admits the sender to the match
// and slot it names (creating the match on its first token) and the envelope's payload, the
// client's Hello, goes to that match. Nothing is ever sent to a sender that was not admitted,
// and until an admitted client's handshake completes (its first datagram without an envelope)
// the server sends it no more bytes than it received from it.

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "JsonLog.h"
#include "RateLimiter.h"
#include "lockbox/net/LockstepServer.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox_admission/TokenAuthority.h"

namespace lockbox::server {

/// Why a datagram from a sender that is not admitted was dropped (besides token refusals).
enum class Drop : uint8_t {
    e_rateLimited = 0,  ///< its source address sent too much before being admitted
    e_noToken,          ///< no admission envelope (or a malformed one)
    e_serverFull,       ///< a valid token, but the match or player limit is reached
    e_draining,         ///< a valid token, but the server is shutting down
    e_strayEnvelope,    ///< an admitted sender presented another token
    e_peerBandwidth,    ///< an admitted sender sent more bytes than its per-peer budget
    e_wrongSlot,        ///< an admitted rollback peer claimed a relay slot its token does not name
    e_slotTaken,        ///< a relay join for a slot whose holder is still heard (spectators in turn)
    e_count
};
/// Metric label of a drop reason ("rate_limited", ...).
const char* DropName(Drop drop) noexcept;

/// What every match of a host runs (docs/deploy.md "Match kinds").
enum class MatchKind : uint8_t {
    e_lockstepRelay = 0,      ///< LockstepServer relaying inputs; the clients simulate
    e_lockstepAuthoritative,  ///< LockstepServer that also simulates the scene and checks hashes
    e_rollbackRelay,          ///< RelayServer between rollback peers; the server records inputs
};
/// Option value of a kind ("lockstep-relay", "lockstep-authoritative", "rollback-relay").
const char* MatchKindName(MatchKind kind) noexcept;

/// Settings of a host.
struct HostConfig {
    admission::TokenKey key{};
    std::vector<uint32_t> matchIds;  ///< hosted matches; empty: any id a token names
    uint32_t maxMatches = 64;
    uint32_t maxPlayers = 256;
    MatchKind kind = MatchKind::e_lockstepRelay;
    net::ServerConfig match;  ///< settings of every match (playerCount, inputBytes, ...)
    /// Rollback relay: relay slots after the players' for spectators (tokens for slots
    /// playerCount .. playerCount + spectatorsPerMatch - 1); players + spectators <=
    /// net::kRelayMaxSlots.
    uint32_t spectatorsPerMatch = 0;
    /// Bytes a second an admitted client may send per stream it sends (one second's worth at
    /// once); more is dropped unread (Drop::e_peerBandwidth). 0: no limit. A lockstep client and
    /// a spectator have one stream (to the server, to their host); a rollback-relay player one
    /// per other player (playerCount - 1), and slot 0, the spectators' host, one more per
    /// spectator slot.
    uint32_t peerBytesPerSecond = 65536;
    /// Rollback relay with spectator slots: the budget of slot 0, the player whose peer hosts the
    /// spectators (it sends each the confirmed inputs, and a joining one a snapshot), in bytes a
    /// second (0: no limit), instead of its streams' count times peerBytesPerSecond.
    std::optional<uint32_t> spectatorHostBytesPerSecond;
    uint64_t startTimeoutMicros = 60'000'000;
    uint64_t tokenMaxLifetimeSeconds = 3600;
    size_t replayCacheSize = 65536;
    uint32_t rateLimitPerSecond = 20;
    uint32_t rateLimitBurst = 40;
    std::string scene;      ///< library scene of the matches (replays; the authoritative world)
    std::string replayDir;  ///< where finished matches' replays go; empty: none
    /// Wall clock in Unix seconds (token deadlines); tests replace it.
    std::function<uint64_t()> unixNow;
};

/// Counters of a host (never reset).
struct HostStats {
    uint64_t datagramsIn = 0, bytesIn = 0, datagramsOut = 0, bytesOut = 0;
    std::array<uint64_t, static_cast<size_t>(admission::Refusal::e_count)> refusedTokens{};
    std::array<uint64_t, static_cast<size_t>(Drop::e_count)> dropped{};
    uint64_t heldBeforeHandshake = 0;  ///< sends refused so a sender is never sent more than it sent
    uint64_t admitted = 0, matchesCreated = 0, matchesEnded = 0;
    uint64_t desyncs = 0, lateJoins = 0, replaysWritten = 0, replayFailures = 0;
    /// Rollback relay: admitted addresses taken over by a new client's fresh token (the
    /// previous client's port went to another socket; see MatchHost::Rebind).
    uint64_t rebound = 0;
};

class MatchHost {
public:
    /// Takes the socket; `log` must outlive the host.
    MatchHost(std::unique_ptr<net::UdpTransport> socket, HostConfig config, JsonLog& log);
    ~MatchHost();
    MatchHost(const MatchHost&) = delete;
    MatchHost& operator=(const MatchHost&) = delete;

    /// Reads what arrived (at most one socket poll), routes it, updates every match and ends
    /// the finished ones. Never blocks.
    void Update();
    /// Stops admitting: every new token is dropped (Drop::e_draining) from now on.
    void BeginDrain();
    /// Ends every match now (its clients are told the server is closing); replays are written.
    void CloseAll();

    bool Draining() const noexcept { return m_draining; }
    size_t MatchCount() const noexcept { return m_matches.size(); }
    size_t PlayerCount() const noexcept { return m_peers.size(); }
    const HostStats& Stats() const noexcept { return m_stats; }
    net::UdpTransport& Socket() noexcept { return *m_socket; }
    /// The lockstep server of match `id` (lockstep kinds), or null: for inspection.
    const net::LockstepServer* LockstepOf(uint32_t id) const;
    /// Durations of the latest Updates, microseconds (the newest 4096).
    const std::vector<uint32_t>& UpdateMicros() const noexcept { return m_updateMicros; }

private:
    class MatchTransport;
    struct Match;
    struct Peer {
        uint32_t matchId = 0;
        int32_t slot = -1;
        admission::TokenBytes token{};
        uint64_t bytesIn = 0, bytesOut = 0;  // before the handshake completed
        bool handshakeDone = false;
        uint64_t credit = 0;      // bandwidth budget, byte-microseconds
        uint64_t creditTime = 0;  // when credit was last brought up to date
        std::string address;
    };

    void Route(net::Datagram& d);
    void Deliver(Match& m, net::PeerId peer, const Peer& p, std::span<const uint8_t> payload);
    bool WithinBandwidth(Peer& p, size_t bytes, uint64_t nowMicros) const;
    uint64_t BytesPerSecondOf(const Peer& p) const;
    void Record(Match& m);
    void RecordRollbackInputs(Match& m, int32_t slot, std::span<const uint8_t> payload);
    void Admit(net::Datagram& d, uint64_t nowMicros);
    bool Rebind(net::Datagram& d, std::span<const uint8_t> token);
    void Forget(net::PeerId peer);
    bool SendFor(uint32_t matchId, net::PeerId peer, std::span<const uint8_t> bytes);
    Match* CreateMatch(uint32_t id, uint64_t nowMicros);
    void UpdateMatch(Match& m, uint64_t nowMicros);
    void EndMatch(uint32_t id, const char* why);
    void Refuse(net::PeerId peer, const std::string& address, const char* reason, bool isToken, size_t index);
    uint64_t UnixNow() const;

    std::unique_ptr<net::UdpTransport> m_socket;
    HostConfig m_config;
    JsonLog& m_log;
    admission::TokenVerifier m_verifier;
    RateLimiter m_limiter;
    std::map<uint32_t, std::unique_ptr<Match>> m_matches;
    std::map<uint32_t, uint64_t> m_ended;  // match id -> Unix second it ended (refused until forgotten)
    std::map<net::PeerId, Peer> m_peers;
    std::vector<net::Datagram> m_inbox;
    std::vector<net::PeerId> m_forget;  // refused senders, forgotten after the poll's routing
    std::vector<uint32_t> m_updateMicros;
    size_t m_updateNext = 0;
    uint64_t m_refusalLogSecond = 0;
    uint32_t m_refusalLogged = 0;
    bool m_draining = false;
    HostStats m_stats;
};

}  // namespace lockbox::server
