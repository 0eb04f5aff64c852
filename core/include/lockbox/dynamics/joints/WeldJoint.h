#pragma once
/// @file
/// b2WeldJoint (Box2D 2.2.1): glues two bodies together (point and angle), optionally with a
/// soft angular spring (frequencyHz > 0).

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Weld joint definition: the local anchors, the reference angle and the optional softness.
/// Initialize fills them from the bodies' current poses and one world anchor.
struct LOCKBOX_API b2WeldJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2WeldJointDef() { type = e_weldJoint; }

    /// Bodies, anchors from one world point (m), reference angle from the current angles.
    void Initialize(b2Body* bodyA, b2Body* bodyB, const b2Vec2& anchor);

    b2Vec2 localAnchorA;   ///< m, relative to A's origin
    b2Vec2 localAnchorB;   ///< m, relative to B's origin
    Fixed referenceAngle;  ///< angleB - angleA in the reference state, rad
    Fixed frequencyHz;     ///< angular spring frequency, Hz, in [0, 30]; 0 = rigid
    Fixed dampingRatio;    ///< angular spring damping ratio
};

/// A weld joint: holds B fixed relative to A (anchor point and angle). The iterative solver makes
/// chains of welded bodies flex a little; a single body with several fixtures is stiffer.
class LOCKBOX_API b2WeldJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Point reaction on B, N.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Angular reaction on B, N*m.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Anchor on body A in A's frame, m.
    const b2Vec2& GetLocalAnchorA() const noexcept { return m_localAnchorA; }
    /// Anchor on body B in B's frame, m.
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// Reference angle angleB - angleA, rad.
    Fixed GetReferenceAngle() const noexcept { return m_referenceAngle; }
    /// Angular spring frequency, Hz.
    void SetFrequency(Fixed hz) noexcept { m_frequencyHz = hz; }
    /// Spring frequency, Hz.
    Fixed GetFrequency() const noexcept { return m_frequencyHz; }
    /// Angular spring damping ratio.
    void SetDampingRatio(Fixed ratio) noexcept { m_dampingRatio = ratio; }
    /// Damping ratio (dimensionless).
    Fixed GetDampingRatio() const noexcept { return m_dampingRatio; }

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2WeldJoint(const b2WeldJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2WeldJoint(b2RestoreTag tag) : b2Joint(tag, e_weldJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_localAnchorA, m_localAnchorB, m_referenceAngle, m_frequencyHz, m_dampingRatio, m_impulse);
    }

    Fixed m_frequencyHz;
    Fixed m_dampingRatio;
    Wide m_bias;  ///< rad/s
    b2Vec2 m_localAnchorA;
    b2Vec2 m_localAnchorB;
    Fixed m_referenceAngle;
    Wide m_gamma;  ///< 1/(kg m^2)
    b2WideVec3 m_impulse;

    int32 m_indexA = 0;
    int32 m_indexB = 0;
    b2Vec2 m_rA;
    b2Vec2 m_rB;
    b2Vec2 m_localCenterA;
    b2Vec2 m_localCenterB;
    Wide m_invMassA, m_invMassB, m_invIA, m_invIB;
    b2WideMat33 m_K;               ///< solved, never inverted
    b2WideSolver22 m_pointSolver;  ///< m_K's upper block, prepared once per step (soft weld)
    b2WideMat22 m_pointMass;       ///< its inverse, once per step: the point iterations' product
    b2WideSolver33 m_rigidSolver;  ///< m_K, prepared once per step (rigid weld)
    Wide m_angularMass;            ///< soft angular effective mass, kg*m^2
};

}  // namespace lockbox
