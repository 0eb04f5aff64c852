// The C API of bodies: create from a definition, destroy, read the state, move and push.
#include <string>

#include "Bindings.h"
#include "DefReader.h"

using namespace lockbox;
using namespace lockbox::web;

/// Creates a body from a definition (DefReader words, fields in this order: type, position,
/// angle, linearVelocity, angularVelocity, linearDamping, angularDamping, allowSleep, awake,
/// fixedRotation, bullet, active, gravityScale, userData). Returns its id, or -1.
LOCKBOX_WEB_API int32_t lb_body_create(WebWorld* w, const int32_t* words, int32_t count) {
    if (w->world->IsLocked()) return Fail("createBody: the world is locked (called from inside a step)");
    DefReader r(words, count);
    b2BodyDef def;
    int32_t type = b2_staticBody;
    if (r.Int(type) && (type < b2_staticBody || type > b2_dynamicBody))
        return Fail("createBody: type " + std::to_string(type) + " is not static (0), kinematic (1) or dynamic (2)");
    def.type = static_cast<b2BodyType>(type);
    r.Vec(def.position);
    r.Fixed(def.angle);
    r.Vec(def.linearVelocity);
    r.Fixed(def.angularVelocity);
    r.Fixed(def.linearDamping);
    r.Fixed(def.angularDamping);
    r.Bool(def.allowSleep);
    r.Bool(def.awake);
    r.Bool(def.fixedRotation);
    r.Bool(def.bullet);
    r.Bool(def.active);
    r.Fixed(def.gravityScale);
    r.U64(def.userData);
    if (!r.ok()) return Fail("createBody: malformed definition");
    if (def.linearDamping < Fixed(0) || def.angularDamping < Fixed(0)) return Fail("createBody: negative damping");
    b2Body* b = w->world->CreateBody(&def);
    return b ? b->GetId() : Fail("createBody: refused");
}

/// Destroys a body with its fixtures and joints; -1 when there is no such body.
LOCKBOX_WEB_API int32_t lb_body_destroy(WebWorld* w, int32_t id) {
    if (w->world->IsLocked()) return Fail("destroyBody: the world is locked (called from inside a step)");
    b2Body* b = FindBody(*w, id, "destroyBody");
    if (!b) return -1;
    w->world->DestroyBody(b);
    return 0;
}

/// Writes the body's state into out[0..21]: position x, y, angle, linear velocity x, y,
/// angular velocity, world centre x, y, local centre x, y, type, flags (1 awake, 2 active,
/// 4 bullet, 8 sleeping allowed, 16 fixed rotation, 32 out of bounds), mass (2 words, Q32.32),
/// inertia (2 words, Q32.32), linear damping, angular damping, gravity scale, user data (2
/// words). Returns -1 when there is no such body.
LOCKBOX_WEB_API int32_t lb_body_state(WebWorld* w, int32_t id, int32_t* out) {
    const b2Body* b = FindBody(*w, id, "body");
    if (!b) return -1;
    out[0] = b->GetPosition().x.Raw();
    out[1] = b->GetPosition().y.Raw();
    out[2] = b->GetAngle().Raw();
    out[3] = b->GetLinearVelocity().x.Raw();
    out[4] = b->GetLinearVelocity().y.Raw();
    out[5] = b->GetAngularVelocity().Raw();
    out[6] = b->GetWorldCenter().x.Raw();
    out[7] = b->GetWorldCenter().y.Raw();
    out[8] = b->GetLocalCenter().x.Raw();
    out[9] = b->GetLocalCenter().y.Raw();
    out[10] = b->GetType();
    out[11] = (b->IsAwake() ? 1 : 0) | (b->IsActive() ? 2 : 0) | (b->IsBullet() ? 4 : 0) |
              (b->IsSleepingAllowed() ? 8 : 0) | (b->IsFixedRotation() ? 16 : 0) | (b->IsOutOfBounds() ? 32 : 0);
    PutU64(out + 12, static_cast<uint64_t>(b->GetMass().Raw()));
    PutU64(out + 14, static_cast<uint64_t>(b->GetInertia().Raw()));
    out[16] = b->GetLinearDamping().Raw();
    out[17] = b->GetAngularDamping().Raw();
    out[18] = b->GetGravityScale().Raw();
    PutU64(out + 19, b->GetUserData());
    out[21] = 0;
    return 0;
}

/// Sets the position (m) and angle (rad); -1 when refused.
LOCKBOX_WEB_API int32_t lb_body_set_transform(WebWorld* w, int32_t id, int32_t x, int32_t y, int32_t angle) {
    if (w->world->IsLocked()) return Fail("setTransform: the world is locked (called from inside a step)");
    b2Body* b = FindBody(*w, id, "setTransform");
    if (!b) return -1;
    b->SetTransform(b2Vec2(Fx(x), Fx(y)), Fx(angle));
    return 0;
}

/// Velocities and pushes, by kind: 0 set linear velocity (x, y), 1 set angular velocity (x),
/// 2 force at a world point (x, y at px, py), 3 force at the centre (x, y), 4 torque (x),
/// 5 linear impulse at a world point (x, y at px, py), 6 angular impulse (x). -1 when refused.
LOCKBOX_WEB_API int32_t lb_body_apply(WebWorld* w, int32_t id, int32_t kind, int32_t x, int32_t y, int32_t px,
                                      int32_t py) {
    b2Body* b = FindBody(*w, id, "body");
    if (!b) return -1;
    const b2Vec2 v(Fx(x), Fx(y));
    const b2Vec2 p(Fx(px), Fx(py));
    switch (kind) {
        case 0: b->SetLinearVelocity(v); break;
        case 1: b->SetAngularVelocity(Fx(x)); break;
        case 2: b->ApplyForce(v, p); break;
        case 3: b->ApplyForceToCenter(v); break;
        case 4: b->ApplyTorque(Fx(x)); break;
        case 5: b->ApplyLinearImpulse(v, p); break;
        case 6: b->ApplyAngularImpulse(Fx(x)); break;
        default: return Fail("unknown body action " + std::to_string(kind));
    }
    return 0;
}

/// Body settings, by kind: 0 type (value 0..2), 1 awake, 2 active, 3 bullet, 4 sleeping
/// allowed, 5 fixed rotation, 6 linear damping (raw), 7 angular damping (raw), 8 gravity
/// scale (raw), 9 user data (value low half, hi high half). -1 when refused.
LOCKBOX_WEB_API int32_t lb_body_set(WebWorld* w, int32_t id, int32_t kind, int32_t value, int32_t hi) {
    b2Body* b = FindBody(*w, id, "body");
    if (!b) return -1;
    const bool structural = kind == 0 || kind == 2 || kind == 5;
    if (structural && w->world->IsLocked()) return Fail("body: the world is locked (called from inside a step)");
    switch (kind) {
        case 0:
            if (value < b2_staticBody || value > b2_dynamicBody)
                return Fail("setType: unknown type " + std::to_string(value));
            b->SetType(static_cast<b2BodyType>(value));
            break;
        case 1: b->SetAwake(value != 0); break;
        case 2: b->SetActive(value != 0); break;
        case 3: b->SetBullet(value != 0); break;
        case 4: b->SetSleepingAllowed(value != 0); break;
        case 5: b->SetFixedRotation(value != 0); break;
        case 6:
            if (value < 0) return Fail("setLinearDamping: negative damping");
            b->SetLinearDamping(Fx(value));
            break;
        case 7:
            if (value < 0) return Fail("setAngularDamping: negative damping");
            b->SetAngularDamping(Fx(value));
            break;
        case 8: b->SetGravityScale(Fx(value)); break;
        case 9: b->SetUserData(GetU64(value, hi)); break;
        default: return Fail("unknown body setting " + std::to_string(kind));
    }
    return 0;
}

/// The ids of the body's fixtures (list order) into the result buffer; returns the count, or
/// -1 when there is no such body.
LOCKBOX_WEB_API int32_t lb_body_fixtures(WebWorld* w, int32_t id) {
    b2Body* b = FindBody(*w, id, "body");
    if (!b) return -1;
    w->results.clear();
    for (b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) w->results.push_back(f->GetId());
    return static_cast<int32_t>(w->results.size());
}

/// A point or vector between body and world frames, by kind: 0 local point to world, 1 world
/// point to local, 2 local vector to world, 3 world vector to local, 4 velocity of a world
/// point. Writes x, y into out[0..1]; -1 when there is no such body.
LOCKBOX_WEB_API int32_t lb_body_transform_point(WebWorld* w, int32_t id, int32_t kind, int32_t x, int32_t y,
                                                int32_t* out) {
    const b2Body* b = FindBody(*w, id, "body");
    if (!b) return -1;
    const b2Vec2 v(Fx(x), Fx(y));
    b2Vec2 r;
    switch (kind) {
        case 0: r = b->GetWorldPoint(v); break;
        case 1: r = b->GetLocalPoint(v); break;
        case 2: r = b->GetWorldVector(v); break;
        case 3: r = b->GetLocalVector(v); break;
        case 4: r = b->GetLinearVelocityFromWorldPoint(v); break;
        default: return Fail("unknown point transform " + std::to_string(kind));
    }
    out[0] = r.x.Raw();
    out[1] = r.y.Raw();
    return 0;
}
