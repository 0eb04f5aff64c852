#pragma once
// One point of Box2D 2.2.1's b2ContactSolver::SolvePositionConstraints: where a face manifold's
// point is (b2PositionSolverManifold for e_faceA and e_faceB), the correction impulse that pushes
// it towards -linearSlop, and that impulse applied to both bodies.
//
// Written once over number types: Fixed and Wide test every operation's range (saturate and
// report); UncheckedFixed and UncheckedWide test none, and the solver takes them only where the
// constraint's bound (ContactPositionBound.h) proves every value in range. The one text is what
// makes the two give the same bits. The division is Wide's on either.

#include <type_traits>

#include "SolverMath.h"
#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/unchecked/UncheckedWide.h"
#include "lockbox/common/Settings.h"

namespace lockbox::solver {

// A manifold point as the correction sees it.
struct PositionPoint {
    b2Vec2 normal;     ///< unit, from A to B
    b2Vec2 rA, rB;     ///< arms from the centres to the point (m)
    b2Vec2 gap;        ///< a face point's clip point less its plane point (m)
    Fixed separation;  ///< m
};

// Point j of a face manifold from the bodies' transforms and centres: the reference face's body
// (A for e_faceA) gives the normal and the plane point, the other the clip point.
template <class F, bool faceA>
[[gnu::always_inline]] inline PositionPoint LocateFace(const b2ContactPositionConstraint& pc,
                                                       const b2Transform& reference, const b2Transform& incident,
                                                       const b2Vec2& cA, const b2Vec2& cB, int32 j) noexcept {
    PositionPoint p;
    p.normal = Rotate(reference.q, F(pc.localNormal.x), F(pc.localNormal.y));
    const b2Vec2 plane = Rotate(reference.q, F(pc.localPoint.x), F(pc.localPoint.y));
    const F planeX = F(plane.x) + F(reference.p.x), planeY = F(plane.y) + F(reference.p.y);
    const b2Vec2 clip = Rotate(incident.q, F(pc.localPoints[j].x), F(pc.localPoints[j].y));
    const F clipX = F(clip.x) + F(incident.p.x), clipY = F(clip.y) + F(incident.p.y);
    const F gapX = clipX - planeX, gapY = clipY - planeY;
    p.gap = b2Vec2(Fixed(gapX), Fixed(gapY));
    p.separation = Fixed(F(Dot(gapX, gapY, p.normal)) - F(pc.radiusA) - F(pc.radiusB));
    // The normal points from A to B.
    if (!faceA) p.normal = b2Vec2(Fixed(-F(p.normal.x)), Fixed(-F(p.normal.y)));
    p.rA = b2Vec2(Fixed(clipX - F(cA.x)), Fixed(clipY - F(cA.y)));
    p.rB = b2Vec2(Fixed(clipX - F(cB.x)), Fixed(clipY - F(cB.y)));
    return p;
}
template <class F>
[[gnu::always_inline]] inline PositionPoint LocateFacePoint(const b2ContactPositionConstraint& pc,
                                                            const b2Transform& xfA, const b2Transform& xfB,
                                                            const b2Vec2& cA, const b2Vec2& cB, int32 j) noexcept {
    if (pc.type == b2Manifold::e_faceA) return LocateFace<F, true>(pc, xfA, xfB, cA, cB, j);
    return LocateFace<F, false>(pc, xfB, xfA, cA, cB, j);
}

// The pair's inverse masses and inertias as a pass sees them (the time-of-impact pass holds all
// but its two bodies still).
template <class N>
struct PairMasses {
    N mA, mB, iA, iB;
};

// The correction at a point: its arms across the normal and its impulse (N*s, zero when the
// point needs none or the bodies cannot move).
struct PositionCorrection {
    Fixed rnA, rnB;
    Wide impulse;
};

template <class F, class N>
[[gnu::always_inline]] inline PositionCorrection CorrectPoint(const PositionPoint& p, const PairMasses<N>& m,
                                                              Fixed baumgarte) noexcept {
    // Prevent large corrections and allow slop.
    const Fixed C =
        b2Clamp(Fixed(F(baumgarte) * (F(p.separation) + F(b2_linearSlop))), -b2_maxLinearCorrection, Fixed());
    PositionCorrection c;
    // On a proven point nothing below can saturate, and a zero C gives a zero impulse: a point
    // within the slop needs neither K nor the division.
    if constexpr (!std::is_same_v<N, Wide>) {
        if (C == Fixed()) return c;
    }
    c.rnA = Cross(F(p.rA.x), F(p.rA.y), p.normal);
    c.rnB = Cross(F(p.rB.x), F(p.rB.y), p.normal);
    const Wide K = AsWide(EffectiveInverseMass(m.mA, m.mB, m.iA, m.iB, c.rnA, c.rnB));
    c.impulse = K > Wide() ? -(Wide(C) / K) : Wide();
    return c;
}

// Position changes are rounded once from impulse * inverse mass. Equal masses give B the very
// changes of A (computed, and reported on saturation, once).
template <class F, class N>
[[gnu::always_inline]] inline void ApplyCorrection(const b2Vec2& normal, const PositionCorrection& c,
                                                   const PairMasses<N>& m, b2Vec2& cA, Fixed& aA, b2Vec2& cB,
                                                   Fixed& aB) noexcept {
    const N impulse = N(c.impulse);
    const N linA = m.mA * impulse;
    const F dxA = F(MulToFixed(linA, normal.x));
    const F dyA = F(MulToFixed(linA, normal.y));
    cA = b2Vec2(Fixed(F(cA.x) - dxA), Fixed(F(cA.y) - dyA));
    aA = Fixed(F(aA) - F(MulToFixed(m.iA * impulse, c.rnA)));
    if (m.mB == m.mA) {
        cB = b2Vec2(Fixed(F(cB.x) + dxA), Fixed(F(cB.y) + dyA));
    } else {
        const N linB = m.mB * impulse;
        cB = b2Vec2(Fixed(F(cB.x) + F(MulToFixed(linB, normal.x))), Fixed(F(cB.y) + F(MulToFixed(linB, normal.y))));
    }
    aB = Fixed(F(aB) + F(MulToFixed(m.iB * impulse, c.rnB)));
}

// Whether a face point located without range tests is within the constraint's widths: then its
// correction may be formed without them too. The other body's arm (the clip point less its own
// centre) is a difference of two turned local vectors, which the bound covers, and the gap is the
// reference arm less two more.
[[gnu::always_inline]] inline bool FacePointFits(const b2ContactPositionConstraint& pc,
                                                 const PositionPoint& p) noexcept {
    const b2Vec2& arm = pc.type == b2Manifold::e_faceA ? p.rA : p.rB;
    return Within(Folded(arm.x) | Folded(arm.y), pc.unchecked.arm);
}

}  // namespace lockbox::solver
