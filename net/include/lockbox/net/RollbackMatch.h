#pragma once
/// @file
/// RollbackMatch (docs/rollback.md, "One object for the common case"): a peer-to-peer rollback
/// match of a game whose state is one lockbox world plus a WorldGame, assembled in one
/// place. RollbackMatchBuilder takes the players (local ones, remote ones by address or by
/// PeerId), the input size, input delay, prediction window, desync interval, start and
/// disconnect timeouts, the transport (or a UDP port to open one on, optionally behind a
/// LatencyTransport) and the world; Build() checks everything at once and names the first bad
/// setting in its error, never asserting. The match owns the RollbackSession, the
/// WorldGameAdapter, the RollbackPeer and the transports it opened; each stays reachable for
/// what the match does not cover (spectators, the budget guard, stats).
///
/// Each Tick runs the per-tick order: Poll, then (unless time sync asks this tick to wait)
/// AddLocalInput for every local player and AdvanceFrame, Execute on the adapter, then Flush.
/// Inputs come from a MatchInputSource asked for the frame each input lands on, so a scripted
/// source gives the same match on every run.
///
/// The end of a match: EndAt(N) stops adding local inputs at frame N; once frame N is final
/// here (every live peer holds every input before it, so every peer reaches the same state at
/// N), the match takes its hash of frame N, waits until every remote has sent its own hash of
/// N or has left (bounded by a timeout), then leaves (RbDisconnect: nobody waits for a
/// timeout). PlayTo does all of that in real time and returns the final hashes.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/LatencyTransport.h"
#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/Transport.h"

namespace lockbox {
class b2World;
}
namespace lockbox {
class WorldGame;
}

namespace lockbox::net {

class UdpTransport;

/// The setting a RollbackMatchBuilder refused.
enum class MatchSetting : uint8_t {
    e_none = 0,
    e_players,            ///< Players: 1 .. kRollbackMaxPlayers
    e_localPlayers,       ///< LocalPlayer: at least one, each a player once
    e_remotePlayers,      ///< RemotePlayer: each a player once, not local; every player local or remote
    e_inputBytes,         ///< InputBytes: 1 .. kRollbackMaxInputBytes
    e_inputDelay,         ///< InputDelay: 0 .. kRollbackMaxInputDelay
    e_predictionWindow,   ///< PredictionWindow: 1 .. kRollbackMaxWindow
    e_startTimeout,       ///< StartTimeoutMicros: >= 1
    e_disconnectTimeout,  ///< DisconnectTimeoutMicros: >= 2
    e_world,              ///< World: not given, or a tick rate of 0
    e_transport,          ///< UseTransport or UdpPort: exactly one; addresses need UDP
    e_latency,            ///< Latency: rates above 1000 per mille
    e_address,            ///< RemotePlayer: an address the transport cannot use
    e_port,               ///< UdpPort: the socket could not be opened
};
/// Short name of a setting ("players", "input delay", ...).
LOCKBOX_API const char* MatchSettingName(MatchSetting setting) noexcept;

/// Why Build() refused (setting e_none: it did not).
struct RollbackMatchError {
    /// The refused setting; e_none when Build() succeeded.
    MatchSetting setting = MatchSetting::e_none;
    std::string message;  ///< one line naming the setting and the bad value
    /// True when Build() did not refuse. (No conversion to bool, like replay::Error: lockbox's
    /// result types that convert to bool are true on success.)
    bool ok() const noexcept { return setting == MatchSetting::e_none; }
};

class RollbackMatch;

/// What Build() made: a match, or the error (exactly one of them).
struct RollbackMatchBuild {
    /// The match, or nullptr when `error` is set.
    std::unique_ptr<RollbackMatch> match;
    /// Why Build() refused; empty (setting e_none) when `match` is set.
    RollbackMatchError error;
};

/// Fills local `player`'s input for `frame` (`out` holds inputBytes zero bytes). Called once
/// per input the session takes; a pure function of its arguments makes the match repeatable.
using MatchInputSource = std::function<void(uint32_t player, int32_t frame, std::span<uint8_t> out)>;

/// Where a match is in its life.
enum class MatchPhase : uint8_t {
    e_synchronizing = 0,  ///< the start phase: waiting to hear every remote (RollbackPeer)
    e_running,            ///< playing
    e_ending,             ///< frame N reached: waiting until it is final and every remote has it
    e_ended,              ///< over, left; End() has the final hashes
    e_failed,             ///< the start timed out, a restore failed, or the others removed us
};
/// Short name of a phase ("running", ...).
LOCKBOX_API const char* MatchPhaseName(MatchPhase phase) noexcept;

/// One remote at the end of a match.
struct RollbackRemoteEnd {
    bool hashed = false;    ///< its hash of the last frame arrived
    uint64_t hash = 0;      ///< that hash (when hashed)
    bool left = false;      ///< it left, timed out or was cut before its hash arrived
    bool desynced = false;  ///< an e_desync event named it during the match
};

/// How a match ended (RollbackMatch::End).
struct LOCKBOX_API RollbackMatchEnd {
    bool ended = false;     ///< the match is over (phase e_ended or e_failed)
    bool finished = false;  ///< frame `frame` is final here and every remote hashed it or left
    bool timedOut = false;  ///< the wait for the remotes hit the timeout
    bool failed = false;    ///< phase e_failed (`failure` says why)
    /// Why the match failed (a one-line reason), empty unless `failed`.
    std::string failure;
    int32_t frame = -1;                      ///< the last frame (EndAt's)
    uint64_t hash = 0;                       ///< this peer's state hash at `frame` (FoldedStateHash), when finished
    std::vector<RollbackRemoteEnd> remotes;  ///< per remote, in the order they were configured
    /// True when finished, no desync was reported, and every remote that hashed the last frame
    /// has this peer's hash.
    bool Agreed() const noexcept;
};

/// Collects a match's settings; Build() checks them all.
class LOCKBOX_API RollbackMatchBuilder {
public:
    /// Number of players, 1 .. kRollbackMaxPlayers (default 2).
    RollbackMatchBuilder& Players(uint32_t players);
    /// `player` plays on this machine. Once per local player.
    RollbackMatchBuilder& LocalPlayer(uint32_t player);
    /// `player` plays on the machine at the numeric address `host` ("127.0.0.1", "::1") and
    /// UDP `port` (1 .. 65535); players at one address share one remote. Needs UdpPort (or
    /// UseTransport with a UdpTransport).
    RollbackMatchBuilder& RemotePlayer(uint32_t player, std::string host, uint16_t port);
    /// `player` plays on the machine the transport calls `peer` (SimNet, a relay, ...).
    RollbackMatchBuilder& RemotePlayer(uint32_t player, PeerId peer);
    /// Bytes of one player's input per frame, 1 .. kRollbackMaxInputBytes (default 8).
    RollbackMatchBuilder& InputBytes(uint32_t bytes);
    /// Frames between adding a local input and the frame it is applied in, from 0 to
    /// kRollbackMaxInputDelay (default 2).
    RollbackMatchBuilder& InputDelay(uint32_t frames);
    /// Frames the match may run ahead on predictions, 1 .. kRollbackMaxWindow (default 8).
    RollbackMatchBuilder& PredictionWindow(uint32_t frames);
    /// Compare state hashes every this many frames (default 10; 0: never, and EndAt refuses).
    RollbackMatchBuilder& DesyncInterval(uint32_t frames);
    /// Longest start phase, microseconds, >= 1 (default 10 s): remotes not heard by then are
    /// named in e_startTimeout events and the match fails.
    RollbackMatchBuilder& StartTimeoutMicros(uint64_t micros);
    /// Silence after which a remote's players leave, microseconds, >= 2 (default 2 s).
    RollbackMatchBuilder& DisconnectTimeoutMicros(uint64_t micros);
    /// Same on every peer of the match (default 1).
    RollbackMatchBuilder& MatchId(uint32_t id);
    /// Runs on `transport`, which must outlive the match.
    RollbackMatchBuilder& UseTransport(Transport& transport);
    /// Opens a UdpTransport bound to `bindHost` (numeric) and `port` (0: ephemeral) at Build.
    RollbackMatchBuilder& UdpPort(uint16_t port, std::string bindHost = "127.0.0.1");
    /// Delays what the match receives through a LatencyTransport (rates <= 1000 per mille).
    RollbackMatchBuilder& Latency(const LatencyProfile& profile, uint64_t seed);
    /// The game: `world` and `game` (both must outlive the match, the world at its start) and
    /// how to step (a tick rate >= 1; it is also the match's tick rate).
    RollbackMatchBuilder& World(b2World& world, WorldGame& game, WorldStepSettings step);

    /// The match, or the first bad setting (checked in the order of MatchSetting; the socket
    /// is opened last, so nothing is opened for a bad configuration).
    RollbackMatchBuild Build() const;

private:
    struct Remote {
        uint32_t player = 0;
        std::string host;
        uint16_t port = 0;
        PeerId peer = kNoPeer;  // kNoPeer: by address
    };
    uint32_t m_players = 2;
    std::vector<uint32_t> m_local;
    std::vector<Remote> m_remotes;
    uint32_t m_inputBytes = 8;
    uint32_t m_inputDelay = 2;
    uint32_t m_window = 8;
    uint32_t m_desyncInterval = 10;
    uint64_t m_startTimeout = 10000000;
    uint64_t m_disconnectTimeout = 2000000;
    uint32_t m_matchId = 1;
    Transport* m_transport = nullptr;
    bool m_udp = false;
    uint16_t m_udpPort = 0;
    std::string m_bindHost;
    bool m_latency = false;
    LatencyProfile m_latencyProfile;
    uint64_t m_latencySeed = 0;
    b2World* m_world = nullptr;
    WorldGame* m_game = nullptr;
    WorldStepSettings m_step;
};

/// A peer-to-peer rollback match of one lockbox world and a WorldGame: owns the session, the
/// world adapter, the peer and the transports it opened, runs the per-tick order in Tick and ends
/// the match cleanly at a frame every peer agrees on (see the file comment). Made by
/// RollbackMatchBuilder.
class LOCKBOX_API RollbackMatch {
public:
    ~RollbackMatch();
    RollbackMatch(const RollbackMatch&) = delete;
    RollbackMatch& operator=(const RollbackMatch&) = delete;

    /// One tick: Poll; then, unless time sync skips this tick, AddLocalInput for every local
    /// player (input from `inputs` for the frame it lands on; none at or past EndAt's frame)
    /// and AdvanceFrame, executed on the adapter; Flush. Then the end-of-match checks. Call at
    /// the tick rate (TickMicros apart on the transport's clock). Returns the phase.
    MatchPhase Tick(const MatchInputSource& inputs);
    /// Ends the match at `frame` (the state after `frame` steps): no local input is added for
    /// it or later; once it is final here, its hash is taken, and the match waits up to
    /// `timeoutMicros` for every remote's hash of it (or its leaving), then leaves. False (no
    /// change) when desync detection is off or `frame` is not a multiple of the desync interval
    /// (no peer would send its hash), or a local input at or past `frame` was already added.
    bool EndAt(int32_t frame, uint64_t timeoutMicros);
    /// Plays to `frame` in real time: EndAt(frame, timeoutMicros), then Tick every TickMicros
    /// (sleeping between ticks) until the match is over. For real sockets; on SimNet call
    /// EndAt and Tick yourself, moving the virtual clock between ticks. Returns End(). When
    /// EndAt refuses, returns at once with failed set.
    RollbackMatchEnd PlayTo(int32_t frame, const MatchInputSource& inputs, uint64_t timeoutMicros);
    /// Leaves now (RbDisconnect to every remote); the phase becomes e_ended (not finished).
    void Leave();

    /// Where the match is (synchronizing, running, ending, ended, failed).
    MatchPhase Phase() const noexcept { return m_phase; }
    /// The end so far (complete once `ended`).
    const RollbackMatchEnd& End() const noexcept { return m_end; }
    /// Events since the last call, oldest first (the session's, drained by Tick).
    std::vector<RollbackEvent> TakeEvents();
    /// Microseconds between two ticks (1,000,000 / tick rate).
    uint64_t TickMicros() const noexcept;
    /// The folded state hash of the world and game now (FoldedStateHash).
    uint64_t StateHash() const;

    /// The parts the match owns, for what it does not cover itself (spectators, the budget guard,
    /// stats); they live as long as the match.
    ///@{
    RollbackSession& Session() noexcept { return *m_session; }
    RollbackPeer& Peer() noexcept { return *m_peer; }
    WorldGameAdapter& Adapter() noexcept { return *m_adapter; }
    ///@}
    /// The transport the peer runs on (the LatencyTransport when there is one).
    Transport& Net() noexcept { return *m_net; }
    /// The UdpTransport the match opened (UdpPort), else nullptr.
    UdpTransport* Udp() noexcept { return m_udp.get(); }

private:
    friend class RollbackMatchBuilder;
    RollbackMatch() = default;
    void Fail(std::string why);
    void CheckEnd();

    std::unique_ptr<UdpTransport> m_udp;
    std::unique_ptr<LatencyTransport> m_latency;
    Transport* m_net = nullptr;
    std::unique_ptr<RollbackSession> m_session;
    std::unique_ptr<WorldGameAdapter> m_adapter;
    std::unique_ptr<RollbackPeer> m_peer;
    b2World* m_world = nullptr;
    WorldGame* m_game = nullptr;
    uint32_t m_tickRate = 60;
    std::vector<uint32_t> m_local;
    std::vector<std::string> m_remoteNames;  // "host:port" or "peer N", per remote
    std::vector<uint8_t> m_input;
    std::vector<RollbackEvent> m_events;
    MatchPhase m_phase = MatchPhase::e_synchronizing;
    RollbackMatchEnd m_end;
    int32_t m_endFrame = -1;
    uint64_t m_endTimeout = 0;
    uint64_t m_endDeadline = 0;  // set when frame m_endFrame is reached here
    bool m_reached = false;
    bool m_hashed = false;  // m_end.hash is taken
    uint32_t m_flushesAfterHash = 0;
};

}  // namespace lockbox::net
