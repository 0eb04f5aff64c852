#pragma once
/// @file
/// b2Profile (as in later Box2D releases): what one b2World::Step did and how long each stage
/// took. The wall-clock figures are for benchmarks; the integer work counters are
/// deterministic and are what tests check.

#include <cstdint>

#include "lockbox/common/Settings.h"
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

}  // namespace lockbox
