#pragma once
/// @file
/// RollbackSpectator: watches a rollback match. A host peer (a RollbackPeer with
/// this machine in RollbackPeerConfig::spectators) sends every player's confirmed inputs, the
/// same stream a replay stores; the spectator acknowledges them and hands them out frame by
/// frame. Confirmed inputs never change, so a spectator never rolls back: it applies each
/// frame once, RTT plus the slowest player's latency behind the players.
///
/// Late join (config.lateJoin): the spectator sends RbJoinRequest until its host answers with
/// a snapshot of a confirmed frame F in RbSnapshotChunk pieces. Chunks are acked one by one,
/// reassembled in any order and checked (length from the chunk headers, XXH3-64 of the whole)
/// before the game sees them: TakeSnapshot hands out (F, bytes) once, then Next gives frames
/// F, F + 1, ... A snapshot that fails the check is dropped and asked for again (a new
/// attempt); an incomplete one is never handed out. For a WorldGameAdapter game the bytes go
/// to WorldGameAdapter::RestoreSnapshot.

#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Protocol.h"
#include "lockbox/net/RollbackProtocol.h"
#include "lockbox/net/Transport.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::net {

class SnapshotReceiver;

/// Settings of a spectator.
struct RollbackSpectatorConfig {
    uint32_t matchId = 1;              ///< the match's id (RollbackPeerConfig::matchId)
    uint32_t players = 2;              ///< 1 .. kRollbackMaxPlayers
    uint32_t inputBytes = 8;           ///< 1 .. kRollbackMaxInputBytes
    PeerId host = kNoPeer;             ///< the peer that sends the confirmed inputs
    uint64_t timeoutMicros = 2000000;  ///< silence after which HostAlive() turns false
    /// Silence after which HostInterrupted() turns true and e_interrupted is queued (like a
    /// player's RollbackPeerConfig::interruptTimeoutMicros); 0 turns the reports off.
    uint64_t interruptTimeoutMicros = 500000;
    uint32_t maxBufferedFrames = 4096;                ///< frames kept before Next takes them (more are not acked)
    bool lateJoin = false;                            ///< ask the host for a snapshot instead of starting at frame 0
    uint32_t maxSnapshotBytes = kRbMaxSnapshotBytes;  ///< larger snapshots are refused, 1 .. kRbMaxSnapshotBytes
    /// The engine's determinism version, announced to the host and required of it (RbHello).
    uint32_t determinismVersion = b2_determinismVersion;
};

/// Where a spectator stands.
enum class SpectatorState : uint8_t {
    e_following = 0,      ///< receiving the confirmed inputs (from frame 0, or after TakeSnapshot)
    e_joining = 1,        ///< late join: asking for / assembling a snapshot
    e_snapshotReady = 2,  ///< late join: a checked snapshot waits for TakeSnapshot
    /// The host runs another protocol, match, engine determinism version or session shape
    /// (Incompatibility() says which): nothing more is taken from it and Next gives nothing.
    e_incompatible = 3,
};

/// What happened to the link to the host (RollbackSpectator::TakeEvents), so a spectator can
/// show "waiting for the host" before it gives up, as players do with their events.
struct SpectatorEvent {
    /// What happened to the link to the host.
    enum class Kind : uint8_t {
        e_interrupted = 0,  ///< nothing from the host for interruptTimeoutMicros
        e_resumed = 1,      ///< heard again after e_interrupted, or after an e_hostLost of silence
        e_hostLost = 2,     ///< timeoutMicros of silence, or the host's RbDisconnect
    };
    /// What happened.
    Kind kind = Kind::e_interrupted;
    int32_t frame = 0;  ///< ReceivedFrame() at that moment
};

/// Watches a rollback match: receives and acknowledges the confirmed inputs from a host peer and
/// hands them out frame by frame (Next), never rolling back; can join late from a snapshot (see the
/// file comment).
class LOCKBOX_API RollbackSpectator {
public:
    /// `transport` must outlive the spectator.
    RollbackSpectator(Transport& transport, RollbackSpectatorConfig config);
    ~RollbackSpectator();
    RollbackSpectator(const RollbackSpectator&) = delete;
    RollbackSpectator& operator=(const RollbackSpectator&) = delete;

    /// Reads what arrived from the host; frames must arrive in order (the host resends).
    void Poll();
    /// Acknowledges the frames received so far (one datagram to the host, led by our hello).
    /// Once incompatible: a few hello-only datagrams, so the host stops sending, then nothing.
    void Flush();
    /// The next frame's inputs (players * inputBytes bytes, player 0 first) and its number;
    /// false when it has not arrived yet (and always before TakeSnapshot in a late join).
    bool Next(int32_t& frame, std::vector<uint8_t>& inputs);
    /// Late join: the checked snapshot (the state at `frame`, the bytes the host's game
    /// offered), handed out once; false while none is ready. Load it before calling Next.
    bool TakeSnapshot(int32_t& frame, std::vector<uint8_t>& bytes);
    /// Where the spectator stands (e_joining until a checked snapshot arrives in a late join).
    SpectatorState State() const noexcept { return m_state; }
    /// Assembled snapshots dropped because their checksum did not match.
    uint64_t SnapshotsRefused() const noexcept { return m_snapshotsRefused; }
    /// Snapshot chunks taken into an assembly (duplicates not counted).
    uint64_t SnapshotChunks() const noexcept { return m_snapshotChunks; }
    /// Snapshot bytes of the last snapshot handed out (0 before).
    uint64_t SnapshotBytes() const noexcept { return m_snapshotBytes; }

    /// Frames before this have arrived.
    int32_t ReceivedFrame() const noexcept { return m_received; }
    /// Frames handed out by Next.
    int32_t ConsumedFrame() const noexcept { return m_consumed; }
    /// False after timeoutMicros of silence (true again when heard), and for good after the
    /// host's RbDisconnect.
    bool HostAlive() const noexcept { return m_alive; }
    /// True from interruptTimeoutMicros of silence until the host is heard again.
    bool HostInterrupted() const noexcept { return m_interrupted; }
    /// The link events since the last call, oldest first (each outage: e_interrupted, then
    /// e_resumed, or e_hostLost and e_resumed if the host comes back).
    std::vector<SpectatorEvent> TakeEvents();
    /// Datagrams refused (malformed, another match, not from the host, incompatible).
    uint64_t Refused() const noexcept { return m_refused; }
    /// Why the host cannot be followed (e_none unless State() is e_incompatible).
    RollbackIncompatibility Incompatibility() const noexcept { return m_incompatibility; }

private:
    void TakeChunk(const RbSnapshotChunk& c);
    void HostLost();  // m_alive false; e_hostLost once per outage

    Transport& m_transport;
    RollbackSpectatorConfig m_config;
    RollbackShape m_shape;
    std::deque<std::vector<uint8_t>> m_frames;  // frames [m_consumed, m_received)
    int32_t m_received = 0;
    int32_t m_consumed = 0;
    uint64_t m_lastHeard = 0;
    bool m_alive = true;
    bool m_interrupted = false;
    bool m_lostReported = false;  // e_hostLost queued for the current outage
    bool m_hostLeft = false;      // the host's RbDisconnect: gone for good
    std::vector<SpectatorEvent> m_events;
    uint64_t m_refused = 0;
    SpectatorState m_state = SpectatorState::e_following;
    RollbackIncompatibility m_incompatibility = RollbackIncompatibility::e_none;
    static constexpr uint32_t kIncompatibleNotices = 5;  // hello-only datagrams sent once incompatible
    uint32_t m_incompatibleNotices = 0;
    uint32_t m_attempt = 1;
    // The assembly (the lockstep late join's chunk reassembly) and the checksum its chunks carry.
    std::unique_ptr<SnapshotReceiver> m_receiver;
    uint64_t m_asmChecksum = 0;
    // The last refused snapshot: its stragglers are ignored instead of assembled again.
    bool m_hasBad = false;
    int32_t m_badFrame = 0;
    uint64_t m_badChecksum = 0;
    std::vector<RbSnapshotAck> m_pendingAcks;
    int32_t m_snapshotFrame = 0;
    uint64_t m_snapshotChecksum = 0;
    std::vector<uint8_t> m_snapshot;
    uint64_t m_snapshotsRefused = 0;
    uint64_t m_snapshotChunks = 0;
    uint64_t m_snapshotBytes = 0;
    std::vector<Datagram> m_inbox;
    std::vector<RollbackMessage> m_messages;
    RollbackDatagramWriter m_writer;
};

}  // namespace lockbox::net
