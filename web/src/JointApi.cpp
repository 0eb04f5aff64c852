// The C API of joints: the ten joint types from their definitions (with the manual's
// Initialize helpers), destroy, read and drive them.
#include <string>

#include "Bindings.h"
#include "DefReader.h"
#include "lockbox/dynamics/joints/Joints.h"

using namespace lockbox;
using namespace lockbox::web;

namespace {

// Each Read* reads the type's fields in table order (the JavaScript side writes the same
// order) and fills the definition; the "init" fields, when given, call the definition's
// Initialize first, and explicit fields given as well then override what it computed.

void ReadRevolute(DefReader& r, b2RevoluteJointDef& d) {
    b2Vec2 anchor;
    if (r.Vec(anchor)) d.Initialize(d.bodyA, d.bodyB, anchor);
    r.Vec(d.localAnchorA);
    r.Vec(d.localAnchorB);
    r.Fixed(d.referenceAngle);
    r.Bool(d.enableLimit);
    r.Fixed(d.lowerAngle);
    r.Fixed(d.upperAngle);
    r.Bool(d.enableMotor);
    r.Fixed(d.motorSpeed);
    r.Fixed(d.maxMotorTorque);
}

void ReadPrismatic(DefReader& r, b2PrismaticJointDef& d) {
    b2Vec2 anchor, axis(1, 0);
    const bool hasAnchor = r.Vec(anchor), hasAxis = r.Vec(axis);
    if (hasAnchor || hasAxis) d.Initialize(d.bodyA, d.bodyB, anchor, axis);
    r.Vec(d.localAnchorA);
    r.Vec(d.localAnchorB);
    r.Vec(d.localAxisA);
    r.Fixed(d.referenceAngle);
    r.Bool(d.enableLimit);
    r.Fixed(d.lowerTranslation);
    r.Fixed(d.upperTranslation);
    r.Bool(d.enableMotor);
    r.Fixed(d.maxMotorForce);
    r.Fixed(d.motorSpeed);
}

void ReadDistance(DefReader& r, b2DistanceJointDef& d) {
    b2Vec2 anchorA, anchorB;
    const bool hasA = r.Vec(anchorA), hasB = r.Vec(anchorB);
    if (hasA || hasB) d.Initialize(d.bodyA, d.bodyB, anchorA, anchorB);
    r.Vec(d.localAnchorA);
    r.Vec(d.localAnchorB);
    r.Fixed(d.length);
    r.Fixed(d.frequencyHz);
    r.Fixed(d.dampingRatio);
}

void ReadPulley(DefReader& r, b2PulleyJointDef& d) {
    r.Vec(d.groundAnchorA);
    r.Vec(d.groundAnchorB);
    b2Vec2 anchorA, anchorB;
    const bool hasA = r.Vec(anchorA), hasB = r.Vec(anchorB);
    r.Fixed(d.ratio);
    if (hasA || hasB) {
        d.Initialize(d.bodyA, d.bodyB, d.groundAnchorA, d.groundAnchorB, anchorA, anchorB, d.ratio);
    }
    r.Vec(d.localAnchorA);
    r.Vec(d.localAnchorB);
    r.Fixed(d.lengthA);
    r.Fixed(d.lengthB);
}

void ReadMouse(DefReader& r, b2MouseJointDef& d) {
    r.Vec(d.target);
    r.Wide(d.maxForce);
    r.Fixed(d.frequencyHz);
    r.Fixed(d.dampingRatio);
}

void ReadWheel(DefReader& r, b2WheelJointDef& d) {
    b2Vec2 anchor, axis(1, 0);
    const bool hasAnchor = r.Vec(anchor), hasAxis = r.Vec(axis);
    if (hasAnchor || hasAxis) d.Initialize(d.bodyA, d.bodyB, anchor, axis);
    r.Vec(d.localAnchorA);
    r.Vec(d.localAnchorB);
    r.Vec(d.localAxisA);
    r.Bool(d.enableMotor);
    r.Fixed(d.maxMotorTorque);
    r.Fixed(d.motorSpeed);
    r.Fixed(d.frequencyHz);
    r.Fixed(d.dampingRatio);
}

void ReadWeld(DefReader& r, b2WeldJointDef& d) {
    b2Vec2 anchor;
    if (r.Vec(anchor)) d.Initialize(d.bodyA, d.bodyB, anchor);
    r.Vec(d.localAnchorA);
    r.Vec(d.localAnchorB);
    r.Fixed(d.referenceAngle);
    r.Fixed(d.frequencyHz);
    r.Fixed(d.dampingRatio);
}

void ReadFriction(DefReader& r, b2FrictionJointDef& d) {
    b2Vec2 anchor;
    if (r.Vec(anchor)) d.Initialize(d.bodyA, d.bodyB, anchor);
    r.Vec(d.localAnchorA);
    r.Vec(d.localAnchorB);
    r.Fixed(d.maxForce);
    r.Fixed(d.maxTorque);
}

void ReadRope(DefReader& r, b2RopeJointDef& d) {
    r.Vec(d.localAnchorA);
    r.Vec(d.localAnchorB);
    r.Fixed(d.maxLength);
}

/// The common header (bodyA, bodyB, collideConnected, userData), then the type's fields;
/// creates the joint. Returns its id or -1.
template <class Def, class Reader>
int32_t Create(WebWorld& w, DefReader& r, Reader read, bool needsBodies) {
    Def d;
    int32_t a = -1, b = -1;
    const bool hasA = r.Int(a), hasB = r.Int(b);
    r.Bool(d.collideConnected);
    r.U64(d.userData);
    if (needsBodies && (!hasA || !hasB)) return Fail("createJoint: bodyA and bodyB are required");
    if (hasA && !(d.bodyA = FindBody(w, a, "createJoint bodyA"))) return -1;
    if (hasB && !(d.bodyB = FindBody(w, b, "createJoint bodyB"))) return -1;
    if (needsBodies && d.bodyA == d.bodyB) return Fail("createJoint: bodyA and bodyB are the same body");
    if constexpr (std::is_same_v<Def, b2GearJointDef>) {
        int32_t j1 = -1, j2 = -1;
        const bool has1 = r.Int(j1), has2 = r.Int(j2);
        r.Fixed(d.ratio);
        if (!has1 || !has2) return Fail("createJoint: a gear needs joint1 and joint2");
        if (!(d.joint1 = FindJoint(w, j1, "createJoint joint1")) ||
            !(d.joint2 = FindJoint(w, j2, "createJoint joint2")))
            return -1;
        (void)read;
    } else {
        read(r, d);
    }
    if (!r.ok()) return Fail("createJoint: malformed definition");
    b2Joint* j = w.world->CreateJoint(&d);
    return j ? j->GetId() : Fail("createJoint: refused (a gear joins two revolute or prismatic joints)");
}

}  // namespace

/// Creates a joint: words[0] is the b2JointType (1 revolute, 2 prismatic, 3 distance, 4 pulley,
/// 5 mouse, 6 gear, 7 wheel, 8 weld, 9 friction, 10 rope), then the definition's words
/// (DefReader). Returns the joint id, or -1.
LOCKBOX_WEB_API int32_t lb_joint_create(WebWorld* w, const int32_t* words, int32_t count) {
    if (w->world->IsLocked()) return Fail("createJoint: the world is locked (called from inside a step)");
    if (count < 1) return Fail("createJoint: malformed definition");
    DefReader r(words + 1, count - 1);
    switch (words[0]) {
        case e_revoluteJoint: return Create<b2RevoluteJointDef>(*w, r, ReadRevolute, true);
        case e_prismaticJoint: return Create<b2PrismaticJointDef>(*w, r, ReadPrismatic, true);
        case e_distanceJoint: return Create<b2DistanceJointDef>(*w, r, ReadDistance, true);
        case e_pulleyJoint: return Create<b2PulleyJointDef>(*w, r, ReadPulley, true);
        case e_mouseJoint: return Create<b2MouseJointDef>(*w, r, ReadMouse, true);
        case e_gearJoint: return Create<b2GearJointDef>(*w, r, nullptr, false);
        case e_wheelJoint: return Create<b2WheelJointDef>(*w, r, ReadWheel, true);
        case e_weldJoint: return Create<b2WeldJointDef>(*w, r, ReadWeld, true);
        case e_frictionJoint: return Create<b2FrictionJointDef>(*w, r, ReadFriction, true);
        case e_ropeJoint: return Create<b2RopeJointDef>(*w, r, ReadRope, true);
        default: return Fail("createJoint: unknown joint type " + std::to_string(words[0]));
    }
}

/// Destroys a joint (and the gears coupling it); -1 when there is no such joint.
LOCKBOX_WEB_API int32_t lb_joint_destroy(WebWorld* w, int32_t id) {
    if (w->world->IsLocked()) return Fail("destroyJoint: the world is locked (called from inside a step)");
    b2Joint* j = FindJoint(*w, id, "destroyJoint");
    if (!j) return -1;
    w->world->DestroyJoint(j);
    return 0;
}

/// Writes into out[0..17]: type, body A id, body B id, collideConnected, anchor A (x, y),
/// anchor B (x, y), reaction force (x, y) and torque at inv_dt (raw 1/s), user data (2 words),
/// then two coordinates and a motor effort by type: revolute angle, speed, motor torque;
/// prismatic and wheel translation, speed, motor force or torque; distance length; pulley
/// lengths A and B; gear coordinates A and B; rope max length and limit state; mouse target
/// (x, y); then the motor-enabled and limit-enabled flags. -1 when there is no such joint.
LOCKBOX_WEB_API int32_t lb_joint_state(WebWorld* w, int32_t id, int32_t invDtRaw, int32_t* out) {
    b2Joint* j = FindJoint(*w, id, "joint");
    if (!j) return -1;
    const Fixed invDt = Fx(invDtRaw);
    for (int i = 0; i < 18; ++i) out[i] = 0;
    out[0] = j->GetType();
    out[1] = j->GetBodyA()->GetId();
    out[2] = j->GetBodyB()->GetId();
    out[3] = j->GetCollideConnected() ? 1 : 0;
    const b2Vec2 a = j->GetAnchorA(), b = j->GetAnchorB(), force = j->GetReactionForce(invDt);
    out[4] = a.x.Raw();
    out[5] = a.y.Raw();
    out[6] = b.x.Raw();
    out[7] = b.y.Raw();
    out[8] = force.x.Raw();
    out[9] = force.y.Raw();
    out[10] = j->GetReactionTorque(invDt).Raw();
    PutU64(out + 11, j->GetUserData());
    switch (j->GetType()) {
        case e_revoluteJoint: {
            const auto* r = static_cast<const b2RevoluteJoint*>(j);
            out[13] = r->GetJointAngle().Raw();
            out[14] = r->GetJointSpeed().Raw();
            out[15] = r->GetMotorTorque(invDt).Raw();
            out[16] = r->IsMotorEnabled();
            out[17] = r->IsLimitEnabled();
            break;
        }
        case e_prismaticJoint: {
            const auto* p = static_cast<const b2PrismaticJoint*>(j);
            out[13] = p->GetJointTranslation().Raw();
            out[14] = p->GetJointSpeed().Raw();
            out[15] = p->GetMotorForce(invDt).Raw();
            out[16] = p->IsMotorEnabled();
            out[17] = p->IsLimitEnabled();
            break;
        }
        case e_wheelJoint: {
            const auto* wj = static_cast<const b2WheelJoint*>(j);
            out[13] = wj->GetJointTranslation().Raw();
            out[14] = wj->GetJointSpeed().Raw();
            out[15] = wj->GetMotorTorque(invDt).Raw();
            out[16] = wj->IsMotorEnabled();
            break;
        }
        case e_distanceJoint: out[13] = static_cast<const b2DistanceJoint*>(j)->GetLength().Raw(); break;
        case e_pulleyJoint: {
            const auto* p = static_cast<const b2PulleyJoint*>(j);
            out[13] = p->GetLengthA().Raw();
            out[14] = p->GetLengthB().Raw();
            break;
        }
        case e_gearJoint: {
            const auto* g = static_cast<const b2GearJoint*>(j);
            out[13] = g->GetCoordinateA().Raw();
            out[14] = g->GetCoordinateB().Raw();
            break;
        }
        case e_ropeJoint: {
            const auto* r = static_cast<const b2RopeJoint*>(j);
            out[13] = r->GetMaxLength().Raw();
            out[14] = r->GetLimitState();
            break;
        }
        case e_mouseJoint: {
            const auto* m = static_cast<const b2MouseJoint*>(j);
            out[13] = m->GetTarget().x.Raw();
            out[14] = m->GetTarget().y.Raw();
            break;
        }
        default: break;
    }
    return 0;
}

namespace {

// The setting `kind` on a joint of type J, or -1 when J has no such setting.
int32_t Unsupported(const b2Joint& j, int32_t kind) {
    return Fail("joint " + std::to_string(j.GetId()) + " (type " + std::to_string(j.GetType()) + ") has no setting " +
                std::to_string(kind));
}

}  // namespace

/// Joint settings, by kind: 0 enable motor (a), 1 motor speed, 2 max motor torque or force,
/// 3 enable limit (a), 4 limits (a lower, b upper), 5 mouse target (a, b), 6 spring frequency,
/// 7 damping ratio, 8 length (distance) or max length (rope), 9 ratio (gear), 10 max force
/// (friction: raw Q16.16 in a; mouse: Q32.32 in a low, b high), 11 max torque (friction),
/// 12 user data (a low, b high). Numbers are raw. -1 when refused.
LOCKBOX_WEB_API int32_t lb_joint_set(WebWorld* w, int32_t id, int32_t kind, int32_t a, int32_t b) {
    b2Joint* j = FindJoint(*w, id, "joint");
    if (!j) return -1;
    const b2JointType type = j->GetType();
    auto* rev = type == e_revoluteJoint ? static_cast<b2RevoluteJoint*>(j) : nullptr;
    auto* pri = type == e_prismaticJoint ? static_cast<b2PrismaticJoint*>(j) : nullptr;
    auto* whe = type == e_wheelJoint ? static_cast<b2WheelJoint*>(j) : nullptr;
    switch (kind) {
        case 0:
            if (rev)
                rev->EnableMotor(a != 0);
            else if (pri)
                pri->EnableMotor(a != 0);
            else if (whe)
                whe->EnableMotor(a != 0);
            else
                return Unsupported(*j, kind);
            return 0;
        case 1:
            if (rev)
                rev->SetMotorSpeed(Fx(a));
            else if (pri)
                pri->SetMotorSpeed(Fx(a));
            else if (whe)
                whe->SetMotorSpeed(Fx(a));
            else
                return Unsupported(*j, kind);
            return 0;
        case 2:
            if (a < 0) return Fail("joint: negative motor effort");
            if (rev)
                rev->SetMaxMotorTorque(Fx(a));
            else if (pri)
                pri->SetMaxMotorForce(Fx(a));
            else if (whe)
                whe->SetMaxMotorTorque(Fx(a));
            else
                return Unsupported(*j, kind);
            return 0;
        case 3:
            if (rev)
                rev->EnableLimit(a != 0);
            else if (pri)
                pri->EnableLimit(a != 0);
            else
                return Unsupported(*j, kind);
            return 0;
        case 4:
            if (a > b) return Fail("setLimits: lower above upper");
            if (rev)
                rev->SetLimits(Fx(a), Fx(b));
            else if (pri)
                pri->SetLimits(Fx(a), Fx(b));
            else
                return Unsupported(*j, kind);
            return 0;
        case 5:
            if (type != e_mouseJoint) return Unsupported(*j, kind);
            static_cast<b2MouseJoint*>(j)->SetTarget(b2Vec2(Fx(a), Fx(b)));
            return 0;
        case 6:
            if (type == e_mouseJoint)
                static_cast<b2MouseJoint*>(j)->SetFrequency(Fx(a));
            else if (type == e_distanceJoint)
                static_cast<b2DistanceJoint*>(j)->SetFrequency(Fx(a));
            else if (type == e_weldJoint)
                static_cast<b2WeldJoint*>(j)->SetFrequency(Fx(a));
            else if (whe)
                whe->SetSpringFrequencyHz(Fx(a));
            else
                return Unsupported(*j, kind);
            return 0;
        case 7:
            if (type == e_mouseJoint)
                static_cast<b2MouseJoint*>(j)->SetDampingRatio(Fx(a));
            else if (type == e_distanceJoint)
                static_cast<b2DistanceJoint*>(j)->SetDampingRatio(Fx(a));
            else if (type == e_weldJoint)
                static_cast<b2WeldJoint*>(j)->SetDampingRatio(Fx(a));
            else if (whe)
                whe->SetSpringDampingRatio(Fx(a));
            else
                return Unsupported(*j, kind);
            return 0;
        case 8:
            if (type == e_distanceJoint)
                static_cast<b2DistanceJoint*>(j)->SetLength(Fx(a));
            else if (type == e_ropeJoint)
                static_cast<b2RopeJoint*>(j)->SetMaxLength(Fx(a));
            else
                return Unsupported(*j, kind);
            return 0;
        case 9:
            if (type != e_gearJoint) return Unsupported(*j, kind);
            static_cast<b2GearJoint*>(j)->SetRatio(Fx(a));
            return 0;
        case 10:
            if (type == e_frictionJoint)
                static_cast<b2FrictionJoint*>(j)->SetMaxForce(Fx(a));
            else if (type == e_mouseJoint)
                static_cast<b2MouseJoint*>(j)->SetMaxForce(Wide::FromRaw(static_cast<int64_t>(GetU64(a, b))));
            else
                return Unsupported(*j, kind);
            return 0;
        case 11:
            if (type != e_frictionJoint) return Unsupported(*j, kind);
            static_cast<b2FrictionJoint*>(j)->SetMaxTorque(Fx(a));
            return 0;
        case 12: j->SetUserData(GetU64(a, b)); return 0;
        default: return Fail("unknown joint setting " + std::to_string(kind));
    }
}
