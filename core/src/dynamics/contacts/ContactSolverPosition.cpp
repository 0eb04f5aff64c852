// b2ContactSolver: non-linear position correction (discrete and time-of-impact).
#include "ContactPositionRow.h"
#include "SolverMath.h"
#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/unchecked/UncheckedWide.h"

namespace lockbox {

namespace {

// Box2D's b2PositionSolverManifold for a circles manifold: the normal between the centres, the
// midpoint and the separation, from the solver's positions (always with range tests).
solver::PositionPoint LocateCirclePoint(const b2ContactPositionConstraint& pc, const b2Transform& xfA,
                                        const b2Transform& xfB, const b2Vec2& cA, const b2Vec2& cB) noexcept {
    solver::PositionPoint p;
    const b2Vec2 pointA = b2Mul(xfA, pc.localPoint);
    const b2Vec2 pointB = b2Mul(xfB, pc.localPoints[0]);
    p.normal = pointB - pointA;
    p.normal.Normalize();  // coincident centres keep a zero normal (no push)
    // The midpoint as A plus half the (translation-invariant) difference: halving A + B would
    // round ties by the sign of the world coordinate.
    const b2Vec2 point = pointA + Fixed(0.5) * (pointB - pointA);
    p.separation = b2Dot(pointB - pointA, p.normal) - pc.radiusA - pc.radiusB;
    p.rA = point - cA;
    p.rB = point - cB;
    return p;
}

// A point's correction with range tests, from where the point is.
void CorrectTested(const solver::PositionPoint& p, const solver::PairMasses<Wide>& masses, Fixed baumgarte, b2Vec2& cA,
                   Fixed& aA, b2Vec2& cB, Fixed& aB) noexcept {
    const solver::PositionCorrection c = solver::CorrectPoint<Fixed, Wide>(p, masses, baumgarte);
    solver::ApplyCorrection<Fixed, Wide>(p.normal, c, masses, cA, aA, cB, aB);
}

// One pass over all constraints; returns the smallest separation seen (m, <= 0). A face point
// runs without range tests when allowed and the constraint's widths prove it in range: the poses
// before it is located, the reference arm once located, the impulse once formed.
[[gnu::flatten]] Fixed SolvePass(const b2ContactPositionConstraint* constraints, int32 begin, int32 end,
                                 b2Position* positions, b2CachedRot* rotations, Fixed baumgarte, bool toi,
                                 int32 toiIndexA, int32 toiIndexB) {
    const bool uncheckedAllowed = solver::UncheckedRowsAllowed();
    Fixed minSeparation;
    for (int32 i = begin; i < end; ++i) {
        const b2ContactPositionConstraint* pc = constraints + i;
        const int32 indexA = pc->indexA;
        const int32 indexB = pc->indexB;
        solver::PairMasses<Wide> masses{pc->invMassA, pc->invMassB, pc->invIA, pc->invIB};
        if (toi) {
            // Only the two TOI bodies move; the others act as if static.
            if (indexA != toiIndexA && indexA != toiIndexB) {
                masses.mA = Wide();
                masses.iA = Wide();
            }
            if (indexB != toiIndexA && indexB != toiIndexB) {
                masses.mB = Wide();
                masses.iB = Wide();
            }
        }

        b2Vec2 cA = positions[indexA].c;
        Fixed aA = positions[indexA].a;
        b2Vec2 cB = positions[indexB].c;
        Fixed aB = positions[indexB].a;

        // SinCos is a pure function of the angle: a body's rotation is recomputed only when a
        // correction changed its angle since it was last built (never for a static body).
        b2CachedRot& rotA = rotations[indexA];
        b2CachedRot& rotB = rotations[indexB];
        b2Transform xfA, xfB;
        for (int32 j = 0; j < pc->pointCount; ++j) {
            xfA.q = rotA.For(aA);
            xfB.q = rotB.For(aB);
            xfA.p = solver::BodyOrigin(cA, xfA.q, pc->localCenterA);
            xfB.p = solver::BodyOrigin(cB, xfB.q, pc->localCenterB);

            if (pc->type == b2Manifold::e_circles) {
                const solver::PositionPoint p = LocateCirclePoint(*pc, xfA, xfB, cA, cB);
                minSeparation = b2Min(minSeparation, p.separation);
                CorrectTested(p, masses, baumgarte, cA, aA, cB, aB);
                continue;
            }
#ifdef LOCKBOX_UNCHECKED_ROWS
            if (uncheckedAllowed && solver::Within(solver::FoldedPair(cA, aA, cB, aB), pc->unchecked.poses)) {
                using solver::UncheckedFixed, solver::UncheckedWide;
                const solver::PositionPoint p = solver::LocateFacePoint<UncheckedFixed>(*pc, xfA, xfB, cA, cB, j);
                if (solver::FacePointFits(*pc, p)) {
                    minSeparation = b2Min(minSeparation, p.separation);
                    const solver::PairMasses<UncheckedWide> unchecked{masses.mA, masses.mB, masses.iA, masses.iB};
                    const solver::PositionCorrection c =
                        solver::CorrectPoint<UncheckedFixed, UncheckedWide>(p, unchecked, baumgarte);
                    // A zero impulse moves neither body.
                    if (c.impulse == Wide()) continue;
                    if (solver::Within(solver::Folded(c.impulse), pc->unchecked.impulses)) {
                        solver::ApplyCorrection<UncheckedFixed, UncheckedWide>(p.normal, c, unchecked, cA, aA, cB, aB);
                    } else {
                        solver::ApplyCorrection<Fixed, Wide>(p.normal, c, masses, cA, aA, cB, aB);
                    }
                    continue;
                }
            }
#else
            (void)uncheckedAllowed;
#endif
            const solver::PositionPoint p = solver::LocateFacePoint<Fixed>(*pc, xfA, xfB, cA, cB, j);
            minSeparation = b2Min(minSeparation, p.separation);
            CorrectTested(p, masses, baumgarte, cA, aA, cB, aB);
        }

        solver::Store(positions[indexA], cA, aA, masses.mA, masses.iA);
        solver::Store(positions[indexB], cB, aB, masses.mB, masses.iB);
    }
    return minSeparation;
}

}  // namespace

Fixed b2ContactSolver::SolvePositionConstraints(int32 begin, int32 end) {
    return SolvePass(m_positionConstraints, begin, end, m_positions, m_rotations, b2_baumgarte, false, -1, -1);
}

bool b2ContactSolver::SolveTOIPositionConstraints(int32 toiIndexA, int32 toiIndexB) {
    const Fixed minSeparation = SolvePass(m_positionConstraints, 0, m_count, m_positions, m_rotations, b2_toiBaugarte,
                                          true, toiIndexA, toiIndexB);
    // Done once the overlap is less than 1.5 linearSlop (raw 492). The time of impact leaves the
    // pair at its target, 3 linearSlop deep, and one correction of 0.75 (separation + linearSlop)
    // lands exactly on 1.5: float Box2D lands a rounding error beyond it and corrects once more,
    // which leaves the body 0.47 mm higher. The tie is refused so that it does the same.
    return minSeparation > Fixed::FromRaw(-3 * b2_linearSlop.Raw() / 2);
}

}  // namespace lockbox
