// DescribeWorld: a world as a SceneDocument, read through the public API only. Bodies, each
// body's fixtures and the joints are listed in creation order (the world's lists are newest
// first), so that building the document creates them in the same order again: same ids, same
// lists, same state hash.
#include <unordered_map>

#include "lockbox/scenefile/SceneFile.h"

namespace lockbox::scenefile {

namespace {

ShapeDesc DescribeShape(const b2Shape& shape) {
    switch (shape.GetType()) {
        case b2Shape::e_circle: return static_cast<const b2CircleShape&>(shape);
        case b2Shape::e_edge: return static_cast<const b2EdgeShape&>(shape);
        case b2Shape::e_polygon: return static_cast<const b2PolygonShape&>(shape);
        default: return static_cast<const b2ChainShape&>(shape);
    }
}

BodyDesc DescribeBody(const b2Body& body, const SceneMetadata* meta) {
    BodyDesc out;
    b2BodyDef& d = out.def;
    d.type = body.GetType();
    d.position = body.GetPosition();
    d.angle = body.GetAngle();
    d.linearVelocity = body.GetLinearVelocity();
    d.angularVelocity = body.GetAngularVelocity();
    d.linearDamping = body.GetLinearDamping();
    d.angularDamping = body.GetAngularDamping();
    d.gravityScale = body.GetGravityScale();
    d.allowSleep = body.IsSleepingAllowed();
    d.awake = body.IsAwake();
    d.fixedRotation = body.IsFixedRotation();
    d.bullet = body.IsBullet();
    d.active = body.IsActive();
    // As b2dJson: the mass data of a body that has mass (every dynamic body). Setting it back
    // with SetMassData reproduces the body's mass, inverse mass, inertia and centre exactly.
    if (body.GetType() == b2_dynamicBody) {
        b2MassData mass;
        body.GetMassData(&mass);
        out.massData = mass;
    }
    std::vector<const b2Fixture*> fixtures;
    for (const b2Fixture* f = body.GetFixtureList(); f; f = f->GetNext()) fixtures.push_back(f);
    out.fixtures.reserve(fixtures.size());
    for (size_t i = fixtures.size(); i-- > 0;) {
        const b2Fixture& f = *fixtures[i];
        FixtureDesc fd{b2FixtureDef(), DescribeShape(*f.GetShape()), {}};
        fd.def.friction = f.GetFriction();
        fd.def.restitution = f.GetRestitution();
        fd.def.density = f.GetDensity();
        fd.def.isSensor = f.IsSensor();
        fd.def.filter = f.GetFilterData();
        if (meta) {
            if (const ObjectInfo* info = meta->FindFixture(f)) fd.info = *info;
        }
        out.fixtures.push_back(std::move(fd));
    }
    if (meta) {
        if (const ObjectInfo* info = meta->FindBody(body)) out.info = *info;
    }
    return out;
}

// The mouse joint's grab point in world coordinates, as the format stores it, chosen so that
// taking it back into the body's frame (what b2MouseJoint's constructor does) gives the joint's
// local anchor exactly: the rounded world point usually does; when rotation rounding moves it,
// the nearest point within 3 raw units that does is taken.
b2Vec2 GrabPoint(const b2Body& body, const b2Vec2& local) {
    const b2Transform& xf = body.GetTransform();
    const b2Vec2 w0 = b2Mul(xf, local);
    for (int32 ring = 0; ring <= 3; ++ring) {
        for (int32 dy = -ring; dy <= ring; ++dy) {
            for (int32 dx = -ring; dx <= ring; ++dx) {
                if (dx != -ring && dx != ring && dy != -ring && dy != ring) continue;  // the ring only
                const b2Vec2 w(Fixed::FromRaw(w0.x.Raw() + dx), Fixed::FromRaw(w0.y.Raw() + dy));
                if (b2MulT(xf, w) == local) return w;
            }
        }
    }
    return w0;
}

// The definition that recreates `joint` (bodies and geared joints are filled in by index).
JointDefDesc DescribeJointDef(const b2Joint& joint, b2Vec2& mouseTarget) {
    switch (joint.GetType()) {
        case e_revoluteJoint: {
            const auto& j = static_cast<const b2RevoluteJoint&>(joint);
            b2RevoluteJointDef d;
            d.localAnchorA = j.GetLocalAnchorA();
            d.localAnchorB = j.GetLocalAnchorB();
            d.referenceAngle = j.GetReferenceAngle();
            d.enableLimit = j.IsLimitEnabled();
            d.lowerAngle = j.GetLowerLimit();
            d.upperAngle = j.GetUpperLimit();
            d.enableMotor = j.IsMotorEnabled();
            d.motorSpeed = j.GetMotorSpeed();
            d.maxMotorTorque = j.GetMaxMotorTorque();
            return d;
        }
        case e_prismaticJoint: {
            const auto& j = static_cast<const b2PrismaticJoint&>(joint);
            b2PrismaticJointDef d;
            d.localAnchorA = j.GetLocalAnchorA();
            d.localAnchorB = j.GetLocalAnchorB();
            d.localAxisA = j.GetLocalAxisA();
            d.referenceAngle = j.GetReferenceAngle();
            d.enableLimit = j.IsLimitEnabled();
            d.lowerTranslation = j.GetLowerLimit();
            d.upperTranslation = j.GetUpperLimit();
            d.enableMotor = j.IsMotorEnabled();
            d.maxMotorForce = j.GetMaxMotorForce();
            d.motorSpeed = j.GetMotorSpeed();
            return d;
        }
        case e_distanceJoint: {
            const auto& j = static_cast<const b2DistanceJoint&>(joint);
            b2DistanceJointDef d;
            d.localAnchorA = j.GetLocalAnchorA();
            d.localAnchorB = j.GetLocalAnchorB();
            d.length = j.GetLength();
            d.frequencyHz = j.GetFrequency();
            d.dampingRatio = j.GetDampingRatio();
            return d;
        }
        case e_pulleyJoint: {
            const auto& j = static_cast<const b2PulleyJoint&>(joint);
            b2PulleyJointDef d;
            d.groundAnchorA = j.GetGroundAnchorA();
            d.groundAnchorB = j.GetGroundAnchorB();
            d.localAnchorA = j.GetLocalAnchorA();
            d.localAnchorB = j.GetLocalAnchorB();
            d.ratio = j.GetRatio();
            // Side B's current length, and side A's as the rest of the total: the joint keeps
            // lengthA + ratio * lengthB, and (total - ratio * lengthB) + ratio * lengthB gives
            // the total back exactly, whatever rounding ratio * lengthB had. Should side B be
            // longer than the total allows (a stretched pulley), lengthB 0 keeps it exact.
            const Fixed total = j.GetTotalLength();
            d.lengthB = j.GetLengthB();
            const Fixed part = d.ratio * d.lengthB;
            if (part > total) {
                d.lengthB = Fixed();
                d.lengthA = total;
            } else {
                d.lengthA = total - part;
            }
            return d;
        }
        case e_mouseJoint: {
            const auto& j = static_cast<const b2MouseJoint&>(joint);
            b2MouseJointDef d;
            d.target = GrabPoint(*joint.GetBodyB(), j.GetLocalAnchorB());
            mouseTarget = j.GetTarget();
            d.maxForce = j.GetMaxForce();
            d.frequencyHz = j.GetFrequency();
            d.dampingRatio = j.GetDampingRatio();
            return d;
        }
        case e_gearJoint: {
            const auto& j = static_cast<const b2GearJoint&>(joint);
            b2GearJointDef d;
            d.ratio = j.GetRatio();
            return d;
        }
        case e_wheelJoint: {
            const auto& j = static_cast<const b2WheelJoint&>(joint);
            b2WheelJointDef d;
            d.localAnchorA = j.GetLocalAnchorA();
            d.localAnchorB = j.GetLocalAnchorB();
            d.localAxisA = j.GetLocalAxisA();
            d.enableMotor = j.IsMotorEnabled();
            d.motorSpeed = j.GetMotorSpeed();
            d.maxMotorTorque = j.GetMaxMotorTorque();
            d.frequencyHz = j.GetSpringFrequencyHz();
            d.dampingRatio = j.GetSpringDampingRatio();
            return d;
        }
        case e_weldJoint: {
            const auto& j = static_cast<const b2WeldJoint&>(joint);
            b2WeldJointDef d;
            d.localAnchorA = j.GetLocalAnchorA();
            d.localAnchorB = j.GetLocalAnchorB();
            d.referenceAngle = j.GetReferenceAngle();
            d.frequencyHz = j.GetFrequency();
            d.dampingRatio = j.GetDampingRatio();
            return d;
        }
        case e_frictionJoint: {
            const auto& j = static_cast<const b2FrictionJoint&>(joint);
            b2FrictionJointDef d;
            d.localAnchorA = j.GetLocalAnchorA();
            d.localAnchorB = j.GetLocalAnchorB();
            d.maxForce = j.GetMaxForce();
            d.maxTorque = j.GetMaxTorque();
            return d;
        }
        default: {
            const auto& j = static_cast<const b2RopeJoint&>(joint);
            b2RopeJointDef d;
            d.localAnchorA = j.GetLocalAnchorA();
            d.localAnchorB = j.GetLocalAnchorB();
            d.maxLength = j.GetMaxLength();
            return d;
        }
    }
}

}  // namespace

SceneDocument DescribeWorld(const b2World& world, const SceneMetadata* meta) {
    SceneDocument doc;
    WorldDesc& w = doc.world;
    w.gravity = world.GetGravity();
    w.allowSleep = world.GetAllowSleeping();
    w.autoClearForces = world.GetAutoClearForces();
    w.warmStarting = world.GetWarmStarting();
    w.continuousPhysics = world.GetContinuousPhysics();
    w.subStepping = world.GetSubStepping();
    if (meta) {
        w.step = meta->step;
        w.info = meta->worldInfo;
    }

    std::vector<const b2Body*> bodies;
    for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext()) bodies.push_back(b);
    std::unordered_map<int32, int32> bodyIndex;  // body id -> index in the document (lookups only)
    doc.bodies.reserve(bodies.size());
    for (size_t i = bodies.size(); i-- > 0;) {
        bodyIndex[bodies[i]->GetId()] = static_cast<int32>(doc.bodies.size());
        doc.bodies.push_back(DescribeBody(*bodies[i], meta));
    }

    std::vector<const b2Joint*> joints;
    for (const b2Joint* j = world.GetJointList(); j; j = j->GetNext()) joints.push_back(j);
    std::unordered_map<int32, int32> jointIndex;
    doc.joints.reserve(joints.size());
    for (size_t i = joints.size(); i-- > 0;) {
        const b2Joint& joint = *joints[i];
        jointIndex[joint.GetId()] = static_cast<int32>(doc.joints.size());
        JointDesc jd;
        jd.def = DescribeJointDef(joint, jd.mouseTarget);
        jd.bodyA = bodyIndex.at(joint.GetBodyA()->GetId());
        jd.bodyB = bodyIndex.at(joint.GetBodyB()->GetId());
        std::visit([&](auto& d) { d.collideConnected = joint.GetCollideConnected(); }, jd.def);
        if (joint.GetType() == e_gearJoint) {
            // A gear is created after the joints it couples, so they are already listed.
            const auto& gear = static_cast<const b2GearJoint&>(joint);
            jd.joint1 = jointIndex.at(gear.GetJoint1()->GetId());
            jd.joint2 = jointIndex.at(gear.GetJoint2()->GetId());
        }
        if (meta) {
            if (const ObjectInfo* info = meta->FindJoint(joint)) jd.info = *info;
        }
        doc.joints.push_back(std::move(jd));
    }

    if (meta) {
        for (const ImageDesc& image : meta->images) {
            ImageDesc copy = image;
            const auto it = bodyIndex.find(image.body);
            copy.body = image.body >= 0 && it != bodyIndex.end() ? it->second : -1;
            doc.images.push_back(std::move(copy));
        }
    }
    return doc;
}

}  // namespace lockbox::scenefile
