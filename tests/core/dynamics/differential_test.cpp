// Test 6: differential runs against float Box2D 2.4.1 over the first 60 steps at lockbox's
// real time step (1092/65536 s): positions within 0.01 m, angles within 0.01 rad.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "Box2DFloat.h"  // float Box2D without its constant macros
#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

// One scene description, built in both engines from plain doubles (exactly representable in
// Q16.16 or rounded once at compile time on the lockbox side).
struct BoxSpec {
    bool dynamic;
    double x, y, hx, hy, angle, friction;
    bool circle;  // hx is the radius
};

using Trace = std::vector<std::vector<double>>;  // per step: x, y, angle of each dynamic body

Trace RunFloat(const std::vector<BoxSpec>& scene) {
    b2World world(b2Vec2(0.0f, -10.0f));
    std::vector<b2Body*> dynamics;
    for (const BoxSpec& s : scene) {
        b2BodyDef bd;
        bd.type = s.dynamic ? b2_dynamicBody : b2_staticBody;
        bd.position.Set(static_cast<float>(s.x), static_cast<float>(s.y));
        bd.angle = static_cast<float>(s.angle);
        b2Body* body = world.CreateBody(&bd);
        b2FixtureDef fd;
        b2PolygonShape box;
        b2CircleShape circle;
        if (s.circle) {
            circle.m_radius = static_cast<float>(s.hx);
            fd.shape = &circle;
        } else {
            box.SetAsBox(static_cast<float>(s.hx), static_cast<float>(s.hy));
            fd.shape = &box;
        }
        fd.density = s.dynamic ? 1.0f : 0.0f;
        fd.friction = static_cast<float>(s.friction);
        body->CreateFixture(&fd);
        if (s.dynamic) dynamics.push_back(body);
    }
    Trace trace;
    for (int n = 0; n < 60; ++n) {
        world.Step(static_cast<float>(lockbox::test::kDtDouble), 8, 3);
        std::vector<double> row;
        for (b2Body* b : dynamics) {
            row.push_back(b->GetPosition().x);
            row.push_back(b->GetPosition().y);
            row.push_back(b->GetAngle());
        }
        trace.push_back(row);
    }
    return trace;
}

}  // namespace LOCKBOX_TEST_FILE

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

// Scene values are given in milli-units so both engines see the same decimal numbers; the
// lockbox side converts with an exact rational (one rounding, like the float literal).
Fixed Milli(double v) { return Fixed::FromRatio(static_cast<int64_t>(std::llround(v * 1000.0)), 1000); }

Trace RunLockbox(const std::vector<BoxSpec>& scene) {
    b2World world(b2Vec2(0, -10));
    std::vector<b2Body*> dynamics;
    for (const BoxSpec& s : scene) {
        b2BodyDef bd;
        bd.type = s.dynamic ? b2_dynamicBody : b2_staticBody;
        bd.position.Set(Milli(s.x), Milli(s.y));
        bd.angle = Milli(s.angle);
        b2Body* body = world.CreateBody(&bd);
        b2FixtureDef fd;
        b2PolygonShape box;
        b2CircleShape circle;
        if (s.circle) {
            circle.m_radius = Milli(s.hx);
            fd.shape = &circle;
        } else {
            box.SetAsBox(Milli(s.hx), Milli(s.hy));
            fd.shape = &box;
        }
        fd.density = s.dynamic ? 1 : 0;
        fd.friction = Milli(s.friction);
        body->CreateFixture(&fd);
        if (s.dynamic) dynamics.push_back(body);
    }
    Trace trace;
    for (int n = 0; n < 60; ++n) {
        world.Step(kDt, 8, 3);
        std::vector<double> row;
        for (b2Body* b : dynamics) {
            row.push_back(b->GetPosition().x.ToDouble());
            row.push_back(b->GetPosition().y.ToDouble());
            row.push_back(b->GetAngle().ToDouble());
        }
        trace.push_back(row);
    }
    return trace;
}

double Compare(const char* name, const std::vector<BoxSpec>& scene) {
    const Trace ref = RunFloat(scene);
    const Trace got = RunLockbox(scene);
    double worst = 0;
    for (size_t n = 0; n < ref.size(); ++n) {
        for (size_t k = 0; k < ref[n].size(); ++k) {
            EXPECT_NEAR(got[n][k], ref[n][k], 0.01) << name << " step " << n << " value " << k;
            worst = std::max(worst, std::fabs(got[n][k] - ref[n][k]));
        }
    }
    std::printf("differential %-12s worst |lockbox - float| = %.6f\n", name, worst);
    return worst;
}

// Angles in radians: 0.3 rad slope.
const BoxSpec kGround{false, 0, -10, 50, 10, 0, 0.3, false};

TEST(Differential, HelloWorld) { Compare("hello", {kGround, {true, 0, 4, 1, 1, 0, 0.3, false}}); }

TEST(Differential, FallingCircle) { Compare("circle", {kGround, {true, 0.25, 3, 0.5, 0, 0, 0.3, true}}); }

TEST(Differential, BoxOnSlope) {
    // A slope of 0.3 rad (tan 0.309 > mu 0.2): the box slides.
    const double a = 0.3;
    const double nx = -std::sin(a), ny = std::cos(a);
    Compare("slope", {{false, -nx * 1.0, -ny * 1.0, 30, 1, a, 0.2, false},
                      {true, nx * 0.53, ny * 0.53, 0.5, 0.5, a, 0.2, false}});
}

TEST(Differential, SmallStack) {
    Compare("stack", {kGround,
                      {true, 0, 0.6, 0.5, 0.5, 0, 0.6, false},
                      {true, 0.1, 1.8, 0.5, 0.5, 0, 0.6, false},
                      {true, -0.1, 3.0, 0.5, 0.5, 0, 0.6, false}});
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
