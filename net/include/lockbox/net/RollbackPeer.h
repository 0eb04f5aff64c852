#pragma once
/// @file
/// RollbackPeer (docs/rollback.md): carries one RollbackSession's inputs, acks,
/// time-sync reports and final hashes over a Transport to the other peers of a peer-to-peer
/// match, and the confirmed input stream to spectators (RollbackSpectator.h), including
/// spectators that join late from a snapshot the game offers (SnapshotWanted, OfferSnapshot).
/// A remote silent for interruptTimeoutMicros raises e_interrupted in the session, then
/// e_resumed when heard again or e_disconnected at disconnectTimeoutMicros.
///
/// Each tick the game calls Poll (datagrams in: remote inputs and hashes go to the session),
/// then AddLocalInput / AdvanceFrame on the session and executes the requests, then Flush (one
/// datagram out per remote and spectator). Every datagram repeats all local inputs the remote
/// has not acknowledged, so a lost datagram costs nothing but the wait for the next one.
///
/// Disconnects (docs/rollback.md, "Disconnects"): every datagram also carries this peer's
/// view (the first frame it lacks of every player), which the receiver's session uses to
/// decide finality, and "player p frozen at F" for every player this peer considers gone. A
/// remote that sends RbDisconnect, stays silent past disconnectTimeoutMicros, or is named
/// frozen by any live remote (gossip) stops counting as live; its players are frozen here at
/// this peer's received frame, and each is cut at the smallest frozen value once every live
/// remote's value for it has arrived (the same cut on every survivor).
///
/// Start phase: a peer with remotes starts synchronizing. It holds the session
/// (RollbackSession::SetSynchronizing: AdvanceFrame does not advance) until every remote is
/// synchronized, that is, until it has heard the remote and the remote has echoed one of its
/// own datagrams (an RbQualityReply: a full round trip both ways), and only then runs the
/// disconnect and interruption timers. Events: e_synchronizing when a remote is first heard,
/// e_synchronized when its round trip is done, e_running once all are. If that takes longer
/// than startTimeoutMicros, one e_startTimeout names each remote not synchronized, the peer
/// leaves (RbDisconnect) and the state is e_startFailed: the match never runs on zero inputs.
/// Peers may therefore be started seconds apart, in any order.
///
/// Time sync: every datagram carries the sender's frame and its frame advantage (how far it
/// believes it is ahead of the receiver, RTT taken into account). The peer that is ahead
/// idles one tick at a time, spread out (WaitThisTick), until the peers line up.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Protocol.h"
#include "lockbox/net/RollbackProtocol.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/Transport.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::net {

/// Another machine of the match and the players whose inputs it adds.
struct RollbackRemote {
    PeerId peer = kNoPeer;          ///< its PeerId on the transport
    std::vector<uint32_t> players;  ///< players local to it (each remote in the session)
};

/// Settings of a RollbackPeer.
struct RollbackPeerConfig {
    uint32_t matchId = 1;    ///< same on every peer of the match
    uint32_t tickRate = 60;  ///< frames per second, >= 1
    /// Longest start phase: every remote must be synchronized (heard, and its echo of one of
    /// our datagrams heard) within this long of construction, else the start fails naming the
    /// missing remotes (e_startTimeout). Microseconds, >= 1.
    uint64_t startTimeoutMicros = 10000000;
    /// Silence after which a remote's players leave; counted only once the match runs.
    uint64_t disconnectTimeoutMicros = 2000000;
    /// Silence after which an e_interrupted event names the remote (once per silence; an
    /// e_resumed follows when it is heard again). Should be < disconnectTimeoutMicros.
    uint64_t interruptTimeoutMicros = 500000;
    /// The other peers of the match and which players each one adds; every player that is not local
    /// to this session belongs to exactly one of them.
    std::vector<RollbackRemote> remotes;
    std::vector<PeerId> spectators;  ///< receive the confirmed inputs (RbConfirmed)
    /// Senders not listed anywhere whose first valid datagram carries an RbJoinRequest become
    /// late-join spectators, up to this many (0: only the listed spectators).
    uint32_t maxLateSpectators = 0;
    /// A late-join spectator silent this long (microseconds) is forgotten: nothing more is sent
    /// to it and its place counts no more against maxLateSpectators, so a new spectator may
    /// join from the same address (a relay slot that spectators take in turn). 0: never
    /// forgotten. Listed spectators are never forgotten.
    uint64_t lateSpectatorTimeoutMicros = 0;
    /// A snapshot chunk not acked this long after it was sent goes again (microseconds, >= 1);
    /// once acks show the round trip, the resend waits at least that plus four deviations.
    uint64_t snapshotResendMicros = 100000;
    /// Snapshot chunk datagrams sent to one spectator per Flush, >= 1 (16: ~1 MB/s at 60 Hz).
    uint32_t snapshotChunksPerFlush = 16;
    /// Ticks between two waits of WaitThisTick (the "gently" of time sync), >= 1.
    uint32_t waitSpacingTicks = 8;
    /// The engine's determinism version announced in RbHello and required of every remote
    /// and spectator (leave it: a test sets another to stand in for an older build).
    uint32_t determinismVersion = b2_determinismVersion;
};

/// Counters of a RollbackPeer.
struct RollbackPeerStats {
    /// Datagrams sent, to remotes and spectators.
    uint64_t datagramsSent = 0;
    /// Datagrams received, accepted or refused.
    uint64_t datagramsReceived = 0;
    uint64_t refused = 0;             ///< malformed, other match, unknown or incompatible sender
    uint64_t waitsRecommended = 0;    ///< WaitThisTick returned true
    uint64_t snapshotsOffered = 0;    ///< OfferSnapshot calls that started a transfer
    uint64_t snapshotChunksSent = 0;  ///< chunk datagrams, resends included
};

/// Where a RollbackPeer is in its life.
enum class RollbackPeerState : uint8_t {
    e_synchronizing = 0,  ///< waiting for every remote's round trip; the session does not advance
    e_running,            ///< the match runs
    e_startFailed,        ///< the start timeout expired (e_startTimeout named who was missing); left
};
/// Short name of a state ("synchronizing", ...).
LOCKBOX_API const char* RollbackPeerStateName(RollbackPeerState state) noexcept;

/// The network figures of one remote peer in one call (RollbackPeer::RemoteStats). Counts
/// are since the peer was made; rates are over the latest whole second.
struct RollbackRemoteStats {
    bool synchronized = false;        ///< its start-phase round trip is done
    bool alive = false;               ///< not left, timed out or named gone
    bool interrupted = false;         ///< silent past interruptTimeoutMicros right now
    uint64_t rttMicros = 0;           ///< smoothed round-trip time; 0 before the first sample
    uint64_t rttDeviationMicros = 0;  ///< smoothed mean deviation of the RTT samples
    uint32_t rttSamples = 0;          ///< echoes measured
    int32_t remoteFrame = 0;          ///< the frame it last reported (its current frame then)
    /// How far this peer believes it runs ahead of the remote (RTT taken into account), in
    /// thousandths of a frame, averaged over the latest samples; negative: behind.
    int32_t framesAheadMilli = 0;
    /// The remote's own estimate of its lead over this peer, same units (it sends it).
    int32_t remoteFramesAheadMilli = 0;
    uint64_t datagramsSent = 0;      ///< to it
    uint64_t datagramsReceived = 0;  ///< accepted from it
    uint64_t bytesSent = 0;          ///< payload bytes to it
    uint64_t bytesReceived = 0;      ///< payload bytes accepted from it
    /// Bit rates of the latest whole second (0 during the first), payload plus 28 bytes of
    /// IPv4 + UDP header per datagram.
    ///@{
    uint64_t sendBitsPerSecond = 0;
    uint64_t receiveBitsPerSecond = 0;
    ///@}
    /// Its datagrams to this peer that never arrived, estimated from their sequence numbers
    /// since the first one heard (a datagram still in flight counts until it lands; a
    /// duplicated one can hide a loss), and that as a share of those it sent, per mille.
    ///@{
    uint64_t datagramsLost = 0;
    uint32_t lossPermille = 0;
    ///@}
    /// Inputs of its players that arrived after a wrong prediction: the rollbacks it caused
    /// (RollbackSession::MispredictedInputs summed over its players).
    uint64_t mispredictedInputs = 0;
    /// The session's own figures, all remotes together (RollbackStats): rollbacks, frames
    /// re-simulated, and the deepest rollback.
    ///@{
    uint64_t rollbacks = 0;
    uint64_t framesResimulated = 0;
    uint32_t deepestRollback = 0;
    ///@}
    /// The newest final hash it sent (RbHash; a frame f with f % desyncInterval == 0 is sent
    /// once f is final there), and its frame; -1 before the first. RollbackMatch's end of
    /// match waits for every remote's hash of the last frame.
    ///@{
    int32_t finalHashFrame = -1;
    uint64_t finalHash = 0;
    ///@}
};

/// What OfferSnapshot made of a snapshot.
enum class SnapshotOfferResult : uint8_t {
    e_ok = 0,        ///< sent to every spectator that wanted one
    e_notWanted,     ///< no spectator waits for a snapshot (nothing sent)
    e_notConfirmed,  ///< frame < 0 or past min(ConfirmedFrame, CurrentFrame): could still change
    e_inputsGone,    ///< the session no longer keeps the inputs of `frame`: offer a newer frame
    e_badSize,       ///< empty or larger than kRbMaxSnapshotBytes
};

/// One peer of a peer-to-peer rollback match: carries its RollbackSession's inputs, acks, time-sync
/// reports and hashes over a Transport to the other peers and the confirmed inputs to spectators,
/// and handles interruptions, disconnects and late-joining spectators (see the file comment).
class LOCKBOX_API RollbackPeer {
public:
    /// `session` and `transport` must outlive the peer; every remote player must be a
    /// non-local player of the session (others are ignored).
    RollbackPeer(RollbackSession& session, Transport& transport, RollbackPeerConfig config);
    ~RollbackPeer();
    RollbackPeer(const RollbackPeer&) = delete;
    RollbackPeer& operator=(const RollbackPeer&) = delete;

    /// Reads every datagram that has arrived and hands inputs and hashes to the session;
    /// raises e_interrupted / e_resumed for remotes silent past interruptTimeoutMicros / heard
    /// again, freezes the players of remotes silent past the disconnect timeout (or that
    /// left, or that a live remote names gone) and cuts each once every live remote's frozen
    /// value for it has arrived.
    void Poll();
    /// Sends one datagram to every live remote and spectator.
    void Flush();
    /// Tells every remote this peer leaves (a few datagrams), then stops sending.
    void Leave();

    /// True while a spectator waits for a snapshot (late join): the game should call
    /// OfferSnapshot after executing AdvanceFrame's requests, before the next Poll.
    bool SnapshotWanted() const noexcept;
    /// The game state saved at `frame` (e.g. WorldGameAdapter::ConfirmedSnapshot), for every
    /// spectator waiting for one: it is chunked, resent until acked, then those spectators get
    /// the confirmed inputs from `frame` on. `frame` must be <= min(ConfirmedFrame(),
    /// CurrentFrame()) of the session, and the bytes must be final (no rollback pending: call
    /// after executing the requests of AdvanceFrame). The bytes are copied.
    SnapshotOfferResult OfferSnapshot(int32_t frame, std::span<const uint8_t> state);
    /// Spectators served so far (listed and late ones).
    size_t SpectatorCount() const noexcept;
    /// The start phase's progress (see the class comment).
    RollbackPeerState State() const noexcept { return m_state; }
    /// True once remote `index` and this peer have each heard the other (false past the remotes).
    bool RemoteSynchronized(size_t index) const noexcept;
    /// True while remote `index` has been silent past interruptTimeoutMicros (and is alive).
    bool RemoteInterrupted(size_t index) const noexcept;

    /// This peer's smoothed frame advantage over the remotes minus theirs over it, halved:
    /// how many thousandths of a frame it should idle to line up (<= 0: none).
    int32_t RecommendedWaitMilli() const noexcept;
    /// Whole frames of RecommendedWaitMilli (rounded down, >= 0).
    int32_t RecommendedWaitFrames() const noexcept;
    /// True when the game should skip this tick (no AddLocalInput, no AdvanceFrame; still Poll
    /// and Flush): the recommended wait is at least one frame and the last wait is at least
    /// waitSpacingTicks ticks ago. Call once per tick.
    bool WaitThisTick();

    /// Asks every remote to use an input delay of at least `frames` (clamped to
    /// kRollbackMaxInputDelay): this peer's RollbackBudgetGuard::Delay(). Carried by an
    /// RbDelayWish in every datagram from now on.
    void AskInputDelay(uint32_t frames) noexcept;
    /// The largest input delay a live remote asked this peer for (0 when none asked): apply
    /// it, or more, with RollbackSession::SetInputDelay.
    uint32_t RemoteDelayWish() const noexcept;

    /// Every network figure of remote `index` (config order) at once: RTT, frames ahead or
    /// behind, datagrams, bytes and bit rates both ways, the rollbacks its inputs caused. All
    /// zero past the remotes.
    RollbackRemoteStats RemoteStats(size_t index) const;
    /// Smoothed RTT to remote `index` (config order), microseconds; 0 before the first sample.
    uint64_t RttMicros(size_t index) const noexcept;
    /// False once remote `index` left, timed out or was named gone by another live remote
    /// (gossip: its players are being cut), and for an index past the remotes.
    bool RemoteAlive(size_t index) const noexcept;
    /// Why remote `index` cannot play with this peer (e_none while it can; an e_incompatible
    /// event said so once). Its datagrams are refused; it times out and its players are cut.
    RollbackIncompatibility RemoteIncompatibility(size_t index) const noexcept;
    /// Spectators refused as incompatible (their hello named another version or shape).
    size_t IncompatibleSpectators() const noexcept;
    /// True once a remote named one of this peer's players gone (an e_removed event said so):
    /// the others are cutting this peer out of the match.
    bool RemovedFromMatch() const noexcept;
    /// Counters since construction.
    const RollbackPeerStats& Stats() const noexcept { return m_stats; }

private:
    struct Remote;
    struct Spectator;
    Remote* Find(PeerId peer);
    Spectator* FindSpectator(PeerId peer);
    void ForgetSilentSpectators(uint64_t now);
    void HandleSpectator(Spectator& s, const RollbackMessage& m, uint64_t now);
    // The disconnect agreement (RollbackAgreement.cpp).
    void DropRemote(Remote& r, bool tell = true);
    void OnView(Remote& r, const RbView& v);
    void OnFrozen(Remote& r, const RbFrozen& f);
    void TryAgree();
    void AddAgreement(size_t limit);
    bool InputsKept(int32_t frame) const;
    void SendSnapshot(Spectator& s, uint64_t now);
    void Handle(Remote& r, const RollbackMessage& m, uint64_t now);
    void AdvanceStart(uint64_t now);
    void SendTo(Remote& r, uint64_t now);
    void SendSpectator(Spectator& s);
    void BeginDatagram(bool hello, size_t limit);
    bool HelloAcked(const Remote& r) const noexcept;
    int32_t LocalAdvantageMilli(const Remote& r, uint64_t now) const;
    static void CountTraffic(Remote& r, uint64_t now, size_t sentBytes, size_t receivedBytes);
    static void CountSequence(Remote& r, uint8_t sequence);

    RollbackSession& m_session;
    Transport& m_transport;
    RollbackPeerConfig m_config;
    RollbackShape m_shape;
    std::vector<Remote> m_remotes;
    std::vector<Spectator> m_spectators;
    uint32_t m_lateSpectators = 0;
    std::vector<uint32_t> m_localPlayers;
    RollbackDatagramWriter m_writer;
    std::vector<Datagram> m_inbox;
    std::vector<RollbackMessage> m_messages;
    RollbackPeerStats m_stats;
    uint32_t m_ticksSinceWait = 0;
    bool m_left = false;
    RollbackPeerState m_state = RollbackPeerState::e_synchronizing;
    uint64_t m_startedAt = 0;  // transport time at construction: the start timeout runs from here
    int32_t m_delayWish = -1;  // what AskInputDelay set; -1: never asked, nothing sent
    std::array<bool, kRollbackMaxPlayers> m_removed{};  // local players a remote named gone
};

}  // namespace lockbox::net
