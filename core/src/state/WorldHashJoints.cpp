// Joints in the state hash. The accumulated impulses that joints carry between steps are
// private to each joint type; they are reached through GetReactionForce/GetReactionTorque at
// two scales (see HashImpulses). Parameters come from the public getters.

#include "HashWriter.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/joints/Joints.h"

namespace lockbox::state_detail {
namespace {

/// The joint's warm-start impulses. GetReactionForce(inv_dt) rounds inv_dt * impulse to
/// Q16.16 and traps (checked build) or saturates beyond it, so the scale must keep every
/// realistic impulse in range: inv_dt = 1/256 covers |impulse| < 8.3e6 N*s and keeps the top
/// 8 fraction bits (1/256 N*s). Smaller differences show in the bodies' velocities a step later.
void HashImpulses(HashWriter& w, const b2Joint& j) {
    const Fixed scale = Fixed::FromRaw(256);  // 1/256, dimensionless (1/s times s)
    w.V(j.GetReactionForce(scale));
    w.F(j.GetReactionTorque(scale));
}

void HashTypeParameters(HashWriter& w, const b2Joint& j) {
    switch (j.GetType()) {
        case e_revoluteJoint: {
            const auto& r = static_cast<const b2RevoluteJoint&>(j);
            w.V(r.GetLocalAnchorA()); w.V(r.GetLocalAnchorB());
            w.F(r.GetReferenceAngle());
            w.Bool(r.IsLimitEnabled()); w.F(r.GetLowerLimit()); w.F(r.GetUpperLimit());
            w.Bool(r.IsMotorEnabled()); w.F(r.GetMotorSpeed()); w.F(r.GetMaxMotorTorque());
            break;
        }
        case e_prismaticJoint: {
            const auto& p = static_cast<const b2PrismaticJoint&>(j);
            w.V(p.GetLocalAnchorA()); w.V(p.GetLocalAnchorB()); w.V(p.GetLocalAxisA());
            w.F(p.GetReferenceAngle());
            w.Bool(p.IsLimitEnabled()); w.F(p.GetLowerLimit()); w.F(p.GetUpperLimit());
            w.Bool(p.IsMotorEnabled()); w.F(p.GetMotorSpeed()); w.F(p.GetMaxMotorForce());
            break;
        }
        case e_distanceJoint: {
            const auto& d = static_cast<const b2DistanceJoint&>(j);
            w.V(d.GetLocalAnchorA()); w.V(d.GetLocalAnchorB());
            w.F(d.GetLength()); w.F(d.GetFrequency()); w.F(d.GetDampingRatio());
            break;
        }
        case e_pulleyJoint: {
            const auto& p = static_cast<const b2PulleyJoint&>(j);
            w.V(p.GetGroundAnchorA()); w.V(p.GetGroundAnchorB());
            w.F(p.GetRatio());
            break;
        }
        case e_mouseJoint: {
            const auto& m = static_cast<const b2MouseJoint&>(j);
            w.V(m.GetTarget());
            w.W(m.GetMaxForce()); w.F(m.GetFrequency()); w.F(m.GetDampingRatio());
            // The mouse joint exposes its exact Q32.32 impulse.
            w.W(m.GetImpulse().x); w.W(m.GetImpulse().y);
            break;
        }
        case e_gearJoint: {
            const auto& g = static_cast<const b2GearJoint&>(j);
            w.F(g.GetRatio());
            break;
        }
        case e_wheelJoint: {
            const auto& wh = static_cast<const b2WheelJoint&>(j);
            w.V(wh.GetLocalAnchorA()); w.V(wh.GetLocalAnchorB()); w.V(wh.GetLocalAxisA());
            w.Bool(wh.IsMotorEnabled()); w.F(wh.GetMotorSpeed()); w.F(wh.GetMaxMotorTorque());
            w.F(wh.GetSpringFrequencyHz()); w.F(wh.GetSpringDampingRatio());
            break;
        }
        case e_weldJoint: {
            const auto& wd = static_cast<const b2WeldJoint&>(j);
            w.V(wd.GetLocalAnchorA()); w.V(wd.GetLocalAnchorB());
            w.F(wd.GetReferenceAngle()); w.F(wd.GetFrequency()); w.F(wd.GetDampingRatio());
            break;
        }
        case e_frictionJoint: {
            const auto& f = static_cast<const b2FrictionJoint&>(j);
            w.V(f.GetLocalAnchorA()); w.V(f.GetLocalAnchorB());
            w.F(f.GetMaxForce()); w.F(f.GetMaxTorque());
            break;
        }
        case e_ropeJoint: {
            const auto& r = static_cast<const b2RopeJoint&>(j);
            w.V(r.GetLocalAnchorA()); w.V(r.GetLocalAnchorB());
            w.F(r.GetMaxLength());
            w.U32(static_cast<uint32>(r.GetLimitState()));
            break;
        }
        default:
            break;
    }
}

}  // namespace

void HashJoint(HashWriter& w, const b2Joint& j) {
    w.I32(j.GetId());
    w.U32(static_cast<uint32>(j.GetType()));
    w.I32(j.m_bodyA->GetId());
    w.I32(j.m_bodyB->GetId());
    w.Bool(j.GetCollideConnected());
    w.U64(j.GetUserData());
    HashTypeParameters(w, j);
    HashImpulses(w, j);
}

}  // namespace lockbox::state_detail
