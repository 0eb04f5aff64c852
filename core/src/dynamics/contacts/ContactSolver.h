#pragma once
/// b2ContactSolver (Box2D 2.2.1 b2ContactSolver.h): sequential impulses with warm starting,
/// the two-point block solver, restitution above b2_velocityThreshold, Coulomb friction,
/// non-linear position correction and the time-of-impact position solve.
///
/// Formats: positions are Fixed; velocities (the solver's Q32.32 copies), masses, inverse masses and inertias,
/// effective masses (normalMass, tangentMass, K and its inverse) and impulses are Wide (Q32.32). The block solver's
/// condition test k11^2 < 1000 (k11 k22 - k12^2) is evaluated exactly in 128 bits (NUMERICS Table 1: it overflows
/// Q32.32).

#include "Engine.h"
#include "dynamics/TimeStep.h"
#include "dynamics/unchecked/Widths.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"
#include "lockbox/fixed/WideVec.h"

namespace lockbox {

class b2Contact;

/// A symmetric 2x2 matrix of Wide entries (the block solver's K and its inverse).
struct b2WideSym22 {
    Wide k11, k12, k22;
};

/// Per-point velocity data. The iterations never need the anchors themselves: a point's
/// speed along a direction d is d . (vB - vA) + wB (rB x d) - wA (rA x d), and an impulse
/// lambda d moves body A by mA lambda d and turns it by iA lambda (rA x d); so the lever arms
/// (r x d), the angular responses iA (rA x d) and the linear ones mA d (per contact) are
/// computed once per step.
struct b2VelocityConstraintPoint {
    Wide normalImpulse;   ///< accumulated, N*s
    Wide tangentImpulse;  ///< accumulated, N*s
    Wide normalMass;      ///< 1 / K_normal, kg
    Wide tangentMass;     ///< 1 / K_tangent, kg
    Wide turnNA, turnNB;  ///< iA (rA x normal), iB (rB x normal): rad/s per N*s
    Wide turnTA, turnTB;  ///< the same for the tangent
    Fixed velocityBias;   ///< restitution target, m/s
    Fixed rnA, rnB;       ///< rA x normal, rB x normal, m
    Fixed rtA, rtB;       ///< rA x tangent, rB x tangent, m
};

/// One contact's velocity constraint.
struct b2ContactVelocityConstraint {
    b2VelocityConstraintPoint points[b2_maxManifoldPoints];
    b2Vec2 normal;           ///< unit, from A to B
    b2Vec2 tangent;          ///< b2Cross(normal, 1), computed once per step (unit)
    b2WideVec2 pushA;        ///< invMassA * normal, m/s per N*s (the tangent's is (y, -x))
    b2WideVec2 pushB;        ///< invMassB * normal
    bool samePush = false;   ///< pushA == pushB: B's linear change is A's, computed once
    b2WideSym22 normalMass;  ///< inverse of K (block solver only)
    b2WideSym22 K;           ///< block solver matrix, 1/kg
    int32 indexA = 0, indexB = 0;
    Wide invMassA, invMassB;
    Wide invIA, invIB;
    Fixed friction;
    Fixed restitution;
    int32 pointCount = 0;
    int32 contactIndex = 0;
    bool useBlock = false;          ///< two points and a well-conditioned K
    solver::InputWidths unchecked;  ///< when the row may run without range tests (ContactRowBound.h)
};

/// One contact's position constraint (copied from the manifold).
struct b2ContactPositionConstraint {
    /// The widest values for which a face manifold's correction may run without range tests,
    /// set with the constraint each step (ContactPositionBound.h; 0: none): the bodies' centres
    /// and angles, then, once formed, the reference face's body's arm to the point and the
    /// correction impulse.
    struct Widths {
        uint8_t poses = 0;
        uint8_t arm = 0;
        uint8_t impulses = 0;
    };

    b2Vec2 localPoints[b2_maxManifoldPoints];
    b2Vec2 localNormal;
    b2Vec2 localPoint;
    int32 indexA = 0, indexB = 0;
    Wide invMassA, invMassB;
    b2Vec2 localCenterA, localCenterB;
    Wide invIA, invIB;
    b2Manifold::Type type = b2Manifold::e_circles;
    Fixed radiusA, radiusB;
    int32 pointCount = 0;
    Widths unchecked;  ///< when a face manifold's correction may run without range tests
};

/// One field of four consecutive constraints, aligned for one vector load: the unit of the
/// contact lanes' rows. The lanes take quads that begin at a multiple of kConstraints.
struct alignas(32) b2LaneQuad {
    static constexpr int32 kConstraints = 4;
    int64_t lane[kConstraints];

    /// The first quad boundary at or after constraint i, and the last at or before it.
    static constexpr int32 CeilBoundary(int32 i) noexcept { return (i + kConstraints - 1) & ~(kConstraints - 1); }
    static constexpr int32 FloorBoundary(int32 i) noexcept { return i & ~(kConstraints - 1); }
};

/// Input to the contact solver.
struct b2ContactSolverDef {
    b2TimeStep step;
    b2Contact** contacts = nullptr;
    int32 count = 0;
    b2Position* positions = nullptr;
    b2Velocity* velocities = nullptr;
    /// Room for `count` constraints of each kind, owned by the caller and reused between
    /// islands and steps (no allocation per island). The solver writes every field it reads.
    b2ContactPositionConstraint* positionConstraints = nullptr;
    b2ContactVelocityConstraint* velocityConstraints = nullptr;
    /// One entry per island body (indexed like positions), reused likewise.
    b2CachedRot* rotations = nullptr;
    /// Room for LaneRowsSize(count) quads, or null: the velocity constraints' constants by
    /// quads of constraints, for SolveIndependentVelocityConstraints' lanes (written by the
    /// set-up).
    b2LaneQuad* laneRows = nullptr;
};

/// Solves the contacts of one island.
class core_detail::Engine::ContactSolver {
public:
    /// A solver over def's contacts; Load copies their data in.
    explicit ContactSolver(b2ContactSolverDef* def);

    /// Copies the constraint data of every contact; warm-start impulses are scaled by dtRatio.
    void Load() { Load(0, m_count); }
    /// The same for contacts [begin, end) (each writes only its own constraints).
    void Load(int32 begin, int32 end);

    /// Anchors, effective masses, restitution bias and the block-solver matrices.
    void InitializeVelocityConstraints() { InitializeVelocityConstraints(0, m_count); }
    /// The same for constraints [begin, end) (each reads the bodies and writes only itself).
    void InitializeVelocityConstraints(int32 begin, int32 end);
    /// Load and InitializeVelocityConstraints for contacts [begin, end), a few contacts at a
    /// time, so that the set-up reads each constraint while its copy is still in the cache.
    void SetUp(int32 begin, int32 end);
    void SetUp() { SetUp(0, m_count); }
    /// Applies the accumulated impulses of the previous step.
    void WarmStart() { WarmStart(0, m_count); }
    /// The same for constraints [begin, end), in order.
    void WarmStart(int32 begin, int32 end);
    /// One velocity iteration: friction, then normal (block solver for two points).
    void SolveVelocityConstraints() { SolveVelocityConstraints(0, m_count); }
    /// The same for constraints [begin, end), in order.
    void SolveVelocityConstraints(int32 begin, int32 end);
    /// The same for constraints [begin, end) of which no two write the same body (one colour of
    /// a coloured island): the same bits, four constraints at a time where the machine has
    /// 64-bit integer lanes (ContactSolverLanes.cpp). Returns how many the lanes solved.
    int32 SolveIndependentVelocityConstraints(int32 begin, int32 end);
    /// Whether this machine can take SolveIndependentVelocityConstraints in lanes (x86-64 with
    /// AVX2).
    static bool LanesAvailable() noexcept;
    /// The lane rows' size for `count` constraints (quads).
    static size_t LaneRowsSize(int32 count) noexcept;
    /// Copies the constants of velocity constraints [begin, end) into the lane rows (the set-up
    /// does it when the definition has lane rows).
    void StoreLaneRows(int32 begin, int32 end);
    /// Lets the lanes run (the default) or not. Both paths give the same bits; tests compare them.
    static void AllowLanes(bool allow) noexcept;
    /// Copies the accumulated impulses back to the manifolds for warm starting.
    void StoreImpulses() { StoreImpulses(0, m_count); }
    /// The same for constraints [begin, end) (each writes its own contact's manifold).
    void StoreImpulses(int32 begin, int32 end);
    /// One position iteration; true when the largest overlap is within 3 linearSlop.
    bool SolvePositionConstraints() { return PositionAccepted(SolvePositionConstraints(0, m_count)); }
    /// One position pass over constraints [begin, end), in order; returns the smallest
    /// separation seen (m, <= 0).
    Fixed SolvePositionConstraints(int32 begin, int32 end);
    /// Whether a position iteration whose smallest separation was minSeparation is done: Box2D
    /// accepts an overlap of up to 3 linearSlop, since it pushes the separation to -linearSlop.
    static bool PositionAccepted(Fixed minSeparation) noexcept {
        return minSeparation >= Fixed::FromRaw(-3 * b2_linearSlop.Raw());
    }
    /// One TOI position iteration moving only bodies toiIndexA and toiIndexB; true when the
    /// largest overlap is less than 1.5 linearSlop.
    bool SolveTOIPositionConstraints(int32 toiIndexA, int32 toiIndexB);

    b2TimeStep m_step;
    b2Position* m_positions;
    b2Velocity* m_velocities;
    b2ContactPositionConstraint* m_positionConstraints;
    b2ContactVelocityConstraint* m_velocityConstraints;
    b2CachedRot* m_rotations;
    b2Contact** m_contacts;
    b2LaneQuad* m_laneRows;
    int32 m_count;
};

using b2ContactSolver = core_detail::Engine::ContactSolver;

}  // namespace lockbox
