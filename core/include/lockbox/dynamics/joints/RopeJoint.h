#pragma once
/// @file
/// b2RopeJoint (Box2D 2.2.1): a maximum distance between two anchors (a slack rope). It keeps
/// chains and ragdolls from stretching under large mass ratios.

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Rope joint definition: the local anchors and the maximum length (no Initialize: set the
/// anchors in each body's frame).
struct b2RopeJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2RopeJointDef() {
        type = e_ropeJoint;
        localAnchorA.Set(-1, 0);
        localAnchorB.Set(1, 0);
    }

    b2Vec2 localAnchorA;  ///< m, relative to A's origin
    b2Vec2 localAnchorB;  ///< m, relative to B's origin
    Fixed maxLength;      ///< m, > linearSlop
};

/// A rope joint: the distance between an anchor on A and one on B never exceeds maxLength, and
/// may be anything shorter (a slack rope).
class LOCKBOX_API b2RopeJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Rope tension on B, N.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Always 0.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Anchor on body A in A's frame, m.
    const b2Vec2& GetLocalAnchorA() const noexcept { return m_localAnchorA; }
    /// Anchor on body B in B's frame, m.
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// Maximum length, m.
    void SetMaxLength(Fixed length) noexcept { m_maxLength = length; }
    /// Maximum length, m.
    Fixed GetMaxLength() const noexcept { return m_maxLength; }
    /// e_atUpperLimit while the rope is taut, else e_inactiveLimit.
    b2LimitState GetLimitState() const noexcept { return m_state; }

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2RopeJoint(const b2RopeJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2RopeJoint(b2RestoreTag tag) : b2Joint(tag, e_ropeJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_localAnchorA, m_localAnchorB, m_maxLength, m_length, m_impulse, m_state);
    }
    /// Visits the directions the last solve computed that GetReactionForce/GetReactionTorque
    /// read (solver temporaries, not state a step depends on): the snapshot carries them so a
    /// restored joint answers those queries as the saved one did.
    template <class V>
    void VisitReactionState(V& v) {
        v(m_u);
    }

    b2Vec2 m_localAnchorA;
    b2Vec2 m_localAnchorB;
    Fixed m_maxLength;
    Fixed m_length;
    Wide m_impulse;  ///< N*s (<= 0: the rope only pulls)

    int32 m_indexA = 0;
    int32 m_indexB = 0;
    b2Vec2 m_u, m_rA, m_rB;
    b2Vec2 m_localCenterA;
    b2Vec2 m_localCenterB;
    Wide m_invMassA, m_invMassB, m_invIA, m_invIB;
    Wide m_mass;  ///< kg
    b2LimitState m_state = e_inactiveLimit;
};

}  // namespace lockbox
