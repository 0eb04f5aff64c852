#pragma once
/// @file
/// The game side of a replay: what an input means is the game's business. The
/// recorder and the player call Apply before every Step with that frame's inputs, and save and
/// load the game's own state (beyond the world) with every seed and keyframe, so a game with
/// state outside the physics still replays and seeks exactly (docs/replay.md).

#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/StepObserver.h"

namespace lockbox {
class b2World;
}

namespace lockbox::replay {

/// Applies recorded inputs; mirror of SyncTestGame with the step taken by the replay.
class LOCKBOX_API Game {
public:
    virtual ~Game() = default;
    /// Applies frame `frame`'s inputs (0-based frame number) to the world, which is unlocked.
    /// `inputs` holds playerCount * inputBytes bytes: player 0's bytes first.
    virtual void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) = 0;
    /// State beyond the world that influences later frames (default: none). LoadUserState
    /// gets back exactly these bytes.
    virtual void SaveUserState(std::vector<uint8>& out) const { out.clear(); }
    /// Restores the state SaveUserState wrote for the frame being loaded (the same bytes).
    virtual void LoadUserState(std::span<const uint8> in) { (void)in; }
};

/// Called by a player at every stored fencepost of a frame (stage numbers as in Format.h's
/// StageName: 0 inputs applied, 1 collide, 2 solve, 3 broadphase, 4 toi), before the stage is
/// hashed. For debugging and for tests that inject a fault at a known point; the world is
/// locked for stages 1 to 4, so only field edits are allowed there.
class LOCKBOX_API StageHook {
public:
    virtual ~StageHook() = default;
    /// Called at stored stage `stage` (0 to 4, see above) of frame `frame`, before the stage is
    /// hashed.
    virtual void OnStage(int32 frame, uint32 stage, b2World& world) = 0;
    /// Called inside the solve stage for every island's velocity and position phase, before
    /// the phase is hashed (b2StepObserver::OnIsland: changing the buffers injects a fault).
    virtual void OnIsland(int32 frame, b2IslandPhase phase, std::span<b2Body* const> bodies,
                          std::span<b2Position> positions, std::span<b2Velocity> velocities) {
        (void)frame;
        (void)phase;
        (void)bodies;
        (void)positions;
        (void)velocities;
    }
};

}  // namespace lockbox::replay
