// BuildScene: a document into a world. Everything that could refuse is checked first (the
// world's lock, indices, shapes a hand-made document might hold, body positions against the
// world's bounds), so the world is either built completely or left untouched.
#include <string>

#include "lockbox/scenefile/NumberText.h"
#include "lockbox/scenefile/SceneFile.h"

namespace lockbox::scenefile {

namespace {

std::string BodyPath(size_t i) { return "body[" + std::to_string(i) + "]"; }
std::string JointPath(size_t i) { return "joint[" + std::to_string(i) + "]"; }

bool Inside(const b2AABB& box, const b2Vec2& p) {
    return p.x >= box.lowerBound.x && p.x <= box.upperBound.x && p.y >= box.lowerBound.y && p.y <= box.upperBound.y;
}

std::string VecText(const b2Vec2& v) {
    std::string s(1, '(');
    s += FormatFixed(v.x);
    s += ", ";
    s += FormatFixed(v.y);
    s += ')';
    return s;
}

// A shape a document can hold without breaking CreateFixture: ReadScene's shapes always are;
// these checks guard documents assembled by hand.
bool UsableShape(const ShapeDesc& shape) {
    if (const auto* p = std::get_if<b2PolygonShape>(&shape)) {
        return p->m_vertexCount >= 3 && p->m_vertexCount <= b2_maxPolygonVertices;
    }
    if (const auto* c = std::get_if<b2ChainShape>(&shape)) {
        return c->m_count >= 2 && static_cast<size_t>(c->m_count) == c->m_vertices.size();
    }
    return true;
}

SceneResult Check(const SceneDocument& doc, const b2World& world) {
    if (world.IsLocked()) return {SceneError::e_locked, "", "the world is inside Step; load between steps"};
    const b2AABB& bounds = world.GetWorldBounds();
    const auto bodyCount = static_cast<int64_t>(doc.bodies.size());
    for (size_t i = 0; i < doc.bodies.size(); ++i) {
        const BodyDesc& b = doc.bodies[i];
        if (b.def.type < b2_staticBody || b.def.type > b2_dynamicBody) {
            return {SceneError::e_range, BodyPath(i) + ".type", "not a body type (0, 1 or 2)"};
        }
        if (!Inside(bounds, b.def.position)) {
            return {SceneError::e_range, BodyPath(i) + ".position",
                    VecText(b.def.position) + " is outside the world bounds " + VecText(bounds.lowerBound) + " to " +
                        VecText(bounds.upperBound)};
        }
        for (size_t f = 0; f < b.fixtures.size(); ++f) {
            if (!UsableShape(b.fixtures[f].shape)) {
                return {SceneError::e_shape, BodyPath(i) + ".fixture[" + std::to_string(f) + "]",
                        "the shape is not set (vertex count out of range)"};
            }
        }
    }
    const auto jointCount = static_cast<int64_t>(doc.joints.size());
    for (size_t i = 0; i < doc.joints.size(); ++i) {
        const JointDesc& j = doc.joints[i];
        for (int k = 0; k < 2; ++k) {
            const int32 body = k == 0 ? j.bodyA : j.bodyB;
            if (body < 0 || body >= bodyCount) {
                return {SceneError::e_reference, JointPath(i) + (k == 0 ? ".bodyA" : ".bodyB"),
                        "index " + std::to_string(body) + ", the file has " + std::to_string(bodyCount) + " bodies"};
            }
        }
        // Points given in world coordinates lie in the world, as body positions do.
        const auto outside = [&](const b2Vec2& p, const char* field) -> SceneResult {
            return {SceneError::e_range, JointPath(i) + "." + field,
                    VecText(p) + " is outside the world bounds " + VecText(bounds.lowerBound) + " to " +
                        VecText(bounds.upperBound)};
        };
        if (const auto* pulley = std::get_if<b2PulleyJointDef>(&j.def)) {
            if (!Inside(bounds, pulley->groundAnchorA)) return outside(pulley->groundAnchorA, "groundAnchorA");
            if (!Inside(bounds, pulley->groundAnchorB)) return outside(pulley->groundAnchorB, "groundAnchorB");
        }
        if (const auto* mouse = std::get_if<b2MouseJointDef>(&j.def)) {
            if (!Inside(bounds, mouse->target)) return outside(mouse->target, "anchorB");
            if (!Inside(bounds, j.mouseTarget)) return outside(j.mouseTarget, "target");
        }
        if (!std::holds_alternative<b2GearJointDef>(j.def)) {
            if (j.bodyA == j.bodyB) {
                return {SceneError::e_reference, JointPath(i) + ".bodyB",
                        "bodyA and bodyB are both body " + std::to_string(j.bodyA) + "; a joint joins two bodies"};
            }
            continue;
        }
        for (int k = 0; k < 2; ++k) {
            const int32 ref = k == 0 ? j.joint1 : j.joint2;
            const std::string p = JointPath(i) + (k == 0 ? ".joint1" : ".joint2");
            if (ref < 0 || ref >= jointCount) {
                return {SceneError::e_reference, p,
                        "index " + std::to_string(ref) + ", the file has " + std::to_string(jointCount) + " joints"};
            }
            const b2JointType t = JointDescType(doc.joints[static_cast<size_t>(ref)].def);
            if (t != e_revoluteJoint && t != e_prismaticJoint) {
                return {SceneError::e_reference, p,
                        "joint " + std::to_string(ref) + " is a " + JointTypeName(t) +
                            " joint; a gear couples revolute and prismatic joints"};
            }
        }
    }
    for (size_t i = 0; i < doc.images.size(); ++i) {
        const int32 body = doc.images[i].body;
        if (body < -1 || body >= bodyCount) {
            return {SceneError::e_reference, "image[" + std::to_string(i) + "].body",
                    "index " + std::to_string(body) + ", the file has " + std::to_string(bodyCount) + " bodies"};
        }
    }
    return {};
}

b2Body* BuildBody(const BodyDesc& desc, b2World& world, SceneMetadata* meta) {
    b2Body* body = world.CreateBody(&desc.def);
    for (const FixtureDesc& f : desc.fixtures) {
        b2FixtureDef def = f.def;
        def.shape = std::visit([](const auto& s) -> const b2Shape* { return &s; }, f.shape);
        b2Fixture* fixture = body->CreateFixture(&def);
        if (meta && !f.info.Empty()) meta->Fixture(*fixture) = f.info;
    }
    if (desc.massData && desc.def.type == b2_dynamicBody) body->SetMassData(&*desc.massData);
    // The file's linear velocity is the body's (its centre of mass's). A body created with it
    // keeps the velocity of its origin while fixtures move the centre of mass, which changes
    // the reported velocity when the body spins; put the file's value back then.
    if (desc.def.type == b2_dynamicBody && body->GetLinearVelocity() != desc.def.linearVelocity) {
        body->SetLinearVelocity(desc.def.linearVelocity);
    }
    if (meta && !desc.info.Empty()) meta->Body(*body) = desc.info;
    return body;
}

b2Joint* BuildJoint(const JointDesc& desc, b2World& world, const std::vector<b2Body*>& bodies,
                    const std::vector<b2Joint*>& joints) {
    return std::visit(
        [&](const auto& d) -> b2Joint* {
            auto def = d;
            def.bodyA = bodies[static_cast<size_t>(desc.bodyA)];
            def.bodyB = bodies[static_cast<size_t>(desc.bodyB)];
            if constexpr (std::is_same_v<std::decay_t<decltype(d)>, b2GearJointDef>) {
                def.joint1 = joints[static_cast<size_t>(desc.joint1)];
                def.joint2 = joints[static_cast<size_t>(desc.joint2)];
            }
            b2Joint* joint = world.CreateJoint(&def);
            if constexpr (std::is_same_v<std::decay_t<decltype(d)>, b2MouseJointDef>) {
                // b2dJson creates the joint at its grab point, then moves the target (which wakes
                // the body): only move it when it is elsewhere.
                auto* mouse = static_cast<b2MouseJoint*>(joint);
                if (desc.mouseTarget != def.target) mouse->SetTarget(desc.mouseTarget);
            }
            return joint;
        },
        desc.def);
}

}  // namespace

SceneResult BuildScene(const SceneDocument& doc, b2World& world, SceneMetadata* meta) {
    SceneResult checked = Check(doc, world);
    if (!checked) return checked;

    const WorldDesc& w = doc.world;
    world.SetGravity(w.gravity);
    world.SetAllowSleeping(w.allowSleep);
    world.SetAutoClearForces(w.autoClearForces);
    world.SetWarmStarting(w.warmStarting);
    world.SetContinuousPhysics(w.continuousPhysics);
    world.SetSubStepping(w.subStepping);

    std::vector<b2Body*> bodies;
    bodies.reserve(doc.bodies.size());
    for (const BodyDesc& b : doc.bodies) bodies.push_back(BuildBody(b, world, meta));

    // Joints in list order, except a gear joint naming a joint later in the list: those follow
    // all the others (b2dJson's second pass; a file b2dJson or lockbox wrote never has one).
    std::vector<b2Joint*> joints(doc.joints.size(), nullptr);
    std::vector<size_t> deferred;
    for (size_t i = 0; i < doc.joints.size(); ++i) {
        const JointDesc& j = doc.joints[i];
        if (std::holds_alternative<b2GearJointDef>(j.def) &&
            (static_cast<size_t>(j.joint1) > i || static_cast<size_t>(j.joint2) > i)) {
            deferred.push_back(i);
            continue;
        }
        joints[i] = BuildJoint(j, world, bodies, joints);
    }
    for (size_t i : deferred) joints[i] = BuildJoint(doc.joints[i], world, bodies, joints);

    if (meta) {
        for (size_t i = 0; i < joints.size(); ++i) {
            if (joints[i] && !doc.joints[i].info.Empty()) meta->Joint(*joints[i]) = doc.joints[i].info;
        }
        meta->worldInfo = w.info;
        meta->step = w.step;
        for (const ImageDesc& image : doc.images) {
            ImageDesc copy = image;
            copy.body = image.body < 0 ? -1 : bodies[static_cast<size_t>(image.body)]->GetId();
            meta->images.push_back(std::move(copy));
        }
    }
    return {};
}

SceneResult LoadScene(std::string_view json, b2World& world, SceneMetadata* metadata, const SceneLimits& limits) {
    SceneDocument doc;
    SceneResult r = ReadScene(json, doc, limits);
    if (!r) return r;
    return BuildScene(doc, world, metadata);
}

std::unique_ptr<b2World> LoadSceneWorld(std::string_view json, SceneResult* result, SceneMetadata* metadata,
                                        const SceneLimits& limits) {
    SceneDocument doc;
    SceneResult r = ReadScene(json, doc, limits);
    std::unique_ptr<b2World> world;
    if (r) {
        world = std::make_unique<b2World>(doc.world.gravity);
        r = BuildScene(doc, *world, metadata);
        if (!r) world.reset();
    }
    if (result) *result = std::move(r);
    return world;
}

}  // namespace lockbox::scenefile
