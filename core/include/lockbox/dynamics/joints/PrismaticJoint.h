#pragma once
/// @file
/// b2PrismaticJoint (Box2D 2.2.1): one translational degree of freedom along an axis fixed in
/// body A, no relative rotation, with an optional translation limit and motor.

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Prismatic joint definition: the local anchors and axis, the reference angle, and the limit
/// and motor settings. Initialize fills them from the bodies' current poses and a world axis.
struct LOCKBOX_API b2PrismaticJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2PrismaticJointDef() {
        type = e_prismaticJoint;
        localAxisA.Set(1, 0);
    }

    /// Bodies, anchors from one world point (m), the axis from a world direction (normalised
    /// here), and the reference angle from the current angles.
    void Initialize(b2Body* bodyA, b2Body* bodyB, const b2Vec2& anchor, const b2Vec2& axis);

    b2Vec2 localAnchorA;       ///< m, relative to A's origin
    b2Vec2 localAnchorB;       ///< m, relative to B's origin
    b2Vec2 localAxisA;         ///< translation axis in A's frame (unit length)
    Fixed referenceAngle;      ///< angleB - angleA in the reference state, rad
    bool enableLimit = false;  ///< enforce [lowerTranslation, upperTranslation]?
    Fixed lowerTranslation;    ///< m
    Fixed upperTranslation;    ///< m, >= lowerTranslation
    bool enableMotor = false;  ///< drive the translation speed?
    Fixed maxMotorForce;       ///< N, >= 0
    Fixed motorSpeed;          ///< m/s
};

/// A prismatic joint: body B slides relative to body A along an axis fixed in A, without
/// relative rotation; the one degree of freedom is the joint translation (m, zero for a
/// definition made by Initialize). Like the revolute joint it has an optional limit and a
/// motor, with force in place of torque.
class LOCKBOX_API b2PrismaticJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Perpendicular plus limit/motor reaction on B, N.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Angular reaction on B, N*m.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Anchor on body A in A's frame, m.
    const b2Vec2& GetLocalAnchorA() const noexcept { return m_localAnchorA; }
    /// Anchor on body B in B's frame, m.
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// Axis in body A's frame (unit length).
    const b2Vec2& GetLocalAxisA() const noexcept { return m_localXAxisA; }
    /// Reference angle angleB - angleA, rad.
    Fixed GetReferenceAngle() const noexcept { return m_referenceAngle; }

    /// Translation of B's anchor from A's along the axis, m.
    Fixed GetJointTranslation() const;
    /// Translation speed, m/s.
    Fixed GetJointSpeed() const;

    /// Whether the limit is enforced.
    bool IsLimitEnabled() const noexcept { return m_enableLimit; }
    /// Enables or disables the limit (wakes the bodies).
    void EnableLimit(bool flag);
    /// Lower bound of the joint translation, m (include 0, or the joint lurches at the start).
    Fixed GetLowerLimit() const noexcept { return m_lowerTranslation; }
    /// Upper bound of the joint translation, m (>= the lower bound).
    Fixed GetUpperLimit() const noexcept { return m_upperTranslation; }
    /// Sets the limits, m (lower <= upper; wakes the bodies).
    void SetLimits(Fixed lower, Fixed upper);

    /// Whether the motor is enabled.
    bool IsMotorEnabled() const noexcept { return m_enableMotor; }
    /// Enables or disables the motor (wakes the bodies).
    void EnableMotor(bool flag);
    /// Target speed, m/s.
    void SetMotorSpeed(Fixed speed);
    /// Target motor speed.
    Fixed GetMotorSpeed() const noexcept { return m_motorSpeed; }
    /// Maximum motor force, N.
    void SetMaxMotorForce(Fixed force);
    /// Maximum motor force, N.
    Fixed GetMaxMotorForce() const noexcept { return m_maxMotorForce; }
    /// Motor force applied in the last step, N.
    Fixed GetMotorForce(Fixed inv_dt) const;

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2PrismaticJoint(const b2PrismaticJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    // Read by the gear joint.
    b2Vec2 m_localAnchorA;
    b2Vec2 m_localAnchorB;
    b2Vec2 m_localXAxisA;
    b2Vec2 m_localYAxisA;
    Fixed m_referenceAngle;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2PrismaticJoint(b2RestoreTag tag) : b2Joint(tag, e_prismaticJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_localAnchorA, m_localAnchorB, m_localXAxisA, m_localYAxisA, m_referenceAngle, m_enableLimit,
          m_lowerTranslation, m_upperTranslation, m_enableMotor, m_motorSpeed, m_maxMotorForce, m_impulse,
          m_motorImpulse, m_limitState);
    }
    /// Visits the directions the last solve computed that GetReactionForce/GetReactionTorque
    /// read (solver temporaries, not state a step depends on): the snapshot carries them so a
    /// restored joint answers those queries as the saved one did.
    template <class V>
    void VisitReactionState(V& v) {
        v(m_axis, m_perp);
    }

    b2WideVec3 m_impulse;  ///< perpendicular (N*s), angular (N*m*s), axial limit (N*s)
    Wide m_motorImpulse;   ///< N*s
    Fixed m_lowerTranslation;
    Fixed m_upperTranslation;
    Fixed m_maxMotorForce;
    Fixed m_motorSpeed;
    bool m_enableLimit;
    bool m_enableMotor;
    b2LimitState m_limitState = e_inactiveLimit;

    int32 m_indexA = 0;
    int32 m_indexB = 0;
    b2Vec2 m_localCenterA;
    b2Vec2 m_localCenterB;
    Wide m_invMassA, m_invMassB, m_invIA, m_invIB;
    b2Vec2 m_axis, m_perp;
    Fixed m_s1, m_s2;  ///< arms of the perpendicular constraint, m
    Fixed m_a1, m_a2;  ///< arms of the axial constraint, m
    b2WideMat33 m_K;
    b2WideSolver22 m_pointSolver;  ///< m_K's upper block, prepared once per step
    b2WideMat22 m_pointMass;       ///< its inverse, once per step: the point iterations' product
    b2WideSolver33 m_limitSolver;  ///< m_K, prepared once per step while the limit is solved
    Wide m_motorMass;              ///< kg
};

}  // namespace lockbox
