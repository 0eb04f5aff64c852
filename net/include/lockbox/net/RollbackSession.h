#pragma once
/// @file
/// The rollback session core (docs/rollback.md): inputs in, requests out. The game
/// adds its local inputs, calls AdvanceFrame once per tick and executes the requests it gets
/// back, in order: SaveState (save the current state as frame f), LoadState (restore frame f)
/// and Advance (apply these inputs, step once). The session never calls into the game, so any
/// game state (a lockbox world, a user blob, anything else) rolls back the way the game wants.
///
/// Frames: the state "at frame f" is the state before frame f's inputs are applied (after f
/// steps from the start); Advance{f} moves it to frame f + 1. Frame 0 is the start.
///
/// Finality: a frame is final (its hash compared, its inputs handed to spectators) once this
/// session holds every input before it and, when remote peers report their views
/// (SetPeerView), once every live remote peer holds them too. A leaving player is first
/// frozen (FreezePlayer), then cut at a frame every survivor agrees on (ReportFrozen,
/// CompleteDisconnect); that cut is never below a final frame (docs/rollback.md,
/// "Disconnects").
///
/// This class knows nothing about the network: remote inputs and hashes are handed to it
/// (AddRemoteInput, AddRemoteHash), by RollbackPeer (RollbackPeer.h) over a Transport or by a
/// test directly. It predicts missing remote inputs, rolls back when a prediction was wrong,
/// waits at the prediction window's edge (never dropping an input), and compares state hashes
/// of frames whose inputs were all confirmed once no rollback is pending.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "lockbox/Export.h"

namespace lockbox::net {

/// Largest player count of a rollback session.
inline constexpr uint32_t kRollbackMaxPlayers = 8;
/// Largest input per player per frame, in bytes.
inline constexpr uint32_t kRollbackMaxInputBytes = 64;
/// Largest prediction window, in frames.
inline constexpr uint32_t kRollbackMaxWindow = 64;
/// Largest input delay, in frames.
inline constexpr uint32_t kRollbackMaxInputDelay = 16;
/// Largest distance, in frames, between the current frame and the final one
/// (ConfirmedFrame): AdvanceFrame waits rather than go further, so a game that keeps the
/// states of the last kRollbackMaxFinalLag + 2 frames (WorldGameAdapter's default 66) can
/// always load what a disconnect cut asks for.
inline constexpr uint32_t kRollbackMaxFinalLag = 64;

/// How one player's input of one Advance came to be.
enum class InputStatus : uint8_t {
    e_confirmed = 0,     ///< the player's real input
    e_predicted = 1,     ///< guessed; a rollback follows if the guess was wrong
    e_disconnected = 2,  ///< the player left; all zero bytes
};

/// Save the state as it is now as the state at `frame`. When `wantHash` is set the game must
/// hand the state's hash to ReportHash(frame, hash) (desync detection); otherwise it may.
struct SaveState {
    /// The frame the state is saved as (the state before that frame's inputs), >= 0.
    int32_t frame = 0;
    /// True when the session needs this state's hash (ReportHash) for desync detection.
    bool wantHash = false;
};
/// Replace the state with the one saved at `frame` (always one the session asked to save).
struct LoadState {
    /// The frame to restore, one the session asked to save and still keeps.
    int32_t frame = 0;
};
/// Apply frame `frame`'s inputs and step once.
struct AdvanceRequest {
    /// The frame whose inputs to apply; the step moves the state to frame + 1.
    int32_t frame = 0;
    std::vector<uint8_t> inputs;      ///< players * inputBytes bytes, player 0 first
    std::vector<InputStatus> status;  ///< one per player
};
/// One thing AdvanceFrame asks the game to do.
using RollbackRequest = std::variant<SaveState, LoadState, AdvanceRequest>;

/// Why a remote peer, host or spectator cannot play this match with us (the first reason
/// found; a datagram with any of them is refused whole).
enum class RollbackIncompatibility : uint8_t {
    e_none = 0,
    e_protocolVersion,     ///< its datagrams carry another kRollbackProtocolVersion
    e_matchId,             ///< it was configured with another match id
    e_determinismVersion,  ///< another lockbox b2_determinismVersion: its states would diverge
    e_sessionShape,        ///< another player count or input size
};
/// Short name of a reason ("determinism version", ...).
LOCKBOX_API const char* RollbackIncompatibilityName(RollbackIncompatibility why) noexcept;

/// Something the game should know about (drained by TakeEvents).
struct RollbackEvent {
    /// What happened; the fields below say to whom and when.
    enum class Kind : uint8_t {
        e_desync = 0,        ///< a remote peer's hash of `frame` differs from ours (once per peer)
        e_disconnected = 1,  ///< `player` left; its input is zero from `frame` (the cut) on
        e_waiting = 2,       ///< AdvanceFrame stalled at the window edge from `frame` (once per stall)
        /// Nothing arrived from remote peer `player` (its RollbackPeer config index) for
        /// interruptTimeoutMicros; `frame` is the current frame. Once per silence.
        e_interrupted = 3,
        /// Remote peer `player` is heard again after an e_interrupted, before the disconnect
        /// timeout; `frame` is the current frame.
        e_resumed = 4,
        /// Remote peer `player` cannot play this match with us (`incompatibility` says why);
        /// its datagrams are refused from now on, so it times out like a silent peer (and its
        /// players are cut). Once per remote; `frame` is the current frame.
        e_incompatible = 5,
        /// The other peers consider this peer gone: a remote announced local player `player`
        /// frozen at `frame` (it timed this peer out, or heard so from another). They will cut
        /// it; this peer is out of the match and should end it. Once per local player.
        e_removed = 6,
        /// Start phase (RollbackPeer): remote peer `player` is heard for the first time; the
        /// round trip with it is under way. `frame` is 0.
        e_synchronizing = 7,
        /// Start phase: remote peer `player` and this peer have each heard the other (a full
        /// round trip). `frame` is 0.
        e_synchronized = 8,
        /// Start phase over: every remote peer is synchronized and AdvanceFrame advances from
        /// now on; the disconnect and interruption timers run from here. `frame` is 0.
        e_running = 9,
        /// The start timeout expired before remote peer `player` was synchronized: one event
        /// per missing remote, then the peer leaves and AdvanceFrame never advances (the match
        /// did not start; RollbackPeer::State() is e_startFailed). `frame` is 0.
        e_startTimeout = 10,
    };
    /// What happened.
    Kind kind = Kind::e_desync;
    /// The frame concerned (see each kind; 0 where the kind names none).
    int32_t frame = 0;
    /// The player (e_disconnected, e_removed: a local one) or the remote peer tag (e_desync,
    /// e_interrupted, e_resumed, e_incompatible, e_synchronizing, e_synchronized,
    /// e_startTimeout; 0 for e_running).
    uint32_t player = 0;
    uint64_t localHash = 0;                                                     ///< desync: ours
    uint64_t remoteHash = 0;                                                    ///< desync: theirs
    RollbackIncompatibility incompatibility = RollbackIncompatibility::e_none;  ///< e_incompatible: why
};

/// Guesses a remote input: `last` is the player's latest confirmed input before `frame` (all
/// zeros when there is none), `lastFrame` its frame (-1 when none); fill `out` (inputBytes).
/// Must be a pure function of its arguments: every peer may predict differently, but the
/// same session must get the same guess for the same arguments.
using InputPredictor = std::function<void(uint32_t player, int32_t frame, std::span<const uint8_t> last,
                                          int32_t lastFrame, std::span<uint8_t> out)>;

/// Whether local `next` may stand as a repeat of the player's `previous` input (the one
/// queued last) while a lowered input delay catches up (RollbackSession::SetInputDelay): true
/// drops `next`, and the frame it would have filled is paid back. The default takes equal
/// bytes only, so nothing is ever dropped; but a player whose input changes every tick (an
/// analog stick) then never pays back a lowering. A game with analog input can accept, for
/// example, "the same buttons": one tick's stick sample is dropped (the next one supersedes
/// it) and no button edge is lost. Called only during such a catch-up.
using InputRepeatTest =
    std::function<bool(uint32_t player, std::span<const uint8_t> previous, std::span<const uint8_t> next)>;

/// What AddLocalInput / AddRemoteInput said.
enum class InputResult : uint8_t {
    e_ok = 0,
    e_badPlayer,     ///< no such player, or not local (local call) / local (remote call)
    e_badSize,       ///< not inputBytes bytes
    e_alreadyAdded,  ///< local: this tick's input is queued already (the session is waiting)
    e_duplicate,     ///< remote: this frame arrived before (ignored, not an error)
    e_gap,           ///< remote: an earlier frame is missing (ignored; the sender resends)
    e_disconnected,  ///< the player left
    e_tooFarAhead,   ///< remote: beyond what the window can ever need (ignored)
};

/// Running figures.
struct RollbackStats {
    uint64_t framesAdvanced = 0;     ///< Advance requests for new frames
    uint64_t rollbacks = 0;          ///< LoadState requests
    uint64_t framesResimulated = 0;  ///< Advance requests inside rollbacks
    uint32_t deepestRollback = 0;    ///< frames re-simulated by the deepest rollback
    uint64_t waits = 0;              ///< AdvanceFrame calls that could not advance
    uint64_t predictedInputs = 0;    ///< player inputs predicted in new frames
    uint64_t hashesCompared = 0;     ///< local/remote hash pairs compared
    /// ReportFrozen values below the final frame, ignored (only a peer that died before
    /// others heard it can cause one; see docs/rollback.md, "Disconnects").
    uint64_t frozenReportsIgnored = 0;
    /// Local inputs repeated into the frames a raised input delay opened (SetInputDelay).
    uint64_t inputsRepeated = 0;
    /// Local inputs taken as a repeat of the previous one while a lowered input delay
    /// catches up (SetInputDelay): the frame they would have filled is not added.
    uint64_t inputsAbsorbed = 0;
};

/// Settings checked by RollbackSessionBuilder.
struct RollbackConfig {
    uint32_t players = 2;                ///< 1 .. kRollbackMaxPlayers
    uint32_t inputBytes = 8;             ///< 1 .. kRollbackMaxInputBytes
    std::vector<uint32_t> localPlayers;  ///< players whose inputs this machine adds
    uint32_t predictionWindow = 8;       ///< frames past HeldFrame(), 1 .. kRollbackMaxWindow
    uint32_t inputDelay = 0;             ///< frames, 0 .. kRollbackMaxInputDelay
    uint32_t checkDistance = 8;          ///< sync test: frames re-simulated per check (>= 1)
    uint32_t desyncInterval = 10;        ///< compare hashes of frames f with f % interval == 0; 0: never
    InputPredictor predictor;            ///< empty: repeat the last confirmed input
    InputRepeatTest repeatTest;          ///< empty: equal bytes are a repeat
};

class RollbackSession;

/// Collects and checks the settings of a session.
class LOCKBOX_API RollbackSessionBuilder {
public:
    /// Number of players, 1 .. kRollbackMaxPlayers (default 2).
    RollbackSessionBuilder& Players(uint32_t players) {
        m_config.players = players;
        return *this;
    }
    /// Bytes of one player's input per frame, 1 .. kRollbackMaxInputBytes (default 8).
    RollbackSessionBuilder& InputBytes(uint32_t bytes) {
        m_config.inputBytes = bytes;
        return *this;
    }
    /// Marks `player` as local (its inputs come from AddLocalInput). Call once per local player.
    RollbackSessionBuilder& LocalPlayer(uint32_t player) {
        m_config.localPlayers.push_back(player);
        return *this;
    }
    /// Frames the session may run ahead of HeldFrame(), the first frame it lacks an input of (default 8).
    RollbackSessionBuilder& PredictionWindow(uint32_t frames) {
        m_config.predictionWindow = frames;
        return *this;
    }
    /// Frames between adding a local input and the frame it is applied in (default 0).
    RollbackSessionBuilder& InputDelay(uint32_t frames) {
        m_config.inputDelay = frames;
        return *this;
    }
    /// Sync test check distance (default 8).
    RollbackSessionBuilder& CheckDistance(uint32_t frames) {
        m_config.checkDistance = frames;
        return *this;
    }
    /// Hash comparison interval in frames (default 10; 0 turns desync detection off).
    RollbackSessionBuilder& DesyncInterval(uint32_t frames) {
        m_config.desyncInterval = frames;
        return *this;
    }
    /// A custom predictor (default: repeat the last confirmed input).
    RollbackSessionBuilder& Predictor(InputPredictor predictor) {
        m_config.predictor = std::move(predictor);
        return *this;
    }
    /// What counts as a repeated local input while a lowered input delay catches up (default:
    /// equal bytes). See InputRepeatTest.
    RollbackSessionBuilder& RepeatTest(InputRepeatTest test) {
        m_config.repeatTest = std::move(test);
        return *this;
    }

    /// Empty when the settings are valid, else a one-line reason.
    std::string_view Check() const noexcept;
    /// A new session; nullptr when Check() is not empty.
    std::unique_ptr<RollbackSession> Build() const;
    /// The settings collected so far.
    const RollbackConfig& Config() const noexcept { return m_config; }

private:
    RollbackConfig m_config;
};

/// The rollback session core: takes local and remote inputs, predicts missing remote ones and
/// returns the save, load and advance requests that keep the game's state correct (see the file
/// comment). Network-free; build one with RollbackSessionBuilder, carry it over a Transport with
/// RollbackPeer.
class LOCKBOX_API RollbackSession {
public:
    /// Use RollbackSessionBuilder; `config` must pass its Check.
    explicit RollbackSession(RollbackConfig config);
    ~RollbackSession();
    RollbackSession(const RollbackSession&) = delete;
    RollbackSession& operator=(const RollbackSession&) = delete;

    /// Queues local `player`'s input for frame CurrentFrame() + inputDelay. Once per tick per
    /// local player; e_alreadyAdded while the session waits at the window edge (that tick's
    /// input is not taken: the previous one is still queued). While a lowered input delay
    /// catches up (SetInputDelay), an input that repeats the player's previous one (equal
    /// bytes, or the builder's RepeatTest) fills no frame (e_ok); another is queued as usual.
    InputResult AddLocalInput(uint32_t player, std::span<const uint8_t> input);

    /// Changes the input delay during the match (0 .. kRollbackMaxInputDelay; false, and no
    /// change, beyond). Peers need not agree: each only changes which frame its own local
    /// inputs land on, and nothing a player meant is lost. Raising by k repeats every local
    /// player's latest input into the k frames that open (what a remote peer would have
    /// predicted anyway; counted in inputsRepeated). Lowering by k takes effect as the player
    /// repeats itself: each of its next k inputs that equals its previous one is absorbed
    /// (inputsAbsorbed), so a held input is held one frame shorter and no press or release is
    /// dropped; an input that keeps changing keeps the longer delay until it repeats (or until
    /// the builder's RepeatTest accepts it, for analog input).
    /// RollbackBudgetGuard (RollbackBudgetGuard.h) chooses the delay from measured costs.
    bool SetInputDelay(uint32_t frames);
    /// The input delay asked for (the builder's, or the latest SetInputDelay).
    uint32_t InputDelay() const noexcept;

    /// The requests of one tick, to be executed in order before the next call: any rollback
    /// first (LoadState, then Advance + SaveState for every frame up to the current one),
    /// then one new frame (Advance, SaveState) unless the session must wait: at the window's
    /// edge, while a local player's input for the frame is missing, or while the start phase
    /// holds it (SetSynchronizing). The very first call starts with SaveState{0}.
    std::vector<RollbackRequest> AdvanceFrame();

    /// The game's hash of the state it saved for `frame` (after a SaveState request). Ignored
    /// for a frame the session no longer keeps.
    void ReportHash(int32_t frame, uint64_t hash);

    /// A remote player's input for `frame` (from the network). Frames must arrive in order per
    /// player; a duplicate or out-of-order frame is ignored (the sender resends).
    InputResult AddRemoteInput(uint32_t player, int32_t frame, std::span<const uint8_t> input);
    /// A remote peer's final hash of `frame` (peerTag names the peer in desync events).
    void AddRemoteHash(uint32_t peerTag, int32_t frame, uint64_t hash);
    /// `player` left: its input is zero, with status disconnected, from the first frame not
    /// received yet (or the smallest ReportFrozen value, if any came). Frames already
    /// simulated with other inputs are rolled back; an e_disconnected event names the cut.
    /// For a session without peers or with one remote peer; RollbackPeer uses the three calls
    /// below to agree on the cut with 3+ peers. No effect on a player already cut.
    void DisconnectPlayer(uint32_t player);
    /// Starts `player`'s departure: no input of it is taken any more (AddRemoteInput and
    /// AddLocalInput say e_disconnected), its inputs past the frozen frame are predicted (so
    /// the window may stall), and frames from the frozen frame on do not become final until
    /// the cut is set. Returns the frozen frame (ReceivedFrame at the first call; later calls
    /// return the same), or -1 for no such player or a player already cut.
    int32_t FreezePlayer(uint32_t player);
    /// Another peer froze `player` at `frame` (its own received frame). Lowers the cut to come
    /// to the smallest value known. `player` must be frozen here first. False (ignored) for a
    /// player not frozen or already cut, a negative frame, or a frame below ConfirmedFrame():
    /// a cut there would change final frames (counted in frozenReportsIgnored).
    bool ReportFrozen(uint32_t player, int32_t frame);
    /// Sets the agreed cut of frozen `player`: the smallest of its frozen frame and every
    /// ReportFrozen value. Input is zero with status e_disconnected from the cut on, frames
    /// at or past it simulated otherwise are rolled back, and one e_disconnected event names
    /// the cut. Returns the cut, or -1 when `player` is not frozen or already cut.
    int32_t CompleteDisconnect(uint32_t player);
    /// What a live remote peer `peerTag` holds: `received[p]` is the first frame of player p
    /// it lacks (players entries, each >= 0; any other size is ignored). Kept per peer as the
    /// largest value heard, so a reordered report never lowers it. Once a peer has a view, no
    /// frame at or past its view of a player still in the match becomes final.
    void SetPeerView(uint32_t peerTag, std::span<const int32_t> received);
    /// Remote peer `peerTag` is no longer live: its view stops limiting finality.
    void DropPeer(uint32_t peerTag);
    /// Queues a connection event about remote peer `peerTag` at the current frame: one of
    /// e_interrupted, e_resumed and the start phase's e_synchronizing, e_synchronized,
    /// e_running, e_startTimeout (called by RollbackPeer; other kinds are ignored: the
    /// session raises those itself).
    void RaiseConnectionEvent(RollbackEvent::Kind kind, uint32_t peerTag);
    /// While true, AdvanceFrame asks for nothing but the first SaveState{0}: the match has not
    /// started (RollbackPeer holds it until every remote peer is synchronized). Local inputs
    /// queue as at the window edge (the first is taken, later ones say e_alreadyAdded), remote
    /// inputs are stored, and these calls do not count in RollbackStats::waits.
    void SetSynchronizing(bool synchronizing) noexcept;
    /// True while SetSynchronizing(true) holds the start.
    bool Synchronizing() const noexcept;
    /// Queues an e_incompatible event about remote peer `peerTag` (called by RollbackPeer).
    void RaiseIncompatible(uint32_t peerTag, RollbackIncompatibility why);
    /// Queues an e_removed event: local player `player` named frozen at `frame` by a remote
    /// (called by RollbackPeer, once per player).
    void RaiseRemoved(uint32_t player, int32_t frame);

    /// The frame the next Advance will step (the number of frames simulated).
    int32_t CurrentFrame() const noexcept;
    /// The first frame that is not final. Every frame before it is final: its inputs are held
    /// here and, as far as their views say, by every live remote peer, and no disconnect cut
    /// can fall below it. Its hash is compared and its inputs go to spectators.
    int32_t ConfirmedFrame() const noexcept;
    /// First frame whose inputs this session does not all hold (a frozen player counts with
    /// its frozen frame); the prediction window is measured from it. >= ConfirmedFrame().
    int32_t HeldFrame() const noexcept;
    /// Frames of `player`'s inputs received or added: every frame before this one is known.
    /// Frozen: the frozen frame; cut: the cut (inputs from the cut on are zeros).
    int32_t ReceivedFrame(uint32_t player) const noexcept;
    /// The frame `player` was frozen at (its ReceivedFrame then), -1 when never frozen; stays
    /// after the cut.
    int32_t FrozenFrame(uint32_t player) const noexcept;
    /// The agreed cut of `player` (first frame of zeros), -1 while it is not cut.
    int32_t CutFrame(uint32_t player) const noexcept;
    /// A confirmed input of `player` at `frame` (< ReceivedFrame(player) and not older than
    /// the kept history); empty span when not kept.
    std::span<const uint8_t> ConfirmedInput(uint32_t player, int32_t frame) const noexcept;
    /// The latest final local hashes (frame, hash), oldest first, at most 8.
    const std::deque<std::pair<int32_t, uint64_t>>& FinalHashes() const noexcept;
    /// Remote inputs of `player` that differed from what a past Advance used for their frame
    /// (a wrong prediction: each asks for a rollback to its frame, or joins one). 0 for a
    /// local player or no such player.
    uint64_t MispredictedInputs(uint32_t player) const noexcept;
    /// True for a player whose inputs this machine adds.
    bool IsLocal(uint32_t player) const noexcept;
    /// True once `player` is cut (DisconnectPlayer or CompleteDisconnect), not while frozen.
    bool IsDisconnected(uint32_t player) const noexcept;
    /// Events since the last call, oldest first.
    std::vector<RollbackEvent> TakeEvents();
    /// Running figures since construction.
    const RollbackStats& Stats() const noexcept;
    /// The settings the session was built with.
    const RollbackConfig& Config() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace lockbox::net
