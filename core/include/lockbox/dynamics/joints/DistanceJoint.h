#pragma once
/// @file
/// b2DistanceJoint (Box2D 2.2.1): keeps two anchor points at a fixed distance, rigidly or
/// through a soft spring (frequencyHz > 0).

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Distance joint definition. Do not make length too short (below a few linearSlop).
struct LOCKBOX_API b2DistanceJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2DistanceJointDef() { type = e_distanceJoint; }

    /// Sets bodies and local anchors from two world anchors (m); length = their distance.
    void Initialize(b2Body* bodyA, b2Body* bodyB, const b2Vec2& anchorA, const b2Vec2& anchorB);

    b2Vec2 localAnchorA;  ///< anchor on A relative to A's origin, m
    b2Vec2 localAnchorB;  ///< anchor on B relative to B's origin, m
    Fixed length = 1;     ///< natural length, m (> 0)
    Fixed frequencyHz;    ///< spring frequency, Hz, in [0, 30]; 0 makes the joint rigid
    Fixed dampingRatio;   ///< 0 = no damping, 1 = critical, in [0, 10]
};

/// A distance joint: the distance between an anchor on A and an anchor on B stays at length, as
/// a rigid rod, or as a spring-damper when the frequency is positive.
class LOCKBOX_API b2DistanceJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Reaction force on B (N): impulse * inv_dt along the joint axis.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Always 0.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Anchor on body A in A's frame, m.
    const b2Vec2& GetLocalAnchorA() const noexcept { return m_localAnchorA; }
    /// Anchor on body B in B's frame, m.
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// Natural length, m.
    void SetLength(Fixed length) noexcept { m_length = length; }
    /// Natural length, m.
    Fixed GetLength() const noexcept { return m_length; }
    /// Spring frequency, Hz (0 = rigid).
    void SetFrequency(Fixed hz) noexcept { m_frequencyHz = hz; }
    /// Spring frequency, Hz.
    Fixed GetFrequency() const noexcept { return m_frequencyHz; }
    /// Damping ratio (dimensionless).
    void SetDampingRatio(Fixed ratio) noexcept { m_dampingRatio = ratio; }
    /// Damping ratio (dimensionless).
    Fixed GetDampingRatio() const noexcept { return m_dampingRatio; }

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2DistanceJoint(const b2DistanceJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2DistanceJoint(b2RestoreTag tag) : b2Joint(tag, e_distanceJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_localAnchorA, m_localAnchorB, m_length, m_frequencyHz, m_dampingRatio, m_impulse);
    }
    /// Visits the directions the last solve computed that GetReactionForce/GetReactionTorque
    /// read (solver temporaries, not state a step depends on): the snapshot carries them so a
    /// restored joint answers those queries as the saved one did.
    template <class V>
    void VisitReactionState(V& v) {
        v(m_u);
    }

    Fixed m_frequencyHz;
    Fixed m_dampingRatio;
    Wide m_bias;  ///< m/s
    b2Vec2 m_localAnchorA;
    b2Vec2 m_localAnchorB;
    Wide m_gamma;    ///< 1/kg
    Wide m_impulse;  ///< N*s
    Fixed m_length;

    // Solver temporaries.
    int32 m_indexA = 0;
    int32 m_indexB = 0;
    b2Vec2 m_u;
    b2Vec2 m_rA;
    b2Vec2 m_rB;
    b2Vec2 m_localCenterA;
    b2Vec2 m_localCenterB;
    Wide m_invMassA, m_invMassB, m_invIA, m_invIB;
    Wide m_mass;  ///< effective mass along u, kg
};

}  // namespace lockbox
