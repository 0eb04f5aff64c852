#pragma once
/// The time step and the solver's per-body state buffers (Box2D's b2TimeStep.h), plus
/// b2Profile: wall-clock figures for benchmarks and integer work counters for tests.

#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"
#include "lockbox/state/Headroom.h"

namespace lockbox {

/// Work done and time spent in one Step, per stage. The *Ns fields are wall-clock nanoseconds
/// from std::chrono::steady_clock: they are read only into this struct, never into world state,
/// so they cannot affect a simulation; use them for benchmarks only. The counters are
/// deterministic and are what tests check ("a stage with nothing to do costs nothing").
struct b2Profile {
    // ---- wall clock (nanoseconds, display/benchmark only) ----
    int64_t stepNs = 0;           ///< the whole Step
    int64_t collideNs = 0;        ///< contact update (narrow phase)
    int64_t solveNs = 0;          ///< island building and solving
    int64_t solveInitNs = 0;      ///< integrate velocities, init constraints, warm start
    int64_t solveVelocityNs = 0;  ///< velocity iterations
    int64_t solvePositionNs = 0;  ///< integrate positions and position iterations
    int64_t broadphaseNs = 0;     ///< fixture synchronisation and new pair search
    int64_t solveTOINs = 0;       ///< continuous collision

    // ---- deterministic work counters (reset at the start of each Step) ----
    int32 pairsFound = 0;               ///< broad-phase pairs reported to AddPair
    int32 contactsCreated = 0;          ///< contacts created from new pairs
    int32 contactsDestroyed = 0;        ///< contacts destroyed (filtering, lost overlap, bodies)
    int32 contactsUpdated = 0;          ///< contacts whose narrow phase ran (b2Contact::Update)
    int32 manifoldsEvaluated = 0;       ///< b2Collide* calls (sensors use overlap tests instead)
    int32 islandsSolved = 0;            ///< discrete islands solved
    int32 bodiesIntegrated = 0;         ///< bodies integrated by the discrete solver
    int32 contactConstraints = 0;       ///< contact constraints initialised by the discrete solver
    int32 jointConstraints = 0;         ///< joints initialised by the discrete solver
    int32 velocityIterations = 0;       ///< sum over islands of velocity iterations x constraints
    int32 jointVelocityIterations = 0;  ///< sum over islands of velocity iterations x joints
    int32 positionIterations = 0;       ///< position iterations run (all islands)
    int32 sleepChecks = 0;              ///< bodies examined by the sleep test
    int32 toiCandidates = 0;            ///< contacts examined by the TOI search (beyond the cheap check)
    int32 toiCalls = 0;                 ///< b2TimeOfImpact calls
    int32 toiEvents = 0;                ///< TOI events (earliest contact advanced)
    int32 toiSubSteps = 0;              ///< TOI islands solved (sub-steps)
    int32 listenerCallbacks = 0;        ///< Begin/End/PreSolve/PostSolve calls made
    int32 boundsViolations = 0;         ///< bodies taken out of the world by the bounds check

    // ---- headroom telemetry (filled only when b2World::SetHeadroomTelemetry(true)) ----
    /// Largest magnitude per quantity class at the end of the step, and the step's saturation
    /// count; the maxima stay zero while the telemetry is off. See lockbox/state/Headroom.h.
    b2Headroom headroom;
};

/// What the solver needs to know about the current (sub-)step.
struct b2TimeStep {
    Fixed dt;       ///< time step, s (1/60 s is raw 1092)
    Fixed inv_dt;   ///< 1 / dt computed in Q16.16, s^-1 (0 when dt is 0)
    Fixed dtRatio;  ///< dt * inv_dt0: warm-start scaling for a variable step (1 exactly for a fixed dt)
    int32 velocityIterations = 0;
    int32 positionIterations = 0;
    int32 stepsToSleep = 0;  ///< round(b2_timeToSleep / dt): consecutive still steps before sleep
    bool warmStarting = false;
};

/// Solver copy of a body's position: centre of mass (m) and angle (rad).
struct b2Position {
    b2Vec2 c;
    Fixed a;
};

/// Solver copy of a body's velocity: linear (m/s) and angular (rad/s).
struct b2Velocity {
    b2Vec2 v;
    Fixed w;
};

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
