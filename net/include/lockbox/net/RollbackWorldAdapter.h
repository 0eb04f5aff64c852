#pragma once
/// @file
/// WorldGameAdapter: executes a RollbackSession's requests for a game whose whole
/// state is one lockbox world plus the WorldGame's user blob. SaveState keeps a rollback
/// frame of the world (b2World::SaveFrame) and the blob (Game::SaveUserState) in a ring slot and
/// reports the folded hash when asked; LoadState restores both (RestoreFrame); Advance calls
/// Game::Apply then steps once. It can also record the match's final frames into a replay
/// (Record), with no second simulation.

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/state/WorldFrame.h"
#include "lockbox/state/WorldGame.h"

namespace lockbox {
class b2World;
}
namespace lockbox::replay {
class Recorder;
}  // namespace lockbox::replay

namespace lockbox::net {

/// Where an executor hands the hash of a saved state: (frame, FoldedStateHash of the state
/// saved for that frame), called at the save.
using RollbackHashReport = std::function<void(int32_t frame, uint64_t hash)>;

/// Runs rollback requests against a world and a game. Both must outlive the adapter.
class LOCKBOX_API WorldGameAdapter {
public:
    /// `slots`: saved states kept. A match driven by a RollbackPeer needs kRollbackMaxFinalLag + 2
    /// (66, the default): a disconnect cut may roll back to the final frame, which can lag the
    /// current one by that much. A session without peers needs only its prediction window + 2.
    WorldGameAdapter(b2World& world, WorldGame& game, WorldStepSettings settings, uint32_t slots = 66);

    /// Executes `requests` in order, reporting hashes to `session` for SaveState requests that
    /// want one. False when a LoadState names a frame not kept or the restore failed (the
    /// world is then in an unknown state; the match cannot go on).
    bool Execute(RollbackSession& session, std::span<const RollbackRequest> requests);
    /// The same with the hashes handed to `reportHash` (frame, folded hash) instead of a
    /// session (a SyncTestSession drives the adapter this way). Records nothing.
    bool Execute(std::span<const RollbackRequest> requests, const RollbackHashReport& reportHash);

    /// Late join, host side: the saved state of the newest final frame F = min(session's
    /// ConfirmedFrame, CurrentFrame) as one snapshot in the lockstep late join's layout
    /// (LockstepClient::SnapshotBlob: u32 image size, the b2World::Save image, u32 user size,
    /// the Game::SaveUserState blob), for RollbackPeer::OfferSnapshot. Call after executing
    /// AdvanceFrame's requests. False when the adapter no longer (or never) saved frame F.
    bool ConfirmedSnapshot(const RollbackSession& session, int32_t& frame, std::vector<uint8_t>& out) const;
    /// Late join, spectator side: loads a ConfirmedSnapshot image into `world` and `game`.
    /// False when the bytes are not such a snapshot (b2World::Restore validates the image
    /// before it touches the world; the game is untouched then).
    static bool RestoreSnapshot(b2World& world, WorldGame& game, std::span<const uint8_t> snapshot);

    /// Records the match into `recorder` as its frames become final (docs/replay.md, "Replays
    /// of rollback matches"): each final frame's inputs (a player's bytes are zero from its
    /// disconnect cut on, as the game got them), the world hash after it, and keyframes of the
    /// confirmed state with the confirmed user state. The recorder must be made on this
    /// adapter's world and game (its settings matching WorldStepSettings) without stage hashes;
    /// it is begun at the first SaveState{0} (the seed is the world at frame 0) and finished
    /// once `frames` frames are recorded (0: only by FinishRecording). Call before the first
    /// Execute, and execute each AdvanceFrame's requests before any new input reaches the
    /// session (the documented order: Poll, AddLocalInput, AdvanceFrame, Execute, Flush), so
    /// that the frames the session calls final are simulated with their final inputs. Every
    /// peer that records `frames` frames with the same RecorderConfig writes the same bytes.
    /// False (nothing changes) when a frame was already executed or `frames` is negative.
    bool Record(replay::Recorder& recorder, int32_t frames = 0);
    /// Records every frame final so far and finishes the recording early (the END record's
    /// hash is the state after the last recorded frame). False when there is no recording, it
    /// failed, or the recorder reports a write error; true when it was finished already.
    bool FinishRecording(const RollbackSession& session);
    /// Frames recorded so far.
    int32_t RecordedFrames() const noexcept { return m_recorded; }
    /// True once the recording is finished (its `frames` reached, or FinishRecording).
    bool RecordingFinished() const noexcept { return m_recordFinished; }
    /// True when recording stopped because a final frame's state was no longer kept (more
    /// than `slots` frames between the final frame and the current one) or a visit failed.
    bool RecordingFailed() const noexcept { return m_recordFailed; }

    /// The world hash folded with the game's user state, FoldedStateHash (StateHash.h): what
    /// ReportHash gets.
    uint64_t StateHash() const;
    /// Advance requests executed inside rollbacks (after a LoadState in the same batch).
    uint64_t FramesResimulated() const noexcept { return m_resimulated; }
    /// Frame of the last Advance executed (-1 before any).
    int32_t LastAdvanced() const noexcept { return m_lastAdvanced; }

private:
    struct Slot {
        int32_t frame = -1;
        b2WorldFrame state;  ///< a rollback frame (b2World::SaveFrame), not a portable image
        std::vector<uint8_t> user;
        bool hashed = false;  ///< worldHash holds b2World::Hash of `state`
        uint64_t worldHash = 0;
        int32_t inputFrame = -1;      ///< the frame whose Advance inputs `inputs` holds
        std::vector<uint8_t> inputs;  ///< recording: the last inputs frame `inputFrame` advanced with
    };
    Slot& SlotOf(int32_t frame) { return m_slots[static_cast<size_t>(frame) % m_slots.size()]; }
    /// Brings the world to slot `s`'s state, takes what is asked, and comes back.
    bool Visit(const Slot& s, std::vector<uint8_t>* image, uint64_t* hash) const;
    bool RecordWantsHash(int32_t frame) const noexcept;
    void RecordFinal(const RollbackSession& session);
    b2World& m_world;
    WorldGame& m_game;
    WorldStepSettings m_settings;
    std::vector<Slot> m_slots;
    mutable b2WorldFrame m_scratch;  ///< the current state while ConfirmedSnapshot visits a slot
    uint64_t m_resimulated = 0;
    int32_t m_lastAdvanced = -1;
    replay::Recorder* m_recorder = nullptr;
    int32_t m_recordEnd = 0;  ///< frames to record (INT32_MAX: until FinishRecording)
    int32_t m_recorded = 0;
    bool m_recordFinished = false, m_recordFailed = false;
};

}  // namespace lockbox::net
