// b2Joint: the parts of the abstract base that need b2Body, and the factory (JointAccess.h).
#include "lockbox/dynamics/joints/Joint.h"

#include "dynamics/joints/JointAccess.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/joints/DistanceJoint.h"
#include "lockbox/dynamics/joints/FrictionJoint.h"
#include "lockbox/dynamics/joints/GearJoint.h"
#include "lockbox/dynamics/joints/MouseJoint.h"
#include "lockbox/dynamics/joints/PrismaticJoint.h"
#include "lockbox/dynamics/joints/PulleyJoint.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"
#include "lockbox/dynamics/joints/RopeJoint.h"
#include "lockbox/dynamics/joints/WeldJoint.h"
#include "lockbox/dynamics/joints/WheelJoint.h"

namespace lockbox {

bool b2Joint::IsActive() const { return m_bodyA->IsActive() && m_bodyB->IsActive(); }

b2Joint* core_detail::Engine::Joints::Create(const b2JointDef* def) {
    if (def == nullptr) return nullptr;
    if (def->type == e_gearJoint) {
        // The gear takes its bodies from the two joints, which must be revolute or prismatic.
        const auto* gear = static_cast<const b2GearJointDef*>(def);
        auto geared = [](const b2Joint* j) {
            return j != nullptr && (j->GetType() == e_revoluteJoint || j->GetType() == e_prismaticJoint);
        };
        if (!geared(gear->joint1) || !geared(gear->joint2)) return nullptr;
    } else if (def->bodyA == nullptr || def->bodyB == nullptr || def->bodyA == def->bodyB) {
        return nullptr;
    }
    switch (def->type) {
        case e_distanceJoint: return new b2DistanceJoint(static_cast<const b2DistanceJointDef*>(def));
        case e_mouseJoint: return new b2MouseJoint(static_cast<const b2MouseJointDef*>(def));
        case e_prismaticJoint: return new b2PrismaticJoint(static_cast<const b2PrismaticJointDef*>(def));
        case e_revoluteJoint: return new b2RevoluteJoint(static_cast<const b2RevoluteJointDef*>(def));
        case e_pulleyJoint: return new b2PulleyJoint(static_cast<const b2PulleyJointDef*>(def));
        case e_gearJoint: return new b2GearJoint(static_cast<const b2GearJointDef*>(def));
        case e_wheelJoint: return new b2WheelJoint(static_cast<const b2WheelJointDef*>(def));
        case e_weldJoint: return new b2WeldJoint(static_cast<const b2WeldJointDef*>(def));
        case e_frictionJoint: return new b2FrictionJoint(static_cast<const b2FrictionJointDef*>(def));
        case e_ropeJoint: return new b2RopeJoint(static_cast<const b2RopeJointDef*>(def));
        case e_unknownJoint: break;
    }
    return nullptr;
}

b2Joint* core_detail::Engine::Joints::CreateEmpty(b2JointType type) {
    const b2RestoreTag tag;
    switch (type) {
        case e_distanceJoint: return new b2DistanceJoint(tag);
        case e_mouseJoint: return new b2MouseJoint(tag);
        case e_prismaticJoint: return new b2PrismaticJoint(tag);
        case e_revoluteJoint: return new b2RevoluteJoint(tag);
        case e_pulleyJoint: return new b2PulleyJoint(tag);
        case e_gearJoint: return new b2GearJoint(tag);
        case e_wheelJoint: return new b2WheelJoint(tag);
        case e_weldJoint: return new b2WeldJoint(tag);
        case e_frictionJoint: return new b2FrictionJoint(tag);
        case e_ropeJoint: return new b2RopeJoint(tag);
        case e_unknownJoint: break;
    }
    return nullptr;
}

void core_detail::Engine::Joints::Destroy(b2Joint* joint) { delete joint; }

}  // namespace lockbox
