#pragma once
/// @file
/// Playing a replay back: restore the seed into a world, then apply each frame's
/// inputs through the game and step with the recorded settings, comparing the state hash
/// wherever the file stores one. Seeking restores the nearest keyframe and steps forward.

#include <cstdint>
#include <string>

#include "lockbox/Export.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/replay/Game.h"
#include "lockbox/replay/ReplayFile.h"

namespace lockbox::replay {

/// What Player::Verify found.
struct VerifyResult {
    bool ok = false;           ///< every stored hash and the final hash matched
    int32 frames = 0;          ///< frames simulated
    int32 hashesChecked = 0;   ///< stored hashes compared
    int32 firstBadFrame = -1;  ///< first frame whose resulting state differs (-1: none)
    uint64 expected = 0;       ///< stored hash at firstBadFrame
    uint64 actual = 0;         ///< re-simulated hash at firstBadFrame
    uint64 finalHash = 0;      ///< hash after the last frame simulated
    Error error;               ///< set when the replay could not be played at all
    std::string message;       ///< one line: "OK ..." or the first divergence
};

/// Steps a world through a parsed replay.
class LOCKBOX_API Player {
public:
    /// The file, world and game must outlive the player. The world is the game's world;
    /// it should hold the game's initial bodies (restoring in place keeps their addresses),
    /// or be empty.
    Player(const ReplayFile& file, b2World& world, Game& game);
    ~Player();
    Player(const Player&) = delete;
    Player& operator=(const Player&) = delete;

    /// Restores the seed: Frame() becomes 0.
    Error Reset();
    /// Restores a stored snapshot (the seed or a keyframe): Frame() becomes its frame.
    Error Restore(const Keyframe& keyframe);
    /// Brings the world to the state after `frame` frames (0 .. frameCount) through the
    /// nearest keyframe at or before it (or from the current frame if that is closer).
    Error Seek(int32 frame);
    /// Plays one frame (Apply, Step). Returns false at the end of the replay.
    bool Step();
    /// Frames played since the seed (the next frame to play).
    int32 Frame() const noexcept { return m_frame; }
    /// True once every recorded frame has been played.
    bool AtEnd() const noexcept { return m_frame >= m_file.frameCount; }
    /// The world being played, and the replay.
    b2World& world() noexcept { return m_world; }
    /// The world being played (read-only view).
    const b2World& world() const noexcept { return m_world; }
    /// The replay being played.
    const ReplayFile& file() const noexcept { return m_file; }

    /// Plays the whole replay from the seed, checking every stored hash; stops at the first
    /// mismatch.
    VerifyResult Verify();

    /// A hook called at every fencepost before it is hashed (nullptr: none).
    void SetStageHook(StageHook* hook) noexcept { m_hook = hook; }
    /// Hash every fencepost of each step (slower; for bisect). Off by default.
    void SetStageHashing(bool on) noexcept { m_stageHashing = on; }
    /// The fencepost hashes of the last frame played with stage hashing on.
    const uint64* LastStages() const noexcept { return m_lastStages; }
    /// The solve-phase hashes of the last frame played with stage hashing on.
    const uint64* LastSolvePhases() const noexcept { return m_lastSolve; }

    /// Snapshots restored so far (seed included).
    int32 Restores() const noexcept { return m_restores; }
    /// Frames played so far (all Step calls).
    int64_t FramesPlayed() const noexcept { return m_framesPlayed; }

private:
    const ReplayFile& m_file;
    b2World& m_world;
    Game& m_game;
    StageHook* m_hook = nullptr;
    bool m_stageHashing = false;
    uint64 m_lastStages[kStagesPerFrame] = {};
    uint64 m_lastSolve[kSolvePhasesPerFrame] = {};
    int32 m_frame = 0;
    int32 m_restores = 0;
    int64_t m_framesPlayed = 0;
    bool m_restored = false;
};

}  // namespace lockbox::replay
