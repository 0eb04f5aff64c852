// b2ContactSolver: non-linear position correction (discrete and time-of-impact).
#include "SolverMath.h"
#include "dynamics/contacts/ContactSolver.h"

namespace lockbox {

namespace {

// Box2D's b2PositionSolverManifold: the current normal, point and separation of one manifold
// point, recomputed from the solver's positions.
struct PositionSolverManifold {
    void Initialize(const b2ContactPositionConstraint* pc, const b2Transform& xfA, const b2Transform& xfB,
                    int32 index) {
        switch (pc->type) {
            case b2Manifold::e_circles: {
                const b2Vec2 pointA = b2Mul(xfA, pc->localPoint);
                const b2Vec2 pointB = b2Mul(xfB, pc->localPoints[0]);
                normal = pointB - pointA;
                normal.Normalize();  // coincident centres keep a zero normal (no push)
                // The midpoint as A plus half the (translation-invariant) difference: halving
                // A + B would round ties by the sign of the world coordinate.
                point = pointA + Fixed(0.5) * (pointB - pointA);
                separation = b2Dot(pointB - pointA, normal) - pc->radiusA - pc->radiusB;
                break;
            }
            case b2Manifold::e_faceA: {
                normal = b2Mul(xfA.q, pc->localNormal);
                const b2Vec2 planePoint = b2Mul(xfA, pc->localPoint);
                const b2Vec2 clipPoint = b2Mul(xfB, pc->localPoints[index]);
                separation = b2Dot(clipPoint - planePoint, normal) - pc->radiusA - pc->radiusB;
                point = clipPoint;
                break;
            }
            case b2Manifold::e_faceB: {
                normal = b2Mul(xfB.q, pc->localNormal);
                const b2Vec2 planePoint = b2Mul(xfB, pc->localPoint);
                const b2Vec2 clipPoint = b2Mul(xfA, pc->localPoints[index]);
                separation = b2Dot(clipPoint - planePoint, normal) - pc->radiusA - pc->radiusB;
                point = clipPoint;
                // Ensure the normal points from A to B.
                normal = -normal;
                break;
            }
        }
    }

    b2Vec2 normal;
    b2Vec2 point;
    Fixed separation;
};

// One pass over all constraints; returns the smallest separation seen (m, <= 0).
Fixed SolvePass(const b2ContactPositionConstraint* constraints, int32 begin, int32 end, b2Position* positions,
                b2CachedRot* rotations, Fixed baumgarte, bool toi, int32 toiIndexA, int32 toiIndexB) {
    Fixed minSeparation;
    for (int32 i = begin; i < end; ++i) {
        const b2ContactPositionConstraint* pc = constraints + i;
        const int32 indexA = pc->indexA;
        const int32 indexB = pc->indexB;
        Wide mA = pc->invMassA, iA = pc->invIA;
        Wide mB = pc->invMassB, iB = pc->invIB;
        if (toi) {
            // Only the two TOI bodies move; the others act as if static.
            if (indexA != toiIndexA && indexA != toiIndexB) {
                mA = Wide();
                iA = Wide();
            }
            if (indexB != toiIndexA && indexB != toiIndexB) {
                mB = Wide();
                iB = Wide();
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

            PositionSolverManifold psm;
            psm.Initialize(pc, xfA, xfB, j);
            const b2Vec2 normal = psm.normal;
            const b2Vec2 rA = psm.point - cA;
            const b2Vec2 rB = psm.point - cB;
            minSeparation = b2Min(minSeparation, psm.separation);

            // Prevent large corrections and allow slop.
            const Fixed C = b2Clamp(baumgarte * (psm.separation + b2_linearSlop), -b2_maxLinearCorrection, Fixed());
            const Fixed rnA = b2Cross(rA, normal);
            const Fixed rnB = b2Cross(rB, normal);
            const Wide K = solver::EffectiveInverseMass(mA, mB, iA, iB, rnA, rnB);
            const Wide impulse = K > Wide() ? -(Wide(C) / K) : Wide();

            // Position changes are rounded once from impulse * inverse mass. Equal masses give
            // B the very changes of A (computed, and reported on saturation, once).
            const Wide linA = mA * impulse;
            const Fixed dxA = MulToFixed(linA, normal.x);
            const Fixed dyA = MulToFixed(linA, normal.y);
            cA.x -= dxA;
            cA.y -= dyA;
            aA -= MulToFixed(iA * impulse, rnA);
            if (mB == mA) {
                cB.x += dxA;
                cB.y += dyA;
            } else {
                const Wide linB = mB * impulse;
                cB.x += MulToFixed(linB, normal.x);
                cB.y += MulToFixed(linB, normal.y);
            }
            aB += MulToFixed(iB * impulse, rnB);
        }

        solver::Store(positions[indexA], cA, aA, mA, iA);
        solver::Store(positions[indexB], cB, aB, mB, iB);
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
