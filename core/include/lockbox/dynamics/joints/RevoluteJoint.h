#pragma once
/// @file
/// b2RevoluteJoint (Box2D 2.2.1): a shared point (hinge) with an optional angle limit and motor.
///
/// Body angles are wrapped into [-pi, pi) every step (docs/dynamics.md), so the joint keeps its
/// own continuous angle: each step it moves to the branch of aB - aA - referenceAngle nearest
/// to the previous value (the relative rotation per step is below pi). Limits may therefore
/// span many turns (keep them within +-16000 rad, half the Q16.16 range).

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Range of the continuous joint angle without a limit, rad: 8192 rad (1303 turns) leaves a
/// 4x margin to the Q16.16 limit for the differences formed from it. Past it a joint without
/// limit restarts from its wrapped angle (see b2RevoluteJoint::GetJointAngle).
inline constexpr Fixed kMaxContinuousAngle = 8192;

/// Revolute joint definition: the local anchors, the reference angle, and the limit and motor
/// settings. Initialize fills the anchors and reference angle from the bodies' current poses.
struct LOCKBOX_API b2RevoluteJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2RevoluteJointDef() { type = e_revoluteJoint; }

    /// Bodies, local anchors from one world anchor (m), and the reference angle from the
    /// bodies' current angles.
    void Initialize(b2Body* bodyA, b2Body* bodyB, const b2Vec2& anchor);

    b2Vec2 localAnchorA;       ///< m, relative to A's origin
    b2Vec2 localAnchorB;       ///< m, relative to B's origin
    Fixed referenceAngle;      ///< angleB - angleA in the reference state, rad
    bool enableLimit = false;  ///< enforce [lowerAngle, upperAngle]?
    Fixed lowerAngle;          ///< rad, may be many turns (|value| <= 16000)
    Fixed upperAngle;          ///< rad, >= lowerAngle
    bool enableMotor = false;  ///< drive the relative angular speed?
    Fixed motorSpeed;          ///< rad/s
    Fixed maxMotorTorque;      ///< N*m, >= 0
};

/// A revolute joint: bodies A and B share one anchor point (a hinge) and keep one degree of
/// freedom, their relative rotation (the joint angle, rad, positive when B turns
/// counter-clockwise relative to A, zero for a definition made by Initialize). An optional
/// limit keeps the angle in [lower, upper] with whatever torque it takes; an optional motor
/// drives the joint speed toward a target with at most maxMotorTorque (speed 0 with a small
/// torque acts as joint friction).
class LOCKBOX_API b2RevoluteJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Point reaction on B, N.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Limit reaction torque on B, N*m (the motor torque is GetMotorTorque).
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Anchor on body A in A's frame, m.
    const b2Vec2& GetLocalAnchorA() const noexcept { return m_localAnchorA; }
    /// Anchor on body B in B's frame, m.
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// Reference angle angleB - angleA, rad.
    Fixed GetReferenceAngle() const noexcept { return m_referenceAngle; }

    /// Continuous joint angle angleB - angleA - referenceAngle, rad: counts whole turns. With
    /// the limit disabled it restarts from the wrapped angle beyond +-kMaxContinuousAngle.
    Fixed GetJointAngle() const;
    /// Relative angular speed wB - wA, rad/s.
    Fixed GetJointSpeed() const;

    /// Whether the limit is enforced.
    bool IsLimitEnabled() const noexcept { return m_enableLimit; }
    /// Enables or disables the limit (wakes the bodies).
    void EnableLimit(bool flag);
    /// Lower bound of the joint angle, rad (include 0, or the joint lurches at the start).
    Fixed GetLowerLimit() const noexcept { return m_lowerAngle; }
    /// Upper bound of the joint angle, rad (>= the lower bound).
    Fixed GetUpperLimit() const noexcept { return m_upperAngle; }
    /// Sets the limits, rad (lower <= upper; wakes the bodies).
    void SetLimits(Fixed lower, Fixed upper);

    /// Whether the motor is enabled.
    bool IsMotorEnabled() const noexcept { return m_enableMotor; }
    /// Enables or disables the motor (wakes the bodies).
    void EnableMotor(bool flag);
    /// Target relative speed, rad/s (wakes the bodies).
    void SetMotorSpeed(Fixed speed);
    /// Target motor speed.
    Fixed GetMotorSpeed() const noexcept { return m_motorSpeed; }
    /// Maximum motor torque, N*m (wakes the bodies).
    void SetMaxMotorTorque(Fixed torque);
    /// Maximum motor torque, N*m.
    Fixed GetMaxMotorTorque() const noexcept { return m_maxMotorTorque; }
    /// Motor torque applied in the last step, N*m.
    Fixed GetMotorTorque(Fixed inv_dt) const;

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2RevoluteJoint(const b2RevoluteJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// What the velocity set-up gives the point-to-point iterations (the joint solver's rows).
    struct PointSetUp {
        int32 indexA = 0;  ///< island body indices
        int32 indexB = 0;
        b2Vec2 localCenterA;  ///< the bodies' local centres of mass (m)
        b2Vec2 localCenterB;
        Wide mA, mB, iA, iB;  ///< inverse masses and rotational inertias
        b2Vec2 rA;            ///< arms from the centres of mass to the anchor (m)
        b2Vec2 rB;
        b2WideMat22 pointMass;  ///< the point block's inverse (kg)
    };
    /// InitVelocityConstraints, returning what the point iterations read. With `keepSolverFields`
    /// false (motor and limit disabled: the joint solver iterates the joint as a row), the
    /// joint's own solver fields are not written; the state and the velocities are, the same.
    PointSetUp SetUpVelocity(const b2SolverData& data, bool keepSolverFields);
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2RevoluteJoint(b2RestoreTag tag) : b2Joint(tag, e_revoluteJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_localAnchorA, m_localAnchorB, m_referenceAngle, m_enableLimit, m_lowerAngle, m_upperAngle, m_enableMotor,
          m_motorSpeed, m_maxMotorTorque, m_impulse, m_motorImpulse, m_angleBase, m_limitState);
    }

    /// The continuous angle for body angles aA, aB: the branch nearest to m_angleBase.
    Fixed ContinuousAngle(Fixed aA, Fixed aB) const noexcept;
    /// Carries the continuous angle to body angles aA, aB (the velocity set-up's step) and
    /// returns it.
    Fixed TrackAngle(Fixed aA, Fixed aB) noexcept;

    // Declared in the order of use, so that a step touches as few cache lines of a joint as it
    // can (a large joint graph's set-up and iterations are memory-bound). First what the
    // velocity set-up reads and writes of every joint: the switches and the state it carries
    // (anchors, angles, impulses). A joint whose motor and limit are disabled is iterated in the
    // joint solver's compact rows and is touched nowhere else in the step.
    b2LimitState m_limitState = e_inactiveLimit;
    bool m_enableMotor;
    bool m_enableLimit;
    b2Vec2 m_localAnchorA;
    b2Vec2 m_localAnchorB;
    Fixed m_referenceAngle;
    Fixed m_angleBase;     ///< continuous joint angle at the last velocity init, rad
    b2WideVec3 m_impulse;  ///< point (N*s) and limit (N*m*s)
    Wide m_motorImpulse;   ///< N*m*s
    Wide m_motorMass;      ///< 1/(iA + iB), kg*m^2
    Fixed m_motorSpeed;
    Fixed m_maxMotorTorque;
    Fixed m_lowerAngle;
    Fixed m_upperAngle;

    // The solver fields of a joint that is iterated by itself (motor or limit enabled), in the
    // order its velocity iterations read them; then what only its set-up and position pass read.
    int32 m_indexA = 0;
    int32 m_indexB = 0;
    b2Vec2 m_rA;
    b2Vec2 m_rB;
    Wide m_invMassA, m_invMassB, m_invIA, m_invIB;
    b2WideMat22 m_pointMass;  ///< the point block's inverse (kg), once per step: the point iterations' product
    b2Vec2 m_localCenterA;
    b2Vec2 m_localCenterB;
    b2WideMat33 m_mass;            ///< the K matrix (1/kg, 1/(kg m), 1/(kg m^2)); its point block is also inverted
    b2WideSolver22 m_pointSolver;  ///< m_mass's point block, prepared once per step
    b2WideSolver33 m_limitSolver;  ///< m_mass, prepared once per step while the limit is solved
};

}  // namespace lockbox
