#pragma once
// Scene helpers shared by the dynamics tests. Everything lockbox lives in lockbox::test so
// that unqualified b2 names resolve to lockbox's even where float Box2D (global b2 names) is
// included beside it.
#include <cstdint>
#include <string>
#include <vector>

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

/// A static sensor box of half-extents (hx, hy) centred at (x, y): it reports overlaps and
/// pushes nothing.
inline b2Body* MakeStaticSensorBox(b2World& world, Fixed x, Fixed y, Fixed hx, Fixed hy) {
    b2Body* body = MakeStaticBox(world, x, y, hx, hy);
    body->GetFixtureList()->SetSensor(true);
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

/// A pyramid of unit boxes on a wide static ground: `rows` rows, each half a box to the right of
/// the one below, row r centred at height (baseCm + r stepCm) / 100 m.
inline void MakeBoxPyramid(b2World& world, int rows, int baseCm, int stepCm) {
    MakeStaticBox(world, 0, Fixed(-0.5), 100, Fixed(0.5));
    for (int row = 0; row < rows; ++row) {
        for (int k = 0; k < rows - row; ++k)
            MakeDynamicBox(world, Fixed(-rows / 2 + k) + Fixed::FromRatio(row, 2),
                           Fixed::FromRatio(baseCm + stepCm * row, 100), Fixed(0.5), Fixed(0.5));
    }
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

/// The world's hash after each of `steps` steps of 1/60 s (8 velocity, 3 position iterations).
inline std::vector<uint64_t> StepHashes(b2World& world, int steps) {
    std::vector<uint64_t> hashes;
    for (int i = 0; i < steps; ++i) {
        world.Step(kDt, 8, 3);
        hashes.push_back(world.Hash());
    }
    return hashes;
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
