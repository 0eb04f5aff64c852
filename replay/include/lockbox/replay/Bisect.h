#pragma once
/// @file
/// Finding the first divergent frame of a replay quickly (`lockbox_replay bisect`):
/// a binary search over the seed and the keyframes (O(log K) restores), then a scan of one
/// keyframe interval, then the fencepost inside the step where re-simulation and the
/// recording split (when the file stores fencepost hashes: RecorderConfig::stageHashes).

#include <string>

#include "lockbox/Export.h"
#include "lockbox/replay/Player.h"

namespace lockbox::replay {

/// Stage number reported when every fencepost of a frame matched but its end state did not
/// (the work after the TOI phase: force clearing, world bounds).
inline constexpr int32 kStageAfterToi = static_cast<int32>(kStagesPerFrame);

/// What Bisect found.
struct LOCKBOX_API BisectResult {
    bool diverged = false;     ///< re-simulation disagrees with the recording
    int32 frame = -1;          ///< first divergent frame (its step produces a different state)
    bool frameExact = true;    ///< false when hashes are sparse: the frame is the first checked
                               ///< frame that differs, the divergence lies within the interval
    int32 stage = -1;          ///< first differing fencepost (StageName, or kStageAfterToi); -1: unknown
    int32 solvePhase = -1;     ///< inside the solve stage: first differing phase (SolvePhaseName); -1: not
                               ///< the solve stage, or no solve-phase hashes stored
    uint64 expected = 0;       ///< recorded hash (of the stage, or of the frame)
    uint64 actual = 0;         ///< re-simulated hash
    int32 lowKeyframe = 0;     ///< last stored state known to re-simulate correctly (a frame)
    int32 highKeyframe = 0;    ///< first stored state known to differ (a frame)
    int32 restores = 0;        ///< snapshots restored
    int64_t framesPlayed = 0;  ///< frames simulated
    int32 probes = 0;          ///< binary-search probes over keyframes
    /// Why the bisection could not run (a replay that cannot be read or played); ok() when it ran.
    Error error;
    /// One or a few lines for people.
    std::string Describe() const;
};

/// Bisects the player's replay (the player's hook, if any, stays installed: tests use it to
/// inject a fault). Leaves the player somewhere after the divergence.
LOCKBOX_API BisectResult Bisect(Player& player);

}  // namespace lockbox::replay
