#pragma once
// The solve of a coloured island shared between workers: the stages of its loops (b2Stages)
// and what their blocks need. Island.cpp owns one; IslandShared.cpp runs it.

#include <atomic>
#include <vector>

#include "dynamics/Island.h"
#include "dynamics/tasks/Stages.h"

namespace lockbox {

struct core_detail::Engine::Island::Shared {
    enum class Kind : uint8 {
        e_integrateVelocities,  ///< bodies' velocity integration (any split)
        e_rotations,            ///< the bodies' cached rotations brought up to date (any split)
        e_setUp,                ///< the contacts' copy into the solver and set-up (any split)
        e_warmStart,            ///< a colour's warm start
        e_jointInit,            ///< a joint colour's set-up (or every joint's, in one block)
        e_jointVelocity,        ///< a joint colour's velocity iteration (or every joint's)
        e_velocity,             ///< a colour's velocity iteration
        e_storeImpulses,        ///< the contacts' impulses back to their manifolds (any split)
        e_jointStoreImpulses,   ///< the joints' impulses back to the joints (any split)
        e_integratePositions,   ///< bodies' position integration (any split)
        e_position,             ///< a colour's position pass
        e_jointPosition,        ///< a joint colour's position pass (or every joint's)
        e_storeBodies,          ///< the solver buffers back to the bodies (any split)
    };
    struct Stage {
        Kind kind = Kind::e_setUp;
        int32 begin = 0, end = 0;  ///< items (bodies or constraints) of the stage
        int32 blockSize = 1;
        bool endsIteration = false;  ///< the last stage of a position iteration
        bool oneColour = false;      ///< its items write no body in common

        /// Block k covers [Grid() + k blockSize, Grid() + (k + 1) blockSize) within the items: a
        /// colour's blocks start on the contact lanes' quad boundaries.
        int32 Grid() const noexcept { return oneColour ? b2LaneQuad::FloorBoundary(begin) : begin; }
    };

    b2Stages stages;
    std::vector<Stage> plan;  ///< per stage of `stages`
    b2Island* island = nullptr;
    b2ContactSolver* contacts = nullptr;
    const b2SolverData* data = nullptr;
    b2Vec2 gravity;
    int32 storeStage = 0;  ///< the position phase's last stage, where an accepted iteration goes
    // The position iteration in hand: its smallest separation (raw) and whether its joints
    // were within their slop; then how many iterations ran and whether the last was accepted.
    std::atomic<int32> minSeparation{0};
    std::atomic<bool> jointsOkay{true};
    int32 positionIterations = 0;
    bool positionSolved = false;

    /// Runs block `block` of stage `stage` (b2Stages::Block).
    static void RunBlock(int32 stage, int32 block, void* context);
    /// After an accepted position iteration, goes on to the copy back (b2Stages::Next).
    static int32 NextPositionStage(int32 stage, void* context);
};

}  // namespace lockbox
