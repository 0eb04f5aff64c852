#pragma once
// One contact's velocity row (Box2D 2.2.1 b2ContactSolver::SolveVelocityConstraints for one
// constraint): friction at each point, then the normal, by the block solver for two points.
//
// The row is written once for any number type N with Wide's operations and a pair type V of
// it. On Wide every operation tests its range (saturate and report); on UncheckedWide none does,
// and the solver takes that only for a row proven to stay in range (ContactRowBound.h). The one
// text is what makes the two give the same bits.

#include "SolverMath.h"
#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/unchecked/UncheckedWide.h"

namespace lockbox::solver {

// Wide's math::Min and math::Max, for any N.
template <class N>
[[gnu::always_inline]] inline N RowMin(N a, N b) noexcept {
    return b < a ? b : a;
}
template <class N>
[[gnu::always_inline]] inline N RowMax(N a, N b) noexcept {
    return a < b ? b : a;
}

// Solves one iteration of vc on the pair's velocities (A: vA, wA; B: vB, wB) and its
// accumulated impulses.
template <class N, class V>
[[gnu::always_inline]] inline void SolveContactRow(b2ContactVelocityConstraint& vc, V& vA, N& wA, V& vB,
                                                   N& wB) noexcept {
    const b2Vec2 normal = vc.normal;
    const b2Vec2 tangent = vc.tangent;
    const V pushNA{N(vc.pushA.x), N(vc.pushA.y)};
    const V pushNB{N(vc.pushB.x), N(vc.pushB.y)};
    // The tangent (n.y, -n.x) moves a body by (push.y, -push.x) per N*s.
    const V pushTA{pushNA.y, -pushNA.x};
    const V pushTB{pushNB.y, -pushNB.x};
    const bool same = vc.samePush;

    // Friction first: non-penetration matters more, so it gets the last word.
    for (int32 j = 0; j < vc.pointCount; ++j) {
        b2VelocityConstraintPoint& vcp = vc.points[j];
        const N vt = SpeedAlong(vA, wA, vcp.rtA, vB, wB, vcp.rtB, tangent);
        N lambda = -(N(vcp.tangentMass) * vt);
        const N maxFriction = N(vcp.normalImpulse) * vc.friction;
        const N oldImpulse = N(vcp.tangentImpulse);
        const N newImpulse = RowMax(-maxFriction, RowMin(oldImpulse + lambda, maxFriction));
        lambda = newImpulse - oldImpulse;
        vcp.tangentImpulse = AsWide(newImpulse);
        ApplyAlong(vA, wA, vB, wB, lambda, pushTA, pushTB, same, N(vcp.turnTA), N(vcp.turnTB));
    }

    if (vc.pointCount == 1) {
        b2VelocityConstraintPoint& vcp = vc.points[0];
        const N vn = SpeedAlong(vA, wA, vcp.rnA, vB, wB, vcp.rnB, normal);
        N lambda = -(N(vcp.normalMass) * (vn - N(vcp.velocityBias)));
        const N oldImpulse = N(vcp.normalImpulse);
        const N newImpulse = RowMax(oldImpulse + lambda, N());
        lambda = newImpulse - oldImpulse;
        vcp.normalImpulse = AsWide(newImpulse);
        ApplyAlong(vA, wA, vB, wB, lambda, pushNA, pushNB, same, N(vcp.turnNA), N(vcp.turnNB));
        return;
    }

    // Block solver (Box2D's total enumeration of the 2-point LCP):
    //   vn = K x + b', x >= 0, vn >= 0, x_i vn_i = 0, with b' = vn0 - bias - K a.
    b2VelocityConstraintPoint& cp1 = vc.points[0];
    b2VelocityConstraintPoint& cp2 = vc.points[1];
    const N a1 = N(cp1.normalImpulse), a2 = N(cp2.normalImpulse);
    const N vn1 = SpeedAlong(vA, wA, cp1.rnA, vB, wB, cp1.rnB, normal);
    const N vn2 = SpeedAlong(vA, wA, cp2.rnA, vB, wB, cp2.rnB, normal);
    const N k11 = N(vc.K.k11), k12 = N(vc.K.k12), k22 = N(vc.K.k22);
    const N b1 = (vn1 - N(cp1.velocityBias)) - (k11 * a1 + k12 * a2);
    const N b2 = (vn2 - N(cp2.velocityBias)) - (k12 * a1 + k22 * a2);

    N x1, x2;
    bool solved = false;
    // Case 1: both points active, vn = 0.
    x1 = -(N(vc.normalMass.k11) * b1 + N(vc.normalMass.k12) * b2);
    x2 = -(N(vc.normalMass.k12) * b1 + N(vc.normalMass.k22) * b2);
    if (x1 >= N() && x2 >= N()) solved = true;
    // Case 2: point 1 active, x2 = 0.
    if (!solved) {
        x1 = -(N(cp1.normalMass) * b1);
        x2 = N();
        const N v2 = k12 * x1 + b2;
        if (x1 >= N() && v2 >= N()) solved = true;
    }
    // Case 3: point 2 active, x1 = 0.
    if (!solved) {
        x1 = N();
        x2 = -(N(cp2.normalMass) * b2);
        const N v1 = k12 * x2 + b1;
        if (x2 >= N() && v1 >= N()) solved = true;
    }
    // Case 4: both separating.
    if (!solved) {
        x1 = N();
        x2 = N();
        if (b1 >= N() && b2 >= N()) solved = true;
    }
    // No solution: give up this iteration (as Box2D; rare and harmless).
    if (!solved) return;
    // Both impulses act along the normal: one linear impulse, two lever arms.
    const N d1 = x1 - a1, d2 = x2 - a2;
    PushPair(vA, vB, d1 + d2, pushNA, pushNB, same);
    wA -= d1 * N(cp1.turnNA) + d2 * N(cp2.turnNA);
    wB += d1 * N(cp1.turnNB) + d2 * N(cp2.turnNB);
    cp1.normalImpulse = AsWide(x1);
    cp2.normalImpulse = AsWide(x2);
}

}  // namespace lockbox::solver
