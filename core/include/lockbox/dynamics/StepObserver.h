#pragma once
/// @file
/// Step fenceposts: optional points inside b2World::Step where an observer may look
/// at (hash) the world. Replay bisection uses them to tell in which stage of a step two runs
/// split. With no observer set (the default) a Step only tests one null pointer per stage.
///
/// The observer must not modify the world through the const reference it gets, and must not
/// call anything that needs an unlocked world (the world is locked during the calls).

#include <span>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"
#include "lockbox/fixed/WideVec.h"

namespace lockbox {

class b2World;
class b2Body;

/// Solver copy of a body's position: centre of mass (m) and angle (rad).
struct b2Position {
    /// Centre of mass in world coordinates, m.
    b2Vec2 c;
    /// Angle, rad.
    Fixed a;
};

/// Solver copy of a body's velocity: linear (m/s) and angular (rad/s), in Q32.32 so that the
/// step adds forces and impulses below the Q16.16 quantum (1/65536 m/s) without rounding them
/// away. The body keeps the part below Q16.16 between steps (docs/numerics.md, "Velocities").
struct b2Velocity {
    /// Linear velocity of the centre of mass, m/s.
    b2WideVec2 v;
    /// Angular velocity, rad/s.
    Wide w;
};

/// The fenceposts of one b2World::Step, in the order they are reached.
enum class b2StepStage : uint32 {
    e_collide = 0,     ///< after the narrow phase (b2ContactManager::Collide)
    e_solve = 1,       ///< after every island's velocity and position solve (b2World::Solve),
                       ///< before the fixtures are synchronised
    e_broadPhase = 2,  ///< after the fixtures' synchronisation and FindNewContacts ending Solve
    e_solveTOI = 3,    ///< after the continuous (time of impact) phase
    e_count = 4
};

/// The two halves of one island's discrete solve (b2Island::Solve), reported inside the
/// e_solve stage so a divergence can be placed in the velocity or the position solve.
enum class b2IslandPhase : uint32 {
    e_velocity = 0,  ///< after the velocity iterations (impulses stored), before positions are integrated
    e_position = 1,  ///< after the position iterations, before the bodies get the results
};

/// Short name of a stage ("collide", "solve", "broadphase", "toi"); "none" for e_count.
LOCKBOX_API const char* b2StepStageName(b2StepStage stage) noexcept;

/// Receives the fenceposts of every Step of the world it is set on (b2World::SetStepObserver).
/// A stage skipped by a step (Solve when dt is 0, the TOI phase with continuous physics off)
/// is not reported.
class LOCKBOX_API b2StepObserver {
public:
    virtual ~b2StepObserver() = default;
    /// Called at each fencepost reached by the step, in b2StepStage order.
    virtual void OnStage(b2StepStage stage, const b2World& world) = 0;
    /// Called twice per island of the discrete solve (velocity, then position phase) with the
    /// island's bodies and its solver buffers (same order; positions and velocities of body i at
    /// index i). The buffers are mutable only so that a test can inject a fault at a known point;
    /// an observer that changes them changes the simulation. Default: nothing.
    virtual void OnIsland(b2IslandPhase phase, std::span<b2Body* const> bodies, std::span<b2Position> positions,
                          std::span<b2Velocity> velocities) {
        (void)phase;
        (void)bodies;
        (void)positions;
        (void)velocities;
    }
};

}  // namespace lockbox
