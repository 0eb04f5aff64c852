#pragma once
/// @file
/// The abstract joint (Box2D 2.2.1 b2Joint.h): types, definition base, graph edges and the
/// solver interface the island calls. The concrete joints live next to this header (one per
/// file); b2World::CreateJoint goes through b2Joint::Create, which dispatches on the type.

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

class b2Body;
class b2Joint;
class b2Draw;
struct b2SolverData;

/// Joint kinds, numbered as in 2.2.1.
enum b2JointType {
    e_unknownJoint,
    e_revoluteJoint,
    e_prismaticJoint,
    e_distanceJoint,
    e_pulleyJoint,
    e_mouseJoint,
    e_gearJoint,
    e_wheelJoint,
    e_weldJoint,
    e_frictionJoint,
    e_ropeJoint
};

/// Limit state of a joint with limits.
enum b2LimitState { e_inactiveLimit, e_atLowerLimit, e_atUpperLimit, e_equalLimits };

/// A joint edge connects bodies and joints in the constraint graph: each joint has two
/// edges, one per attached body, linked into that body's joint list (newest first).
struct b2JointEdge {
    b2Body* other = nullptr;      ///< the body at the other end
    b2Joint* joint = nullptr;     ///< the joint
    b2JointEdge* prev = nullptr;  ///< previous edge in the body's joint list
    b2JointEdge* next = nullptr;  ///< next edge in the body's joint list
};

/// Joint definitions derive from this.
struct b2JointDef {
    b2JointType type = e_unknownJoint;  ///< set by the concrete definition
    uint64 userData = 0;                ///< application data (an id or handle, never a pointer)
    b2Body* bodyA = nullptr;            ///< first attached body
    b2Body* bodyB = nullptr;            ///< second attached body
    bool collideConnected = false;      ///< may the attached bodies collide with each other?
};

/// Base class of all joints. The world owns joints; the island calls the three solver hooks.
class LOCKBOX_API b2Joint {
public:
    /// The joint type.
    b2JointType GetType() const noexcept { return m_type; }
    /// First attached body.
    b2Body* GetBodyA() noexcept { return m_bodyA; }
    /// First attached body (read-only view).
    const b2Body* GetBodyA() const noexcept { return m_bodyA; }
    /// Second attached body.
    b2Body* GetBodyB() noexcept { return m_bodyB; }
    /// Second attached body (read-only view).
    const b2Body* GetBodyB() const noexcept { return m_bodyB; }
    /// Anchor on body A in world coordinates (m).
    virtual b2Vec2 GetAnchorA() const = 0;
    /// Anchor on body B in world coordinates (m).
    virtual b2Vec2 GetAnchorB() const = 0;
    /// Reaction force on body B at its anchor (N), given the inverse time step (1/s).
    virtual b2Vec2 GetReactionForce(Fixed inv_dt) const = 0;
    /// Reaction torque on body B (N*m), given the inverse time step (1/s).
    virtual Fixed GetReactionTorque(Fixed inv_dt) const = 0;
    /// Next joint in the world's list.
    b2Joint* GetNext() noexcept { return m_next; }
    /// Next joint in the world's list (read-only view).
    const b2Joint* GetNext() const noexcept { return m_next; }
    /// Application data.
    uint64 GetUserData() const noexcept { return m_userData; }
    /// Sets the application data: an id or handle, never a pointer (part of the snapshot and the
    /// hash).
    void SetUserData(uint64 data) noexcept { m_userData = data; }
    /// Small integer id of this joint (stable across snapshot and restore).
    int32 GetId() const noexcept { return m_id; }
    /// True when both bodies are active.
    bool IsActive() const;
    /// Whether the attached bodies collide.
    bool GetCollideConnected() const noexcept { return m_collideConnected; }

    b2Joint(const b2Joint&) = delete;
    b2Joint& operator=(const b2Joint&) = delete;

protected:
    /// Restore constructor: an empty joint of the given type whose state a snapshot restore then
    /// fills in.
    b2Joint(b2RestoreTag, b2JointType type) : m_type(type) {}
    /// Copies the common fields (type, bodies, collideConnected, user data) from a definition.
    explicit b2Joint(const b2JointDef* def)
        : m_type(def->type),
          m_bodyA(def->bodyA),
          m_bodyB(def->bodyB),
          m_collideConnected(def->collideConnected),
          m_userData(def->userData) {}
    /// Joints are destroyed by the world (b2World::DestroyJoint, DestroyBody).
    virtual ~b2Joint() = default;

private:
    friend struct core_detail::Engine;

    // The solver interface, called by the island.
    /// Prepares the velocity constraints (and applies warm starting).
    virtual void InitVelocityConstraints(const b2SolverData& data) = 0;
    /// One velocity iteration.
    virtual void SolveVelocityConstraints(const b2SolverData& data) = 0;
    /// One position iteration; returns true when the position error is within tolerance.
    virtual bool SolvePositionConstraints(const b2SolverData& data) = 0;

    b2JointType m_type = e_unknownJoint;
    b2Joint* m_prev = nullptr;
    b2Joint* m_next = nullptr;
    b2JointEdge m_edgeA;
    b2JointEdge m_edgeB;

protected:
    /// The attached bodies (the concrete joints' solvers read them).
    ///@{
    b2Body* m_bodyA = nullptr;
    b2Body* m_bodyB = nullptr;
    ///@}

private:
    int32 m_id = -1;
    int32 m_index = 0;  ///< position in the island being solved
    bool m_collideConnected = false;
    uint64 m_userData = 0;
};

}  // namespace lockbox
