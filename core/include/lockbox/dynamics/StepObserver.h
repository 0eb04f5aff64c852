#pragma once
/// Step fenceposts (issue 9): optional points inside b2World::Step where an observer may look
/// at (hash) the world. Replay bisection uses them to tell in which stage of a step two runs
/// split. With no observer set (the default) a Step only tests one null pointer per stage.
///
/// The observer must not modify the world through the const reference it gets, and must not
/// call anything that needs an unlocked world (the world is locked during the calls).

#include "lockbox/common/Settings.h"

namespace lockbox {

class b2World;

/// The fenceposts of one b2World::Step, in the order they are reached.
enum class b2StepStage : uint32 {
    e_collide = 0,     ///< after the narrow phase (b2ContactManager::Collide)
    e_solve = 1,       ///< after every island's velocity and position solve (b2World::Solve),
                       ///< before the fixtures are synchronised
    e_broadPhase = 2,  ///< after the fixtures' synchronisation and FindNewContacts ending Solve
    e_solveTOI = 3,    ///< after the continuous (time of impact) phase
    e_count = 4
};

/// Short name of a stage ("collide", "solve", "broadphase", "toi"); "none" for e_count.
const char* b2StepStageName(b2StepStage stage) noexcept;

/// Receives the fenceposts of every Step of the world it is set on (b2World::SetStepObserver).
/// A stage skipped by a step (Solve when dt is 0, the TOI phase with continuous physics off)
/// is not reported.
class b2StepObserver {
public:
    virtual ~b2StepObserver() = default;
    /// Called at each fencepost reached by the step, in b2StepStage order.
    virtual void OnStage(b2StepStage stage, const b2World& world) = 0;
};

}  // namespace lockbox
