#pragma once
/// @file
/// b2MouseJoint (Box2D 2.2.1): a soft spring pulling a point on body B toward a world target,
/// with a force cap. bodyA is ignored (use any body, usually the ground).
///
/// maxForce is Q32.32: the testbed's 1000 * mass reaches 1e6 N for a 1000 kg body, beyond
/// Q16.16 (docs/numerics.md, "Formats").

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Mouse joint definition: the world target, the force cap and the spring (frequency and
/// damping ratio). Set target to the grabbed point of bodyB when creating the joint.
struct b2MouseJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2MouseJointDef() { type = e_mouseJoint; }

    b2Vec2 target;                    ///< initial world target, m (also the grab point on B)
    Wide maxForce;                    ///< N, >= 0 (Q32.32, up to ~2e9)
    Fixed frequencyHz = 5;            ///< response speed, Hz, in (0, 30]
    Fixed dampingRatio = Fixed(0.7);  ///< 0 = no damping, 1 = critical
};

/// A mouse joint: a soft spring drags a point of body B toward a world target, with at most
/// maxForce and no restriction on rotation. Made for dragging bodies in a testbed; for precise
/// game-play positioning a kinematic body works better.
class LOCKBOX_API b2MouseJoint : public b2Joint {
public:
    /// The target point, m.
    b2Vec2 GetAnchorA() const override;
    /// The grab point on B, m.
    b2Vec2 GetAnchorB() const override;
    /// Force on B, N (saturates at 32768 N: read GetImpulse for larger forces).
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Always 0.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Moves the target, m (wakes body B).
    void SetTarget(const b2Vec2& target);
    /// The target point, m.
    const b2Vec2& GetTarget() const noexcept { return m_targetA; }
    /// The grab point in body B's frame, m (the definition's target, taken into B's frame).
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// Maximum force, N.
    void SetMaxForce(Wide force) noexcept { m_maxForce = force; }
    /// Maximum force, N.
    Wide GetMaxForce() const noexcept { return m_maxForce; }
    /// Response frequency, Hz.
    void SetFrequency(Fixed hz) noexcept { m_frequencyHz = hz; }
    /// Spring frequency, Hz.
    Fixed GetFrequency() const noexcept { return m_frequencyHz; }
    /// Damping ratio of the spring (dimensionless, >= 0; 1 is critical damping).
    void SetDampingRatio(Fixed ratio) noexcept { m_dampingRatio = ratio; }
    /// Damping ratio (dimensionless).
    Fixed GetDampingRatio() const noexcept { return m_dampingRatio; }
    /// Accumulated impulse of the last step, N*s (Q32.32, never saturated).
    const b2WideVec2& GetImpulse() const noexcept { return m_impulse; }

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2MouseJoint(const b2MouseJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2MouseJoint(b2RestoreTag tag) : b2Joint(tag, e_mouseJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_localAnchorB, m_targetA, m_maxForce, m_frequencyHz, m_dampingRatio, m_impulse);
    }

    b2Vec2 m_localAnchorB;
    b2Vec2 m_targetA;
    Fixed m_frequencyHz;
    Fixed m_dampingRatio;
    Wide m_beta;  ///< 1/s
    b2WideVec2 m_impulse;
    Wide m_maxForce;
    Wide m_gamma;  ///< 1/kg

    int32 m_indexB = 0;
    b2Vec2 m_rB;
    b2Vec2 m_localCenterB;
    Wide m_invMassB, m_invIB;
    b2WideSolver22 m_K;  ///< the effective-mass matrix, prepared once per step; solved, never inverted
    b2WideVec2 m_C;      ///< beta * position error, m/s
};

}  // namespace lockbox
