#pragma once
/// @file
/// The lockstep client (docs/net.md "Sessions"): joins a LockstepServer, sends its
/// player's inputs, and steps its world one frame at a time, only when every player's input
/// for that frame has been confirmed by the server. Before each step it calls the game's
/// Apply(world, frame, inputs) with all players' inputs of the frame (playerCount * inputBytes
/// bytes, slot 0 first): the WorldGame contract, so a replay::SceneGame plugs in directly.
///
/// Input delay: a local input submitted now is for frame (local tick + input delay). Fixed
/// (ClientConfig::inputDelay or the server's), or automatic: from the handshake's RTT samples,
///   delay = clamp(ceil((rttMax + (rttMax - rttMin)) / tick) + 1, 1, maxAutoDelay)
/// where rttMax/rttMin are the largest and smallest of kHandshakePings samples and tick is
/// 1e6 / tickRate microseconds: the relay path is a full round trip, and the spread of the
/// samples is added once more as the jitter margin. The delay is fixed for the session.
///
/// Late join and reconnect: a client that gets a late-join Welcome receives a snapshot of a
/// confirmed frame (b2World::Save plus the game's SaveUserState), restores it, fast-forwards
/// through the confirmed inputs, and reports hashes; the server admits it (Admit) once one of
/// them matches the others'. Until then it sends no inputs (its slot plays empty input).

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

/// RTT samples taken before the first input in automatic delay mode.
inline constexpr uint32_t kHandshakePings = 5;

/// Client settings.
struct ClientConfig {
    uint8_t requestedSlot = kAnySlot;  ///< a slot, or kAnySlot
    uint32_t reconnectToken = 0;       ///< a previous session's Token() to take its slot back; 0: new
    /// Input delay in frames: -1 follows the server (its fixed delay, or automatic when it has
    /// none); 0: automatic; 1 .. 255: fixed.
    int32_t inputDelay = -1;
    uint32_t maxAutoDelay = 30;             ///< cap of the automatic delay, frames
    uint64_t interruptMicros = 500'000;     ///< server silence before an `interrupted` event
    uint64_t disconnectMicros = 2'000'000;  ///< server silence before giving up (`disconnected`)
    uint64_t helloRetryMicros = 200'000;    ///< Hello resend period; no answer in 5 x disconnectMicros: `disconnected`
    uint64_t keepAliveMicros = 200'000;     ///< longest gap between datagrams to the server
    uint64_t pingMicros = 250'000;          ///< RTT probe period once running
    uint32_t maxCatchUpFrames = 16;         ///< frames stepped per Update at most
    uint32_t velocityIterations = 8;        ///< step settings (match the scene's)
    /// Step settings: position iterations per step (match the scene's).
    uint32_t positionIterations = 3;
    /// Send a HashReport every hashInterval-th frame (the default). False: the client reports
    /// no hashes, so the server never compares its state (no desync is ever seen for it) and a
    /// late join or reconnect, which is admitted on a matching hash, never completes. For a
    /// client whose world is not the match's, such as a load generator's.
    bool reportHashes = true;
};

/// Something the caller may want to know about.
struct ClientEvent {
    /// What happened; frame and reason are set where the kind says.
    enum class Kind : uint8_t {
        e_connected,       ///< Welcome received (frame: the start frame)
        e_rejected,        ///< the server refused us (reason)
        e_running,         ///< inputs may be submitted from now on (frame: first input frame)
        e_snapshotLoaded,  ///< late join: the snapshot of `frame` was restored
        e_admitted,        ///< late join: hash matched, inputs from `frame`
        e_interrupted,     ///< the server went silent for interruptMicros
        e_resumed,         ///< it was heard again
        e_disconnected,    ///< the session ended (reason: timeout, server closing, ...)
        e_desync,          ///< the server saw diverging hashes at `frame`
    };
    /// What happened.
    Kind kind = Kind::e_connected;
    /// The frame concerned (-1 when none): the start frame for e_connected, the diverging one for
    /// e_desync.
    int32_t frame = -1;
    /// Why the session ended or was refused (e_disconnected, e_rejected), else e_none.
    RejectReason reason = RejectReason::e_none;
};

/// The client's view of its session.
enum class ClientState : uint8_t {
    e_connecting,  ///< sending Hello
    e_syncing,     ///< Welcome received, measuring RTT (automatic delay)
    e_loading,     ///< late join: receiving the snapshot
    e_catchingUp,  ///< late join: stepping confirmed frames, waiting for Admit
    e_running,     ///< sending inputs and stepping
    e_closed,      ///< rejected, disconnected or left
};

/// Called after each confirmed frame is stepped: the frame, its inputs (all players), the
/// world hash after it (b2World::Hash) and the world (the state after the frame). Fits
/// replay::Recorder::AppendConfirmed(inputs, worldHash, &world).
using ConfirmedFrameHook =
    std::function<void(int32_t frame, std::span<const uint8_t> inputs, uint64_t worldHash, const b2World& world)>;

/// One player's end of a lockstep match: joins a LockstepServer, sends its local inputs and steps
/// the world through confirmed frames only, so every client's world goes through the same states
/// (see the file comment). Non-blocking; call Update often.
class LOCKBOX_API LockstepClient {
public:
    /// `server` is the server's PeerId on `transport`. The transport, world and game must
    /// outlive the client; the world must be in the match's start state (or any state, for a
    /// late joiner: the snapshot replaces it).
    LockstepClient(Transport& transport, PeerId server, ClientConfig config, b2World& world, WorldGame& game);
    ~LockstepClient();
    LockstepClient(const LockstepClient&) = delete;
    LockstepClient& operator=(const LockstepClient&) = delete;

    /// Polls, handles, steps confirmed frames (at most maxCatchUpFrames), reports hashes and
    /// sends. Never blocks.
    void Update();

    /// True when the local clock and the input delay want the next local input now (running,
    /// and the input frame is within the delay window of the simulation).
    bool WantsInput() const;
    /// Queues the local player's input for NextInputFrame(); `input` must hold inputBytes
    /// bytes (shorter is zero-padded, longer is cut). False (nothing queued) when not running
    /// or the input frame is beyond frame + inputDelay.
    bool SubmitLocalInput(std::span<const uint8_t> input);
    /// The frame the next submitted input is for.
    int32_t NextInputFrame() const noexcept;

    /// Leaves the session: sends Disconnect (best effort) and closes.
    void Leave();

    /// Sets a hook called after every stepped frame (replaces any previous one).
    void SetConfirmedFrameHook(ConfirmedFrameHook hook);

    /// Events since the last call, oldest first.
    std::vector<ClientEvent> TakeEvents();

    /// Where the client is in its session (connecting, syncing, loading, catching up, running,
    /// closed).
    ClientState State() const noexcept;
    /// Next frame to step: the world holds the state after every frame before it.
    int32_t Frame() const noexcept;
    /// Our slot (-1 before a Welcome).
    int32_t Slot() const noexcept;
    /// Session token (0 before a Welcome); pass it as reconnectToken to take the slot back.
    uint32_t Token() const noexcept;
    /// Input delay in frames (0 before it is known).
    uint32_t InputDelay() const noexcept;
    /// Smoothed RTT to the server, microseconds (0 before a sample).
    uint64_t RttMicros() const noexcept;
    /// RTT variation (mean deviation), microseconds.
    uint64_t JitterMicros() const noexcept;
    /// State hash after the last stepped frame (world hash folded with the game's user state),
    /// 0 before any step.
    uint64_t LastHash() const noexcept;
    /// The session shape (zero before a Welcome).
    SessionShape Shape() const noexcept;
    /// Datagrams refused by the decoder, by DecodeError.
    const DecodeErrorCounts& Malformed() const noexcept;

    /// The state hash a client reports: b2World::Hash folded with the user state bytes.
    static uint64_t StateHash(const b2World& world, const WorldGame& game);
    /// Snapshot blob layout: u32 world image size, the image, u32 user state size, the bytes
    /// (little-endian). Used by late join; exposed for tests and tools.
    static std::vector<uint8_t> SnapshotBlob(const b2World& world, const WorldGame& game);
    /// Restores a blob into world and game; false (nothing changed in the world) when malformed.
    static bool LoadSnapshotBlob(std::span<const uint8_t> blob, b2World& world, WorldGame& game);

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace lockbox::net
