#pragma once
// The per-point part of a contact's velocity set-up (Box2D 2.2.1
// b2ContactSolver::InitializeVelocityConstraints): the pushes, and at each point the lever arms,
// the effective masses, the angular responses and the restitution bias.
//
// Written once over number types: Fixed and Wide test every operation's range (saturate and
// report); UncheckedFixed and UncheckedWide test none, and the solver takes them only for a
// contact proven to stay in range (ContactPointSetUpBound.h). The one text is what makes the two
// give the same bits. The divisions are Wide's on either.

#include "SolverMath.h"
#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/unchecked/UncheckedWide.h"
#include "lockbox/common/Settings.h"

namespace lockbox::solver {

// Sets up vc's pushes and points from its normal, tangent, masses and restitution, the world
// points, the bodies' centres cA, cB and their velocities (A: vA, wA; B: vB, wB). Returns the
// block solver's K for two points: its diagonal is the points' normal denominators.
template <class F, class N, class V>
[[gnu::always_inline]] inline b2WideSym22 SetUpContactPoints(b2ContactVelocityConstraint& vc, const b2Vec2* points,
                                                             const b2Vec2& cA, const b2Vec2& cB, const V& vA, N wA,
                                                             const V& vB, N wB) noexcept {
    const N mA = N(vc.invMassA), mB = N(vc.invMassB);
    const N iA = N(vc.invIA), iB = N(vc.invIB);
    const b2Vec2 normal = vc.normal;
    const b2Vec2 tangent = vc.tangent;
    vc.pushA = b2WideVec2(AsWide(mA * normal.x), AsWide(mA * normal.y));
    vc.pushB = b2WideVec2(AsWide(mB * normal.x), AsWide(mB * normal.y));
    Wide kNormals[b2_maxManifoldPoints];

    for (int32 j = 0; j < vc.pointCount; ++j) {
        b2VelocityConstraintPoint& vcp = vc.points[j];
        const F rAx = F(points[j].x) - F(cA.x), rAy = F(points[j].y) - F(cA.y);
        const F rBx = F(points[j].x) - F(cB.x), rBy = F(points[j].y) - F(cB.y);

        vcp.rnA = Cross(rAx, rAy, normal);
        vcp.rnB = Cross(rBx, rBy, normal);
        const Wide kNormal = AsWide(EffectiveInverseMass(mA, mB, iA, iB, vcp.rnA, vcp.rnB));
        kNormals[j] = kNormal;
        vcp.normalMass = kNormal > Wide() ? Wide(1) / kNormal : Wide();
        vcp.turnNA = AsWide(iA * vcp.rnA);
        vcp.turnNB = AsWide(iB * vcp.rnB);

        vcp.rtA = Cross(rAx, rAy, tangent);
        vcp.rtB = Cross(rBx, rBy, tangent);
        const Wide kTangent = AsWide(EffectiveInverseMass(mA, mB, iA, iB, vcp.rtA, vcp.rtB));
        vcp.tangentMass = kTangent > Wide() ? Wide(1) / kTangent : Wide();
        vcp.turnTA = AsWide(iA * vcp.rtA);
        vcp.turnTB = AsWide(iB * vcp.rtB);

        // Restitution only above the threshold speed (inelastic resting contact).
        vcp.velocityBias = Fixed();
        const N vRel = SpeedAlong(vA, wA, vcp.rnA, vB, wB, vcp.rnB, normal);
        if (vRel < N(-Wide(b2_velocityThreshold))) vcp.velocityBias = -(vRel * vc.restitution).ToFixed();
    }

    b2WideSym22 K;
    if (vc.pointCount == 2) {
        const b2VelocityConstraintPoint& p1 = vc.points[0];
        const b2VelocityConstraintPoint& p2 = vc.points[1];
        K.k11 = kNormals[0];
        K.k22 = kNormals[1];
        K.k12 = AsWide(mA + mB + iA * N(MulWide(p1.rnA, p2.rnA)) + iB * N(MulWide(p1.rnB, p2.rnB)));
    }
    return K;
}

}  // namespace lockbox::solver
