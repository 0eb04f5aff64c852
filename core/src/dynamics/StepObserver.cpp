// Names of the step fenceposts (StepObserver.h).
#include "lockbox/dynamics/StepObserver.h"

namespace lockbox {

const char* b2StepStageName(b2StepStage stage) noexcept {
    switch (stage) {
        case b2StepStage::e_collide: return "collide";
        case b2StepStage::e_solve: return "solve";
        case b2StepStage::e_broadPhase: return "broadphase";
        case b2StepStage::e_solveTOI: return "toi";
        case b2StepStage::e_count: break;
    }
    return "none";
}

}  // namespace lockbox
