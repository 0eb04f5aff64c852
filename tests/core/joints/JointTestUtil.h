#pragma once
// Scene helpers for the joint tests. lockbox names live in lockbox::jt so that float Box2D's
// global b2 names (included by the differential test) never clash.
#include <cmath>
#include <cstdint>

#include "lockbox/dynamics/joints/Joints.h"
#include "lockbox/lockbox.h"

namespace lockbox::jt {

using namespace lockbox::literals;

/// 1/60 s in Q16.16 (raw 1092), lockbox's real step.
inline constexpr Fixed kDt = Fixed::FromRaw(1092);
/// The same step as a double.
inline constexpr double kDtD = 1092.0 / 65536.0;

inline double D(Fixed f) { return f.ToDouble(); }
inline double D(Wide w) { return w.ToDouble(); }
inline double Dist(const b2Vec2& a, const b2Vec2& b) { return std::hypot(D(a.x) - D(b.x), D(a.y) - D(b.y)); }

inline void Step(b2World& world, int n = 1) {
    for (int i = 0; i < n; ++i) world.Step(kDt, 8, 3);
}

inline b2Body* Ground(b2World& world) {
    b2BodyDef bd;
    return world.CreateBody(&bd);
}

/// A dynamic square box of half-extent h at (x, y) with total mass `mass` (kg), set through
/// the density (area 4 h^2).
inline b2Body* Box(b2World& world, Fixed x, Fixed y, Fixed h, Fixed density) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(x, y);
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(h, h);
    body->CreateFixture(&box, density);
    return body;
}

/// A dynamic circle of radius r at (x, y).
inline b2Body* Ball(b2World& world, Fixed x, Fixed y, Fixed r, Fixed density) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(x, y);
    b2Body* body = world.CreateBody(&bd);
    b2CircleShape c;
    c.m_radius = r;
    body->CreateFixture(&c, density);
    return body;
}

/// Counts overflow traps instead of aborting (checked build) so a test can report them.
struct TrapCounter {
    static inline int traps = 0;
    static void Handler(const char*, int64_t, int64_t) { ++traps; }
    OverflowTrapHandler previous;
    TrapCounter() : previous(SetOverflowTrapHandler(&Handler)) {
        traps = 0;
        ResetSaturationCount();
    }
    ~TrapCounter() { SetOverflowTrapHandler(previous); }
    /// Traps (checked build) plus saturations (default build) since construction.
    static uint64_t Events() { return static_cast<uint64_t>(traps) + SaturationCount(); }
};

}  // namespace lockbox::jt
