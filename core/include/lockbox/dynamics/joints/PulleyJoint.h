#pragma once
/// @file
/// b2PulleyJoint (Box2D 2.2.1): an ideal pulley. Each body hangs from a fixed ground anchor and
/// lengthA + ratio * lengthB stays constant. When one side reaches zero length its direction
/// is undefined: that side then contributes nothing (finite, no division), as in 2.2.1.

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Pulley joint definition. collideConnected is true by default, as in 2.2.1.
struct LOCKBOX_API b2PulleyJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2PulleyJointDef() {
        type = e_pulleyJoint;
        groundAnchorA.Set(-1, 1);
        groundAnchorB.Set(1, 1);
        localAnchorA.Set(-1, 0);
        localAnchorB.Set(1, 0);
        collideConnected = true;
    }

    /// Bodies, ground anchors (m), body anchors (world, m) and the ratio (> 0).
    void Initialize(b2Body* bodyA, b2Body* bodyB, const b2Vec2& groundAnchorA, const b2Vec2& groundAnchorB,
                    const b2Vec2& anchorA, const b2Vec2& anchorB, Fixed ratio);

    b2Vec2 groundAnchorA;  ///< world, m
    b2Vec2 groundAnchorB;  ///< world, m
    b2Vec2 localAnchorA;   ///< m, relative to A's origin
    b2Vec2 localAnchorB;   ///< m, relative to B's origin
    Fixed lengthA;         ///< reference length of side A, m
    Fixed lengthB;         ///< reference length of side B, m
    Fixed ratio = 1;       ///< pulley ratio (block and tackle), > 0
};

/// A pulley joint: each body hangs by a rope from its fixed ground anchor, and lengthA + ratio *
/// lengthB stays constant, so one body rises as the other falls (see the file comment).
class LOCKBOX_API b2PulleyJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Rope tension on B along side B, N.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Always 0.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// Ground anchor of side A (world), m.
    b2Vec2 GetGroundAnchorA() const noexcept { return m_groundAnchorA; }
    /// Ground anchor of side B (world), m.
    b2Vec2 GetGroundAnchorB() const noexcept { return m_groundAnchorB; }
    /// Anchor on body A in A's frame, m.
    const b2Vec2& GetLocalAnchorA() const noexcept { return m_localAnchorA; }
    /// Anchor on body B in B's frame, m.
    const b2Vec2& GetLocalAnchorB() const noexcept { return m_localAnchorB; }
    /// The rope length the joint keeps: lengthA + ratio * lengthB of the definition, m.
    Fixed GetTotalLength() const noexcept { return m_constant; }
    /// Current length of side A, m.
    Fixed GetLengthA() const;
    /// Current length of side B, m.
    Fixed GetLengthB() const;
    /// The pulley ratio (> 0): side A changes ratio times as fast as side B, and its rope carries
    /// 1/ratio of B's tension (a block and tackle).
    Fixed GetRatio() const noexcept { return m_ratio; }

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2PulleyJoint(const b2PulleyJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2PulleyJoint(b2RestoreTag tag) : b2Joint(tag, e_pulleyJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v(m_groundAnchorA, m_groundAnchorB, m_localAnchorA, m_localAnchorB, m_constant, m_ratio, m_impulse);
    }
    /// Visits the directions the last solve computed that GetReactionForce/GetReactionTorque
    /// read (solver temporaries, not state a step depends on): the snapshot carries them so a
    /// restored joint answers those queries as the saved one did.
    template <class V>
    void VisitReactionState(V& v) {
        v(m_uB);
    }

    b2Vec2 m_groundAnchorA;
    b2Vec2 m_groundAnchorB;
    b2Vec2 m_localAnchorA;
    b2Vec2 m_localAnchorB;
    Fixed m_constant;  ///< lengthA + ratio * lengthB, m
    Fixed m_ratio;
    Wide m_impulse;  ///< N*s

    int32 m_indexA = 0;
    int32 m_indexB = 0;
    b2Vec2 m_uA, m_uB, m_rA, m_rB;
    b2Vec2 m_localCenterA;
    b2Vec2 m_localCenterB;
    Wide m_invMassA, m_invMassB, m_invIA, m_invIB;
    Wide m_mass;  ///< kg
};

}  // namespace lockbox
