#pragma once
/// @file
/// The lockstep server (docs/net.md "Sessions"): assigns slots, collects every
/// player's inputs, relays each confirmed frame's inputs to every client, compares the clients'
/// state hashes, times out silent clients and brings late joiners in through a snapshot.
///
/// A frame is confirmed when every live slot's input for it has arrived. A slot that has not
/// joined yet, or whose client was declared disconnected, contributes empty input (all zero
/// bytes) from then on, so the match goes on; a joiner's slot contributes its own inputs again
/// from the join frame the server hands it in Admit.
///
/// Non-blocking: call Update often (every millisecond or so); it polls the transport, handles
/// what arrived, confirms frames and sends. Time is the transport's NowMicros.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Protocol.h"
#include "lockbox/net/Transport.h"

namespace lockbox {
class b2World;
}
namespace lockbox {
class WorldGame;
}

namespace lockbox::net {

/// Server settings.
struct ServerConfig {
    uint32_t playerCount = 2;            ///< slots, 1 .. kMaxPlayers
    uint32_t startPlayers = 0;           ///< frames confirm once this many slots were filled (0: playerCount)
    uint32_t inputBytes = 8;             ///< per player per frame, 1 .. kMaxInputBytes
    uint32_t tickRate = 60;              ///< frames per second, 1 .. 1000
    uint32_t hashInterval = 30;          ///< clients report the hash after every frame f with f % interval == 0 (>= 1)
    uint32_t inputDelay = 0;             ///< frames handed to clients; 0: each client picks it from its RTT
    uint64_t interruptMicros = 500'000;  ///< silence before an `interrupted` event
    uint64_t disconnectMicros = 2'000'000;  ///< silence before the slot is dropped (empty input)
    uint64_t keepAliveMicros = 200'000;     ///< longest gap between datagrams to a client
    uint32_t maxCatchUpFrames = 16;         ///< authoritative mode: frames simulated per Update
    uint64_t tokenSeed = 1;                 ///< seeds the session tokens (any value; tests fix it)
    /// Authoritative mode: the server also simulates every confirmed frame on this world with
    /// this game (both outlive the server), reports its own hash and serves late joiners from
    /// its own state. Both null: relay mode (late joiners get a live client's snapshot).
    b2World* world = nullptr;
    /// The game that applies each confirmed frame's inputs to `world` (authoritative mode); null in
    /// relay mode.
    WorldGame* game = nullptr;
    uint32_t velocityIterations = 8;  ///< authoritative mode step settings
    /// Authoritative mode step settings: position iterations per step.
    uint32_t positionIterations = 3;
    /// Admission (a match server that admits clients by token): when set, a Hello from `peer`
    /// may take only the slot this returns, whatever it requested or the token it carries
    /// names; a negative value or a slot >= playerCount refuses it (Reject e_badToken). Unset:
    /// any slot, as above.
    std::function<int32_t(PeerId peer)> admittedSlot;
};

/// A state hash reported for one frame.
struct SlotHash {
    int32_t slot = -1;  ///< the reporting slot; -1: the authoritative server
    /// The reported hash of that frame (world hash folded with the game's user state).
    uint64_t hash = 0;
};

/// Something the caller may want to know about.
struct ServerEvent {
    /// What happened; the fields below that a kind uses are named next to it.
    enum class Kind : uint8_t {
        e_joined,        ///< a client got a slot (frame: the start frame, or -1 for a joiner)
        e_started,       ///< enough slots filled: frames start confirming
        e_interrupted,   ///< a live slot's client went silent for interruptMicros
        e_resumed,       ///< an interrupted client was heard again
        e_disconnected,  ///< a slot was dropped (timeout, Disconnect, or replaced): empty input from `frame`
        e_admitted,      ///< a joiner's hash matched; it plays from `frame`
        e_joinFailed,    ///< a joiner's hash did not match (or its snapshot source vanished)
        e_desync,        ///< the first mismatching hash reports: `frame` and every hash known then
        e_spoofedInput,  ///< `peer` sent inputs claiming `claimedSlot`, which it does not own
    };
    /// What happened.
    Kind kind = Kind::e_joined;
    int32_t slot = -1;                           ///< the slot concerned (-1 when none)
    PeerId peer = kNoPeer;                       ///< the transport peer concerned
    int32_t frame = -1;                          ///< the frame concerned (-1 when none)
    int32_t claimedSlot = -1;                    ///< e_spoofedInput: the slot the inputs claimed
    RejectReason reason = RejectReason::e_none;  ///< e_disconnected / e_joinFailed: why
    std::vector<SlotHash> hashes;                ///< e_desync: every report of `frame` at that moment, by slot
};

/// Counters.
struct ServerStats {
    DecodeErrorCounts malformed{};  ///< refused datagrams by DecodeError
    uint64_t badToken = 0;          ///< well-formed datagrams with the wrong session token
    uint64_t unknownPeer = 0;       ///< session messages from a peer that owns no slot
    uint64_t spoofedInputs = 0;     ///< Inputs messages claiming another slot
    uint64_t unexpected = 0;        ///< messages a server does not take (Welcome, Confirmed, ...)
    uint64_t rejected = 0;          ///< Hellos answered with Reject
    uint64_t desyncFrames = 0;      ///< frames with mismatching reports (one event for the first)
    uint64_t snapshotsServed = 0;   ///< snapshots fully delivered to joiners
    /// Datagrams the server sent.
    uint64_t datagramsSent = 0;
    int32_t confirmedFrames = 0;  ///< frames confirmed so far (= the next frame to confirm)
    /// Sum of malformed[].
    uint64_t MalformedTotal() const noexcept {
        uint64_t n = 0;
        for (uint64_t c : malformed) n += c;
        return n;
    }
};

/// What the server knows of one slot (for displays and tests).
struct SlotInfo {
    /// Lifecycle of a slot: free (no client), joining (a late joiner loading or catching up), live
    /// (playing), interrupted (its client is silent but not yet timed out), disconnected (dropped;
    /// it plays empty input).
    enum class State : uint8_t { e_free, e_joining, e_live, e_interrupted, e_disconnected };
    /// Where the slot is in that lifecycle.
    State state = State::e_free;
    /// The transport peer that owns the slot (kNoPeer when free).
    PeerId peer = kNoPeer;
    int32_t nextInputFrame = 0;  ///< every input of this slot before this frame has arrived
    int32_t ackedConfirmed = 0;  ///< the client has every confirmed frame before this one
};

/// The authoritative end of a lockstep match: confirms each frame once every live slot's input has
/// arrived and relays the confirmed inputs to every client (see the file comment). Non-blocking;
/// one per match.
class LOCKBOX_API LockstepServer {
public:
    /// The transport must outlive the server. Invalid settings are clamped into range.
    LockstepServer(Transport& transport, ServerConfig config);
    ~LockstepServer();
    LockstepServer(const LockstepServer&) = delete;
    LockstepServer& operator=(const LockstepServer&) = delete;

    /// Polls, handles every datagram, times clients out, confirms frames, simulates them in
    /// authoritative mode (at most maxCatchUpFrames) and sends. Never blocks.
    void Update();
    /// Sends Disconnect{e_serverClosing} to every client (best effort, once).
    void Close();

    /// Events since the last call, oldest first.
    std::vector<ServerEvent> TakeEvents();
    /// Counters since construction.
    const ServerStats& Stats() const noexcept;
    /// The settings in use (after clamping into range).
    const ServerConfig& Config() const noexcept;
    /// Next frame to confirm (every frame before it is confirmed).
    int32_t ConfirmedFrames() const noexcept;
    /// True once startPlayers slots were filled.
    bool Started() const noexcept;
    /// One slot's state, slot < playerCount.
    SlotInfo Slot(uint32_t slot) const;
    /// The confirmed inputs of frame f (playerCount * inputBytes bytes, slot 0 first); empty
    /// when f is not confirmed or no longer kept. The server keeps at least the last 10 s of
    /// frames, and everything a client, a joiner or the authoritative world still needs.
    std::span<const uint8_t> ConfirmedInputs(int32_t frame) const;
    /// Authoritative mode: next frame the server's world will step; relay mode: 0.
    int32_t SimulatedFrames() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace lockbox::net
