#pragma once
// The time step and the solver's per-body buffers (Box2D's b2TimeStep.h). The solver copies
// of positions and velocities (b2Position, b2Velocity) are public: the step observer sees them.

#include <cstdint>

#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

/// What the solver needs to know about the current (sub-)step.
struct b2TimeStep {
    Fixed dt;       ///< time step, s (1/60 s is raw 1092)
    Fixed inv_dt;   ///< 1 / dt computed in Q16.16, s^-1 (0 when dt is 0)
    Fixed dtRatio;  ///< dt * inv_dt0: warm-start scaling for a variable step (1 exactly for a fixed dt)
    int32 velocityIterations = 0;
    int32 positionIterations = 0;
    int32 stepsToSleep = 0;  ///< round(b2_timeToSleep / dt): consecutive still steps before sleep
    bool warmStarting = false;
    bool timers = true;  ///< time the profile's stages (b2World::SetProfileTimers); never read by the solver
};

/// An impulse carried over from the last step, scaled by dtRatio for warm starting. A fixed step's
/// ratio is exactly 1, and x * 1 is x (nothing to round, nothing to saturate) for every raw but
/// INT64_MIN, which no operation produces; so that product is skipped, with the same bits.
inline Wide WarmScaled(Wide x, Fixed dtRatio) noexcept {
    return dtRatio == Fixed(1) && x.Raw() != INT64_MIN ? x : x * dtRatio;
}
/// WarmScaled for each component (Fixed * b2WideVec2 rounds each component as Wide * Fixed).
inline b2WideVec2 WarmScaled(const b2WideVec2& v, Fixed dtRatio) noexcept {
    return {WarmScaled(v.x, dtRatio), WarmScaled(v.y, dtRatio)};
}

/// A body's rotation with the angle it was built from. b2Rot::Set is a pure function of the
/// angle, so an entry whose angle matches needs no sine or cosine, whichever body or island
/// set it last; every entry is always a true pair (it starts as angle 0 and its rotation).
struct b2CachedRot {
    b2CachedRot() noexcept { q.Set(angle); }
    /// The rotation of `a`, computed only when `a` differs from the last angle asked for.
    const b2Rot& For(Fixed a) noexcept {
        if (a != angle) {
            angle = a;
            q.Set(a);
        }
        return q;
    }

    Fixed angle;
    b2Rot q;
};

/// Everything a joint solver reads and writes.
struct b2SolverData {
    b2TimeStep step;
    b2Position* positions = nullptr;
    b2Velocity* velocities = nullptr;
    b2CachedRot* rotations = nullptr;  ///< per island body, shared with the contact solver

    /// The rotation of angle `a` through island body `index`'s cache entry (any angle is
    /// right: the entry is recomputed unless it holds exactly that angle).
    const b2Rot& Rotation(int32 index, Fixed a) const noexcept { return rotations[index].For(a); }
};

}  // namespace lockbox
