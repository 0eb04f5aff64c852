#pragma once
/// @file
/// b2FrictionJoint (Box2D 2.2.1): top-down friction. Resists relative linear and angular
/// motion with at most maxForce and maxTorque.

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Friction joint definition: the local anchors and the force and torque limits. Initialize
/// fills the anchors from one world point.
struct LOCKBOX_API b2FrictionJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2FrictionJointDef() { type = e_frictionJoint; }

    /// Bodies and local anchors from one world anchor (m).
    void Initialize(b2Body* bodyA, b2Body* bodyB, const b2Vec2& anchor);

    b2Vec2 localAnchorA;  ///< m, relative to A's origin
    b2Vec2 localAnchorB;  ///< m, relative to B's origin
    Fixed maxForce;       ///< N, >= 0
    Fixed maxTorque;      ///< N*m, >= 0
};

/// A friction joint: top-down friction between A and B, resisting their relative linear motion
/// with at most maxForce and their relative rotation with at most maxTorque.
class LOCKBOX_API b2FrictionJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Friction force on B, N.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Friction torque on B, N*m.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Anchor on body A in A's frame, m.
    const b2Vec2& GetLocalAnchorA() const noexcept { return m_localAnchorA; }
    /// Anchor on body B in B's frame, m.
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// Maximum friction force, N (>= 0).
    void SetMaxForce(Fixed force) noexcept { m_maxForce = force; }
    /// Maximum force, N.
    Fixed GetMaxForce() const noexcept { return m_maxForce; }
    /// Maximum friction torque, N*m (>= 0).
    void SetMaxTorque(Fixed torque) noexcept { m_maxTorque = torque; }
    /// Maximum torque, N*m.
    Fixed GetMaxTorque() const noexcept { return m_maxTorque; }

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2FrictionJoint(const b2FrictionJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2FrictionJoint(b2RestoreTag tag) : b2Joint(tag, e_frictionJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_localAnchorA, m_localAnchorB, m_maxForce, m_maxTorque, m_linearImpulse, m_angularImpulse);
    }

    b2Vec2 m_localAnchorA;
    b2Vec2 m_localAnchorB;
    b2WideVec2 m_linearImpulse;  ///< N*s
    Wide m_angularImpulse;       ///< N*m*s
    Fixed m_maxForce;
    Fixed m_maxTorque;

    int32 m_indexA = 0;
    int32 m_indexB = 0;
    b2Vec2 m_rA, m_rB;
    b2Vec2 m_localCenterA;
    b2Vec2 m_localCenterB;
    Wide m_invMassA, m_invMassB, m_invIA, m_invIB;
    b2WideSolver22 m_linearK;  ///< linear effective-mass matrix, prepared once per step; solved, never inverted
    Wide m_angularMass;        ///< kg*m^2
};

}  // namespace lockbox
