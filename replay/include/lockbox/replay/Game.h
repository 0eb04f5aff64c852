#pragma once
/// @file
/// The game side of a replay: the recorder and the player call WorldGame::Apply before every
/// Step with that frame's inputs, and save and load the game's own state (beyond the world)
/// with every seed and keyframe, so a game with state outside the physics still replays and
/// seeks exactly (docs/replay.md). Also the player's stage hook.

#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/state/WorldGame.h"

namespace lockbox::replay {

/// The game a recorder and a player drive: core's WorldGame, the one game interface of every
/// state tool (a sync test, a session and a replay take the same game object).
using Game = WorldGame;

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
