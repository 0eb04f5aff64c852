#pragma once
/// @file
/// lockbox::WorldGame: the game side of every state tool. What an input means is the game's
/// business: the sync test, the replay recorder and player, and the lockstep and rollback
/// sessions all call Apply with a frame's inputs before each step, and save and load the game's
/// own state (beyond the world) with every saved frame. One game class serves all of them.

#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

class b2World;

/// A game on a b2World, as the state tools drive it (see the file comment).
class LOCKBOX_API WorldGame {
public:
    virtual ~WorldGame() = default;
    /// Applies frame `frame`'s inputs (0-based frame number) to the world, which is unlocked;
    /// the tool steps the world afterwards. `inputs` holds the frame's bytes for every player,
    /// player 0's first (empty when the tool has no inputs).
    virtual void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) = 0;
    /// State beyond the world that influences later frames (default: none). `out` arrives
    /// empty or holding an earlier save; the bytes written replace it. LoadUserState gets back
    /// exactly these bytes.
    virtual void SaveUserState(std::vector<uint8>& out) const { out.clear(); }
    /// Restores the state SaveUserState wrote for the frame being loaded (the same bytes).
    virtual void LoadUserState(std::span<const uint8> in) { (void)in; }
};

/// How a tool steps the world for each frame.
struct WorldStepSettings {
    uint32 tickRate = 60;  ///< frames per second, >= 1 (time step 1/tickRate s, rounded once to Q16.16)
    /// Velocity iterations per step (the constraint solver's velocity passes, as b2World::Step
    /// takes them).
    uint32 velocityIterations = 8;
    /// Position iterations per step (the solver's position correction passes).
    uint32 positionIterations = 3;
};

/// One frame as every state tool runs it: `game.Apply(world, frame, inputs)`, then one
/// b2World::Step with `step`'s time step (1/tickRate s; a tickRate of 0 counts as 1) and
/// iterations.
LOCKBOX_API void AdvanceWorldFrame(b2World& world, WorldGame& game, int32 frame, std::span<const uint8> inputs,
                                   const WorldStepSettings& step);

}  // namespace lockbox
