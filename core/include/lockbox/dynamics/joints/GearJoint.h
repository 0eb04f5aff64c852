#pragma once
/// @file
/// b2GearJoint (Box2D 2.2.1): couples two revolute and/or prismatic joints so that
/// coordinate1 + ratio * coordinate2 stays constant. Each of those joints must attach a
/// dynamic body (its bodyB) to another body (its bodyA, usually static).
///
/// Lifetime (lockbox's rule): a gear joint depends on joint1 and joint2. Destroying either of
/// them, explicitly or through its body, destroys the gear joint first; the destruction
/// listener hears SayGoodbye(gear) for it. No dangling reference can remain.
///
/// Revolute coordinates are continuous across turns (body angles wrap every step): the gear
/// follows the branch of each angle nearest to its previous value, as b2RevoluteJoint does.

#include "lockbox/Export.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

/// Gear joint definition. bodyA and bodyB are taken from the joints (joint1's and joint2's
/// bodyB) and need not be set.
struct b2GearJointDef : b2JointDef {
    /// Defaults as in Box2D 2.2.1.
    b2GearJointDef() { type = e_gearJoint; }

    b2Joint* joint1 = nullptr;  ///< a revolute or prismatic joint
    b2Joint* joint2 = nullptr;  ///< a revolute or prismatic joint
    Fixed ratio = 1;            ///< gear ratio (dimensionless, or m/rad when mixing types)
};

/// A gear joint: couples two revolute or prismatic joints so that coordinate1 + ratio *
/// coordinate2 stays constant (see the file comment for its lifetime rule).
class LOCKBOX_API b2GearJoint : public b2Joint {
public:
    /// Anchor on body A (world), m.
    b2Vec2 GetAnchorA() const override;
    /// Anchor on body B (world), m.
    b2Vec2 GetAnchorB() const override;
    /// Reaction on B (the body of joint1), N.
    b2Vec2 GetReactionForce(Fixed inv_dt) const override;
    /// Reaction torque, N*m.
    Fixed GetReactionTorque(Fixed inv_dt) const override;

    /// The first coupled joint.
    b2Joint* GetJoint1() noexcept { return m_joint1; }
    /// The first coupled joint (read-only view).
    const b2Joint* GetJoint1() const noexcept { return m_joint1; }
    /// The second coupled joint.
    b2Joint* GetJoint2() noexcept { return m_joint2; }
    /// The second coupled joint (read-only view).
    const b2Joint* GetJoint2() const noexcept { return m_joint2; }
    /// Sets the gear ratio (any sign; in m or 1/m when one joint is prismatic and the other
    /// revolute).
    void SetRatio(Fixed ratio) noexcept { m_ratio = ratio; }
    /// The gear ratio.
    Fixed GetRatio() const noexcept { return m_ratio; }
    /// The two joint coordinates (rad or m) as the gear sees them now.
    ///@{
    Fixed GetCoordinateA() const;
    Fixed GetCoordinateB() const;
    ///@}

private:
    friend struct core_detail::Engine;

    /// Made by b2World::CreateJoint.
    explicit b2GearJoint(const b2GearJointDef* def);

    /// Solver hook (called by b2Island).
    void InitVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island).
    void SolveVelocityConstraints(const b2SolverData& data) override;
    /// Solver hook (called by b2Island); true when within tolerance.
    bool SolvePositionConstraints(const b2SolverData& data) override;

    /// Snapshot restore: an empty joint whose state VisitState fills (core/src/state).
    explicit b2GearJoint(b2RestoreTag tag) : b2Joint(tag, e_gearJoint) {}
    /// Visits every field that persists between steps (parameters, warm-start impulses,
    /// carried angles), in the order of the state hash and the snapshot (docs/determinism.md).
    template <class V>
    void VisitState(V& v) {
        v.JointRef(m_joint1);
        v.JointRef(m_joint2);
        VisitSide(v, m_sideA);
        VisitSide(v, m_sideB);
        v(m_ratio, m_constant, m_impulse);
    }
    /// Visits the directions the last solve computed that GetReactionForce/GetReactionTorque
    /// read (solver temporaries, not state a step depends on): the snapshot carries them so a
    /// restored joint answers those queries as the saved one did.
    template <class V>
    void VisitReactionState(V& v) {
        v(m_JvAC, m_JwA);
    }

    /// One side of the gear: joint (A side: bodies C -> A; B side: bodies D -> B).
    struct Side {
        b2JointType type = e_unknownJoint;
        b2Body* body = nullptr;    ///< the geared body (A or B)
        b2Body* ground = nullptr;  ///< the joint's other body (C or D)
        b2Vec2 localAnchorGround;  ///< anchor on the ground body, m
        b2Vec2 localAnchorBody;    ///< anchor on the geared body, m
        Fixed referenceAngle;
        b2Vec2 localAxisGround;  ///< prismatic axis in the ground frame
        Fixed angleBase;         ///< last continuous revolute coordinate, rad
    };

    static Side MakeSide(b2Joint* joint);
    template <class V>
    static void VisitSide(V& v, Side& s) {
        v(s.type);
        v.BodyRef(s.body);
        v.BodyRef(s.ground);
        v(s.localAnchorGround, s.localAnchorBody, s.referenceAngle, s.localAxisGround, s.angleBase);
    }
    /// Coordinate from body positions (ground at cG, aG; body at c, a).
    static Fixed Coordinate(const Side& s, const b2Vec2& cG, Fixed aG, const b2Vec2& c, Fixed a, const b2Vec2& lcG,
                            const b2Vec2& lc);

    b2Joint* m_joint1;
    b2Joint* m_joint2;
    Side m_sideA;
    Side m_sideB;
    Fixed m_constant;  ///< coordinateA + ratio * coordinateB
    Fixed m_ratio;
    Wide m_impulse;

    int32 m_indexA = 0, m_indexB = 0, m_indexC = 0, m_indexD = 0;
    b2Vec2 m_lcA, m_lcB, m_lcC, m_lcD;
    Wide m_mA, m_mB, m_mC, m_mD;
    Wide m_iA, m_iB, m_iC, m_iD;
    b2Vec2 m_JvAC, m_JvBD;
    Fixed m_JwA, m_JwB, m_JwC, m_JwD;
    Wide m_mass;
};

}  // namespace lockbox
