#pragma once
/// @file
/// b2WheelJoint (Box2D 2.2.1): B's anchor slides on a line fixed in A (the suspension axis)
/// with a spring along it, and B rotates freely with an optional motor. For vehicles.

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Wheel joint definition: the local anchors and suspension axis, the spring and the motor.
/// Initialize fills the anchors and axis from the bodies' current poses and a world axis.
struct LOCKBOX_API b2WheelJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2WheelJointDef() {
        type = e_wheelJoint;
        localAxisA.Set(1, 0);
    }

    /// Bodies, anchors from one world point (m) and the axis from a world direction.
    void Initialize(b2Body* bodyA, b2Body* bodyB, const b2Vec2& anchor, const b2Vec2& axis);

    b2Vec2 localAnchorA;              ///< m, relative to A's origin
    b2Vec2 localAnchorB;              ///< m, relative to B's origin
    b2Vec2 localAxisA;                ///< suspension axis in A's frame (unit length)
    bool enableMotor = false;         ///< drive the wheel's rotation?
    Fixed maxMotorTorque;             ///< N*m, >= 0
    Fixed motorSpeed;                 ///< rad/s
    Fixed frequencyHz = 2;            ///< suspension frequency, Hz, in [0, 30]; 0 = rigid axle
    Fixed dampingRatio = Fixed(0.7);  ///< suspension damping ratio
};

/// A wheel joint: body B's anchor moves along a line fixed in body A, held by a spring along
/// that line (the suspension), and B turns freely about the anchor, optionally driven by a motor.
class LOCKBOX_API b2WheelJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Line plus spring reaction on B, N.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Motor torque on B, N*m.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Anchor on body A in A's frame, m.
    const b2Vec2& GetLocalAnchorA() const noexcept { return m_localAnchorA; }
    /// Anchor on body B in B's frame, m.
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// Axis in body A's frame (unit length).
    const b2Vec2& GetLocalAxisA() const noexcept { return m_localXAxisA; }

    /// Translation along the axis, m.
    Fixed GetJointTranslation() const;
    /// Relative angular speed wB - wA, rad/s.
    Fixed GetJointSpeed() const;

    /// Whether the motor is enabled.
    bool IsMotorEnabled() const noexcept { return m_enableMotor; }
    /// Enables or disables the motor (wakes the bodies).
    void EnableMotor(bool flag);
    /// Target speed, rad/s.
    void SetMotorSpeed(Fixed speed);
    /// Target motor speed.
    Fixed GetMotorSpeed() const noexcept { return m_motorSpeed; }
    /// Maximum motor torque, N*m.
    void SetMaxMotorTorque(Fixed torque);
    /// Maximum motor torque, N*m.
    Fixed GetMaxMotorTorque() const noexcept { return m_maxMotorTorque; }
    /// Motor torque applied in the last step, N*m.
    Fixed GetMotorTorque(Fixed inv_dt) const;

    /// Suspension frequency, Hz (0 disables the spring).
    void SetSpringFrequencyHz(Fixed hz) noexcept { m_frequencyHz = hz; }
    /// Suspension frequency, Hz.
    Fixed GetSpringFrequencyHz() const noexcept { return m_frequencyHz; }
    /// Suspension damping ratio.
    void SetSpringDampingRatio(Fixed ratio) noexcept { m_dampingRatio = ratio; }
    /// Suspension damping ratio.
    Fixed GetSpringDampingRatio() const noexcept { return m_dampingRatio; }

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2WheelJoint(const b2WheelJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2WheelJoint(b2RestoreTag tag) : b2Joint(tag, e_wheelJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_localAnchorA, m_localAnchorB, m_localXAxisA, m_localYAxisA, m_enableMotor, m_motorSpeed, m_maxMotorTorque,
          m_frequencyHz, m_dampingRatio, m_impulse, m_motorImpulse, m_springImpulse);
    }
    /// Visits the directions the last solve computed that GetReactionForce/GetReactionTorque
    /// read (solver temporaries, not state a step depends on): the snapshot carries them so a
    /// restored joint answers those queries as the saved one did.
    template <class V>
    void VisitReactionState(V& v) {
        v(m_ax, m_ay);
    }

    Fixed m_frequencyHz;
    Fixed m_dampingRatio;
    b2Vec2 m_localAnchorA;
    b2Vec2 m_localAnchorB;
    b2Vec2 m_localXAxisA;
    b2Vec2 m_localYAxisA;

    Wide m_impulse;        ///< line constraint, N*s
    Wide m_motorImpulse;   ///< N*m*s
    Wide m_springImpulse;  ///< N*s
    Fixed m_maxMotorTorque;
    Fixed m_motorSpeed;
    bool m_enableMotor;

    int32 m_indexA = 0;
    int32 m_indexB = 0;
    b2Vec2 m_localCenterA;
    b2Vec2 m_localCenterB;
    Wide m_invMassA, m_invMassB, m_invIA, m_invIB;
    b2Vec2 m_ax, m_ay;
    Fixed m_sAx, m_sBx, m_sAy, m_sBy;  ///< arms, m
    Wide m_mass;                       ///< kg
    Wide m_motorMass;                  ///< kg*m^2
    Wide m_springMass;                 ///< kg
    Wide m_bias;                       ///< m/s
    Wide m_gamma;                      ///< 1/kg
};

}  // namespace lockbox
