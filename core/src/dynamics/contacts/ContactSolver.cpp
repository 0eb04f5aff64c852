// b2ContactSolver: setup, warm starting and the velocity iterations.
#include "dynamics/contacts/ContactSolver.h"

#include "ContactPointSetUp.h"
#include "ContactPointSetUpBound.h"
#include "ContactPositionBound.h"
#include "ContactRow.h"
#include "ContactRowBound.h"
#include "SolverMath.h"
#include "dynamics/unchecked/UncheckedWide.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/fixed/detail/Int128.h"

namespace lockbox {

namespace {

// Box2D's k_maxConditionNumber: the block solver is used only while the 2x2 K is well
// conditioned, k11^2 < 1000 (k11 k22 - k12^2). Dimensionless; the comparison is exact.
constexpr int64_t kMaxConditionNumber = 1000;

// Inverts the symmetric K = [k11 k12; k12 k22] exactly in 128 bits. Returns false when K is
// too ill-conditioned for the block solver (or singular after rounding).
bool InvertBlock(const b2WideSym22& K, b2WideSym22* inverse) {
    using namespace detail;
    const S128 k11k22 = MulS64(K.k11.Raw(), K.k22.Raw());
    const S128 k12sq = MulS64(K.k12.Raw(), K.k12.Raw());
    const S128 det = SubS128(k11k22, k12sq);  // Q64.64, >= 0 in exact arithmetic
    if (det.negative || IsZero(det)) return false;
    const S128 k11sq = MulS64(K.k11.Raw(), K.k11.Raw());
    const S128 bound = MulS128S64(det, kMaxConditionNumber);
    if (!LessU128(k11sq.mag, bound.mag)) return false;
    // inverse = adj(K) / det; the Q32.32 raw is round(adj_raw * 2^64 / det_raw).
    auto entry = [&](int64_t adjRaw) {
        S128 n = MulS64(adjRaw, 1);
        n.mag = ShlU128(n.mag, 64);
        return Wide::FromRaw(NarrowWide(DivRoundS128(n, det), "b2ContactSolver block inverse", adjRaw, 0));
    };
    inverse->k11 = entry(K.k22.Raw());
    inverse->k12 = entry(-K.k12.Raw());
    inverse->k22 = entry(K.k11.Raw());
    return true;
}

// The pushes and points of vc and the block solver's K (ContactPointSetUp.h), unchecked where
// the contact is proven to stay in range. Flattened: the unchecked path pays off only with every
// operation inlined.
[[gnu::flatten]] b2WideSym22 SetUpPoints(b2ContactVelocityConstraint& vc, const b2Vec2* points, const b2Vec2& cA,
                                         const b2Vec2& cB, const b2Velocity& A, const b2Velocity& B,
                                         bool uncheckedAllowed) {
#ifdef LOCKBOX_UNCHECKED_ROWS
    if (uncheckedAllowed &&
        solver::Within(solver::FoldedPair(A.v, A.w, B.v, B.w), solver::SetUpVelocityWidth(vc, points, cA, cB))) {
        using solver::UncheckedFixed, solver::UncheckedVec2, solver::UncheckedWide;
        return solver::SetUpContactPoints<UncheckedFixed, UncheckedWide>(vc, points, cA, cB, UncheckedVec2::From(A.v),
                                                                         UncheckedWide(A.w), UncheckedVec2::From(B.v),
                                                                         UncheckedWide(B.w));
    }
#else
    (void)uncheckedAllowed;
#endif
    return solver::SetUpContactPoints<Fixed, Wide>(vc, points, cA, cB, A.v, A.w, B.v, B.w);
}

// Load reads three of each contact's cache lines, then its fixtures, then their bodies and shapes:
// three dependent misses in a large island, whose contacts lie scattered over the heap. Each
// level is requested some places ahead, once the level before it has had time to arrive. Hints
// only: they change no result.
constexpr int32 kContactAhead = 8;
constexpr int32 kFixturesAhead = 4;
constexpr int32 kBodiesAhead = 2;

}  // namespace

b2ContactSolver::ContactSolver(b2ContactSolverDef* def)
    : m_step(def->step),
      m_positions(def->positions),
      m_velocities(def->velocities),
      m_positionConstraints(def->positionConstraints),
      m_velocityConstraints(def->velocityConstraints),
      m_rotations(def->rotations),
      m_contacts(def->contacts),
      m_laneRows(def->laneRows),
      m_count(def->count) {}

void b2ContactSolver::Load(int32 begin, int32 end) {
    // The constraint storage holds the previous island's values: every field read later is
    // written here or in InitializeVelocityConstraints (K and normalMass only for the block
    // solver, which alone reads them).
    const auto prefetchBodyAndShape = [](const b2Fixture* fixture) {
        const b2Body* body = fixture->m_body;
        __builtin_prefetch(&body->m_islandIndex);
        __builtin_prefetch(&body->m_sweep.localCenter);
        __builtin_prefetch(&body->m_invMass);
        __builtin_prefetch(&body->m_invI);
        __builtin_prefetch(&fixture->m_shape->m_radius);
    };
    for (int32 i = begin; i < end; ++i) {
        if (i + kContactAhead < m_count) {
            // Named by the fields read, not by offsets: the friction's line, the manifold's
            // point count (the manifold's last line) and the fixtures' line.
            const b2Contact* ahead = m_contacts[i + kContactAhead];
            __builtin_prefetch(&ahead->m_friction);
            __builtin_prefetch(&ahead->m_manifold.pointCount);
            __builtin_prefetch(&ahead->m_fixtureA);
        }
        if (i + kFixturesAhead < m_count) {
            const b2Contact* ahead = m_contacts[i + kFixturesAhead];
            __builtin_prefetch(&ahead->m_fixtureA->m_body);
            __builtin_prefetch(&ahead->m_fixtureB->m_body);
        }
        if (i + kBodiesAhead < m_count) {
            const b2Contact* ahead = m_contacts[i + kBodiesAhead];
            prefetchBodyAndShape(ahead->m_fixtureA);
            prefetchBodyAndShape(ahead->m_fixtureB);
        }
        b2Contact* contact = m_contacts[i];
        const b2Fixture* fixtureA = contact->m_fixtureA;
        const b2Fixture* fixtureB = contact->m_fixtureB;
        const b2Body* bodyA = fixtureA->GetBody();
        const b2Body* bodyB = fixtureB->GetBody();
        const b2Manifold* manifold = contact->GetManifold();
        const int32 pointCount = manifold->pointCount;

        b2ContactVelocityConstraint* vc = &m_velocityConstraints[static_cast<size_t>(i)];
        vc->friction = contact->m_friction;
        vc->restitution = contact->m_restitution;
        vc->indexA = bodyA->m_islandIndex;
        vc->indexB = bodyB->m_islandIndex;
        vc->invMassA = bodyA->m_invMass;
        vc->invMassB = bodyB->m_invMass;
        vc->invIA = bodyA->m_invI;
        vc->invIB = bodyB->m_invI;
        vc->contactIndex = i;
        vc->pointCount = pointCount;

        b2ContactPositionConstraint* pc = &m_positionConstraints[static_cast<size_t>(i)];
        pc->indexA = bodyA->m_islandIndex;
        pc->indexB = bodyB->m_islandIndex;
        pc->invMassA = bodyA->m_invMass;
        pc->invMassB = bodyB->m_invMass;
        pc->localCenterA = bodyA->m_sweep.localCenter;
        pc->localCenterB = bodyB->m_sweep.localCenter;
        pc->invIA = bodyA->m_invI;
        pc->invIB = bodyB->m_invI;
        pc->localNormal = manifold->localNormal;
        pc->localPoint = manifold->localPoint;
        pc->pointCount = pointCount;
        pc->radiusA = fixtureA->m_shape.get()->m_radius;
        pc->radiusB = fixtureB->m_shape.get()->m_radius;
        pc->type = manifold->type;

        for (int32 j = 0; j < pointCount; ++j) {
            const b2ManifoldPoint* cp = manifold->points + j;
            b2VelocityConstraintPoint* vcp = vc->points + j;
            if (m_step.warmStarting) {
                // dtRatio is exactly 1 for a fixed step (inv_dt is derived from dt).
                vcp->normalImpulse = WarmScaled(cp->normalImpulse, m_step.dtRatio);
                vcp->tangentImpulse = WarmScaled(cp->tangentImpulse, m_step.dtRatio);
            } else {
                vcp->normalImpulse = Wide();
                vcp->tangentImpulse = Wide();
            }
            pc->localPoints[j] = cp->localPoint;
        }
#ifdef LOCKBOX_UNCHECKED_ROWS
        pc->unchecked = solver::FacePositionWidths(*pc);
#else
        pc->unchecked = b2ContactPositionConstraint::Widths();
#endif
    }
}

void b2ContactSolver::SetUp(int32 begin, int32 end) {
    // A large island's constraints do not fit in the cache: copied in one pass and set up in
    // another, each row would be fetched from memory twice (and its lane row a third time).
    // Each contact's set-up reads only its own copy, so any grouping gives the same bits.
    constexpr int32 kContactsPerGroup = 32;
    for (int32 first = begin; first < end; first += kContactsPerGroup) {
        const int32 last = b2Min(end, first + kContactsPerGroup);
        Load(first, last);
        InitializeVelocityConstraints(first, last);
    }
}

void b2ContactSolver::InitializeVelocityConstraints(int32 begin, int32 end) {
    const bool uncheckedAllowed = solver::UncheckedRowsAllowed();
    for (int32 i = begin; i < end; ++i) {
        b2ContactVelocityConstraint* vc = &m_velocityConstraints[static_cast<size_t>(i)];
        const b2ContactPositionConstraint* pc = &m_positionConstraints[static_cast<size_t>(i)];
        const b2Manifold* manifold = m_contacts[vc->contactIndex]->GetManifold();

        const Wide mA = vc->invMassA, mB = vc->invMassB;
        const Wide iA = vc->invIA, iB = vc->invIB;
        const b2Vec2 cA = m_positions[vc->indexA].c;
        const Fixed aA = m_positions[vc->indexA].a;
        const b2Vec2 cB = m_positions[vc->indexB].c;
        const Fixed aB = m_positions[vc->indexB].a;

        b2Transform xfA, xfB;
        xfA.q = m_rotations[vc->indexA].For(aA);
        xfB.q = m_rotations[vc->indexB].For(aB);
        xfA.p = solver::BodyOrigin(cA, xfA.q, pc->localCenterA);
        xfB.p = solver::BodyOrigin(cB, xfB.q, pc->localCenterB);

        b2WorldManifold worldManifold;
        worldManifold.Initialize(manifold, xfA, pc->radiusA, xfB, pc->radiusB);

        vc->normal = worldManifold.normal;
        vc->tangent = b2Cross(vc->normal, Fixed(1));
        b2WideSym22 K = SetUpPoints(*vc, worldManifold.points, cA, cB, m_velocities[vc->indexA],
                                    m_velocities[vc->indexB], uncheckedAllowed);
        vc->samePush = vc->pushA.x == vc->pushB.x && vc->pushA.y == vc->pushB.y;

        // Two points: prepare the block solver if K is well conditioned, else keep one point.
        if (vc->pointCount == 2) {
            const b2VelocityConstraintPoint& p1 = vc->points[0];
            const b2VelocityConstraintPoint& p2 = vc->points[1];
            // Every term of the denominator is >= 0, so a saturation leaves it at +max; only
            // then is it evaluated again, to report the overflow as often as before.
            if (K.k11.Raw() == Wide::kMaxRaw) K.k11 = solver::EffectiveInverseMass(mA, mB, iA, iB, p1.rnA, p1.rnB);
            if (K.k22.Raw() == Wide::kMaxRaw) K.k22 = solver::EffectiveInverseMass(mA, mB, iA, iB, p2.rnA, p2.rnB);
            b2WideSym22 inverse;
            if (InvertBlock(K, &inverse)) {
                vc->K = K;
                vc->normalMass = inverse;
                vc->useBlock = true;
            } else {
                // The constraints are redundant: solve only the first point.
                vc->pointCount = 1;
                vc->useBlock = false;
            }
        }
#ifdef LOCKBOX_UNCHECKED_ROWS
        vc->unchecked = solver::UncheckedWidths(*vc);
#else
        vc->unchecked = solver::InputWidths();
#endif
    }
    if (m_laneRows != nullptr) StoreLaneRows(begin, end);
}

void b2ContactSolver::WarmStart(int32 begin, int32 end) {
    for (int32 i = begin; i < end; ++i) {
        const b2ContactVelocityConstraint* vc = &m_velocityConstraints[static_cast<size_t>(i)];
        b2WideVec2 vA = m_velocities[vc->indexA].v;
        Wide wA = m_velocities[vc->indexA].w;
        b2WideVec2 vB = m_velocities[vc->indexB].v;
        Wide wB = m_velocities[vc->indexB].w;
        // The tangent (n.y, -n.x) moves a body by (push.y, -push.x) per N*s.
        const b2WideVec2 pA = vc->pushA, pB = vc->pushB;
        for (int32 j = 0; j < vc->pointCount; ++j) {
            const b2VelocityConstraintPoint* vcp = vc->points + j;
            const Wide n = vcp->normalImpulse, t = vcp->tangentImpulse;
            const Wide dxA = n * pA.x + t * pA.y;
            const Wide dyA = n * pA.y - t * pA.x;
            vA.x -= dxA;
            vA.y -= dyA;
            if (vc->samePush) {
                vB.x += dxA;
                vB.y += dyA;
            } else {
                vB.x += n * pB.x + t * pB.y;
                vB.y += n * pB.y - t * pB.x;
            }
            wA -= n * vcp->turnNA + t * vcp->turnTA;
            wB += n * vcp->turnNB + t * vcp->turnTB;
        }
        solver::Store(m_velocities[vc->indexA], vA, wA, vc->invMassA, vc->invIA);
        solver::Store(m_velocities[vc->indexB], vB, wB, vc->invMassB, vc->invIB);
    }
}

void b2ContactSolver::SolveVelocityConstraints(int32 begin, int32 end) {
#ifdef LOCKBOX_UNCHECKED_ROWS
    const bool uncheckedAllowed = solver::UncheckedRowsAllowed();
#endif
    for (int32 i = begin; i < end; ++i) {
        b2ContactVelocityConstraint& vc = m_velocityConstraints[static_cast<size_t>(i)];
        b2Velocity& bodyA = m_velocities[vc.indexA];
        b2Velocity& bodyB = m_velocities[vc.indexB];
#ifdef LOCKBOX_UNCHECKED_ROWS
        if (uncheckedAllowed && solver::UncheckedRowFits(vc, bodyA.v, bodyA.w, bodyB.v, bodyB.w)) {
            auto vA = solver::UncheckedVec2::From(bodyA.v), vB = solver::UncheckedVec2::From(bodyB.v);
            solver::UncheckedWide wA = bodyA.w, wB = bodyB.w;
            solver::SolveContactRow(vc, vA, wA, vB, wB);
            solver::Store(bodyA, vA.ToWide(), wA.ToWide(), vc.invMassA, vc.invIA);
            solver::Store(bodyB, vB.ToWide(), wB.ToWide(), vc.invMassB, vc.invIB);
            continue;
        }
#endif
        b2WideVec2 vA = bodyA.v;
        Wide wA = bodyA.w;
        b2WideVec2 vB = bodyB.v;
        Wide wB = bodyB.w;
        solver::SolveContactRow(vc, vA, wA, vB, wB);
        solver::Store(bodyA, vA, wA, vc.invMassA, vc.invIA);
        solver::Store(bodyB, vB, wB, vc.invMassB, vc.invIB);
    }
}

void b2ContactSolver::StoreImpulses(int32 begin, int32 end) {
    for (int32 i = begin; i < end; ++i) {
        const b2ContactVelocityConstraint* vc = &m_velocityConstraints[static_cast<size_t>(i)];
        b2Manifold* manifold = m_contacts[vc->contactIndex]->GetManifold();
        for (int32 j = 0; j < vc->pointCount; ++j) {
            manifold->points[j].normalImpulse = vc->points[j].normalImpulse;
            manifold->points[j].tangentImpulse = vc->points[j].tangentImpulse;
        }
    }
}

}  // namespace lockbox
