#pragma once
// Scene helpers shared by the dynamics tests. Everything lockbox lives in lockbox::test so
// that unqualified b2 names resolve to lockbox's even where float Box2D (global b2 names) is
// included beside it.
#include <cstdint>
#include <string>

#include "lockbox/lockbox.h"

namespace lockbox::test {

/// 1/60 s in Q16.16 (raw 1092).
inline constexpr Fixed kDt = Fixed::FromRaw(1092);
/// The same step as a double, for float Box2D runs and closed forms.
inline constexpr double kDtDouble = 1092.0 / 65536.0;

/// A static box of half-extents (hx, hy) centred at (x, y), rotated by angle.
inline b2Body* MakeStaticBox(b2World& world, Fixed x, Fixed y, Fixed hx, Fixed hy, Fixed angle = Fixed(),
                             Fixed friction = Fixed(0.2), Fixed restitution = Fixed()) {
    b2BodyDef bd;
    bd.position.Set(x, y);
    bd.angle = angle;
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(hx, hy);
    b2FixtureDef fd;
    fd.shape = &box;
    fd.friction = friction;
    fd.restitution = restitution;
    body->CreateFixture(&fd);
    return body;
}

/// A dynamic box of half-extents (hx, hy) at (x, y).
inline b2Body* MakeDynamicBox(b2World& world, Fixed x, Fixed y, Fixed hx, Fixed hy, Fixed density = 1,
                              Fixed friction = Fixed(0.2), Fixed restitution = Fixed(), Fixed angle = Fixed()) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(x, y);
    bd.angle = angle;
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(hx, hy);
    b2FixtureDef fd;
    fd.shape = &box;
    fd.density = density;
    fd.friction = friction;
    fd.restitution = restitution;
    body->CreateFixture(&fd);
    return body;
}

/// A dynamic circle of radius r at (x, y).
inline b2Body* MakeDynamicCircle(b2World& world, Fixed x, Fixed y, Fixed r, Fixed density = 1,
                                 Fixed friction = Fixed(0.2), Fixed restitution = Fixed()) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(x, y);
    b2Body* body = world.CreateBody(&bd);
    b2CircleShape circle;
    circle.m_radius = r;
    b2FixtureDef fd;
    fd.shape = &circle;
    fd.density = density;
    fd.friction = friction;
    fd.restitution = restitution;
    body->CreateFixture(&fd);
    return body;
}

/// Counts contact events and records their order.
class RecordingListener : public b2ContactListener {
public:
    void BeginContact(b2Contact* c) override {
        ++begins;
        log.push_back('B');
        last = c;
    }
    void EndContact(b2Contact* c) override {
        ++ends;
        log.push_back('E');
        last = c;
    }
    void PreSolve(b2Contact* c, const b2Manifold*) override {
        ++preSolves;
        log.push_back('P');
        last = c;
    }
    void PostSolve(b2Contact* c, const b2ContactImpulse*) override {
        ++postSolves;
        log.push_back('S');
        last = c;
    }
    int begins = 0, ends = 0, preSolves = 0, postSolves = 0;
    std::string log;
    b2Contact* last = nullptr;
};

}  // namespace lockbox::test
