#pragma once
/// @file
/// Time of impact (Box2D 2.2.1's b2TimeOfImpact.h): conservative advancement along separating
/// axes with a bracketing root finder, on Q16.16 time fractions. Every loop has an iteration
/// cap and the root finder also stops when its bracket is one raw time unit wide, so the call
/// always terminates (the argument is written out in TimeOfImpact.cpp).

#include "lockbox/Export.h"
#include "lockbox/collision/Distance.h"

namespace lockbox {

/// Input of b2TimeOfImpact: two shapes and their motions over the interval [0, tMax].
struct b2TOIInput {
    b2DistanceProxy proxyA;  ///< shape A
    b2DistanceProxy proxyB;  ///< shape B
    b2Sweep sweepA;          ///< motion of A over the step
    b2Sweep sweepB;          ///< motion of B over the step
    Fixed tMax;              ///< end of the search interval, a sweep fraction in [0, 1]
};

/// Output of b2TimeOfImpact. The iteration counts replace 2.2.1's global counters
/// (b2_toiIters, b2_toiRootIters, ...), which would be hidden state.
struct b2TOIOutput {
    /// How the search ended.
    enum State {
        e_unknown,     ///< not computed
        e_failed,      ///< iteration cap reached or root finder lost the bracket; t is a safe lower bound
        e_overlapped,  ///< the core shapes overlap at t = 0
        e_touching,    ///< the shapes are within target +- tolerance at t
        e_separated    ///< no contact before tMax (t = tMax)
    };

    State state = e_unknown;   ///< result class
    Fixed t;                   ///< time fraction of the result, in [0, tMax]
    int32 iterations = 0;      ///< outer (separating-axis) iterations, 1 to b2_maxTOIIterations
    int32 rootIterations = 0;  ///< root-finder iterations summed over the whole call
};

/// The largest number of outer iterations of b2TimeOfImpact (2.2.1's k_maxIterations).
inline constexpr int32 b2_maxTOIIterations = 20;
/// The largest number of iterations of one root search (2.2.1's literal 50).
inline constexpr int32 b2_maxTOIRootIterations = 50;

/// Computes an upper bound on the time before the two shapes come closer than
/// target = max(linearSlop, rA + rB - 3 linearSlop), as a fraction of [0, tMax]. Uses the
/// swept separating axis method: it may miss an intermediate grazing contact but never lets a
/// shape pass through another. Sweeps are normalised internally (on copies). Deterministic.
LOCKBOX_API void b2TimeOfImpact(b2TOIOutput* output, const b2TOIInput* input);

}  // namespace lockbox
