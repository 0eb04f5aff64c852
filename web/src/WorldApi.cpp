// The C API of a world: create, step, switches, counts, lists, and the world state (hash,
// save, restore).
#include <span>
#include <string>

#include "Bindings.h"

using namespace lockbox;
using namespace lockbox::web;

/// A new empty world with gravity (raw Q16.16), its contact events recorded.
LOCKBOX_WEB_API WebWorld* lb_world_create(int32_t gravityX, int32_t gravityY) {
    auto* w = new WebWorld;
    w->owned = std::make_unique<b2World>(b2Vec2(Fx(gravityX), Fx(gravityY)));
    w->world = w->owned.get();
    w->world->SetContactListener(&w->listener);
    return w;
}

/// Destroys a world made by lb_world_create (a scene's world is destroyed with its scene).
LOCKBOX_WEB_API void lb_world_destroy(WebWorld* w) {
    if (w && w->owned) delete w;
}

/// One step of dt (raw Q16.16 seconds, >= 0) with the given iteration counts (0..1000); -1
/// when refused.
LOCKBOX_WEB_API int32_t lb_world_step(WebWorld* w, int32_t dtRaw, int32_t velocityIterations,
                                      int32_t positionIterations) {
    if (w->world->IsLocked()) return Fail("step: the world is locked (called from inside a step)");
    if (dtRaw < 0) return Fail("step: negative time step");
    // Far beyond any use (the scenes take 8 and 3), and a call from JavaScript that cannot hang.
    if (velocityIterations < 0 || positionIterations < 0 || velocityIterations > 1000 || positionIterations > 1000)
        return Fail("step: iteration counts outside 0..1000");
    w->world->Step(Fx(dtRaw), velocityIterations, positionIterations);
    return 0;
}

/// Clears the forces of every body (only needed with auto-clear off).
LOCKBOX_WEB_API void lb_world_clear_forces(WebWorld* w) { w->world->ClearForces(); }

/// World switches, by index: 0 allow sleeping, 1 warm starting, 2 continuous physics, 3 sub-
/// stepping, 4 auto-clear forces. Returns the previous value, or -1 for an unknown index.
LOCKBOX_WEB_API int32_t lb_world_switch(WebWorld* w, int32_t which, int32_t value) {
    b2World& world = *w->world;
    int32_t old = -1;
    switch (which) {
        case 0:
            old = world.GetAllowSleeping();
            if (value >= 0) world.SetAllowSleeping(value != 0);
            break;
        case 1:
            old = world.GetWarmStarting();
            if (value >= 0) world.SetWarmStarting(value != 0);
            break;
        case 2:
            old = world.GetContinuousPhysics();
            if (value >= 0) world.SetContinuousPhysics(value != 0);
            break;
        case 3:
            old = world.GetSubStepping();
            if (value >= 0) world.SetSubStepping(value != 0);
            break;
        case 4:
            old = world.GetAutoClearForces();
            if (value >= 0) world.SetAutoClearForces(value != 0);
            break;
        default: return Fail("unknown world switch " + std::to_string(which));
    }
    return old;
}

/// Sets the gravity (raw Q16.16).
LOCKBOX_WEB_API void lb_world_set_gravity(WebWorld* w, int32_t x, int32_t y) {
    w->world->SetGravity(b2Vec2(Fx(x), Fx(y)));
}

/// Writes gravity x, y, then the counts of bodies, joints, contacts and broad-phase proxies,
/// then the saturation count (two words), into out[0..7].
LOCKBOX_WEB_API void lb_world_info(WebWorld* w, int32_t* out) {
    const b2World& world = *w->world;
    out[0] = world.GetGravity().x.Raw();
    out[1] = world.GetGravity().y.Raw();
    out[2] = world.GetBodyCount();
    out[3] = world.GetJointCount();
    out[4] = world.GetContactCount();
    out[5] = world.GetProxyCount();
    PutU64(out + 6, world.GetSaturationCount());
}

/// The state hash (XXH3-64, docs/determinism.md) into out[0..1], low half first.
LOCKBOX_WEB_API void lb_world_hash(WebWorld* w, int32_t* out) { PutU64(out, w->world->Hash()); }

/// Saves a snapshot into the world's byte buffer; returns its size (lb_world_bytes points at it).
LOCKBOX_WEB_API int32_t lb_world_save(WebWorld* w) {
    w->world->Save(w->bytes);
    return static_cast<int32_t>(w->bytes.size());
}

/// The bytes of the last snapshot saved.
LOCKBOX_WEB_API const uint8_t* lb_world_bytes(WebWorld* w) { return w->bytes.data(); }

/// Restores a snapshot of `size` bytes; 0 when the world now holds it, -1 when it was refused
/// (the world is unchanged; lb_last_error says why).
LOCKBOX_WEB_API int32_t lb_world_restore(WebWorld* w, const uint8_t* bytes, int32_t size) {
    if (size < 0) return Fail("restore: negative size");
    const b2RestoreResult r = w->world->Restore(std::span<const uint8_t>(bytes, static_cast<size_t>(size)));
    if (!r) return Fail(std::string(b2SnapshotErrorName(r.error)) + ": " + r.message);
    return 0;
}

/// The ids of the bodies (0), joints (1) or contacts' fixture pairs (2: fixture A, fixture B,
/// touching per contact) in list order into the result buffer; returns the word count.
LOCKBOX_WEB_API int32_t lb_world_list(WebWorld* w, int32_t which) {
    std::vector<int32_t>& out = w->results;
    out.clear();
    b2World& world = *w->world;
    switch (which) {
        case 0:
            for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) out.push_back(b->GetId());
            break;
        case 1:
            for (b2Joint* j = world.GetJointList(); j; j = j->GetNext()) out.push_back(j->GetId());
            break;
        case 2:
            for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) {
                out.push_back(c->GetFixtureA()->GetId());
                out.push_back(c->GetFixtureB()->GetId());
                out.push_back(c->IsTouching() ? 1 : 0);
            }
            break;
        default: return Fail("unknown list " + std::to_string(which));
    }
    return static_cast<int32_t>(out.size());
}

/// The result buffer of the last list, query, ray cast or draw.
LOCKBOX_WEB_API const int32_t* lb_world_results(WebWorld* w) { return w->results.data(); }

/// Moves the contact events recorded since the last call into the result buffer (7 words
/// each: begin, fixture A, fixture B, child A, child B, body A, body B); returns the count.
LOCKBOX_WEB_API int32_t lb_world_take_events(WebWorld* w) {
    std::vector<int32_t>& out = w->results;
    out.clear();
    for (const ContactEvent& e : w->listener.events) {
        out.insert(out.end(), {e.begin, e.fixtureA, e.fixtureB, e.childA, e.childB, e.bodyA, e.bodyB});
    }
    const auto n = static_cast<int32_t>(w->listener.events.size());
    w->listener.events.clear();
    return n;
}
