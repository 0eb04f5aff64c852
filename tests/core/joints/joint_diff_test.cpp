// Differential runs against float Box2D 2.4.1 for the first 60 steps at lockbox's real step
// (1092/65536 s): a revolute pendulum, a 10-link chain (the testbed's Chain links) and a car on
// two wheel joints. The worst position deviation of any body is checked against the bound of
// each scene and printed for docs/joints.md.
//
// 2.4.1 differs from 2.2.1 in places: its wheel spring takes stiffness and damping (here from
// b2LinearStiffness with the two-body reduced mass, while 2.2.1 uses the effective mass along
// the axis, including rotation), and its revolute solves the limit separately. The car's
// bound is wider for that reason.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "Box2DFloat.h"  // float Box2D without its constant macros
#include "JointTestUtil.h"

namespace LOCKBOX_TEST_FILE {

namespace lb = lockbox;
using Trace = std::vector<std::vector<double>>;  // per step: x, y, angle of each tracked body

constexpr float kDtF = static_cast<float>(lb::jt::kDtD);

double MaxDeviation(const Trace& a, const Trace& b, double* angle) {
    double worst = 0;
    *angle = 0;
    for (size_t s = 0; s < a.size(); ++s) {
        for (size_t k = 0; k + 2 < a[s].size(); k += 3) {
            worst = std::max(worst, std::hypot(a[s][k] - b[s][k], a[s][k + 1] - b[s][k + 1]));
            *angle = std::max(*angle, std::abs(std::remainder(a[s][k + 2] - b[s][k + 2], 2 * M_PI)));
        }
    }
    return worst;
}

template <typename Body>
void Record(std::vector<double>& row, const Body* b, double x, double y, double a) {
    (void)b;
    row.push_back(x);
    row.push_back(y);
    row.push_back(a);
}

// ---- pendulum and chain -------------------------------------------------------------------

Trace ChainFloat(int links, bool box) {
    b2World world(b2Vec2(0.0f, -10.0f));
    b2BodyDef gd;
    b2Body* ground = world.CreateBody(&gd);
    b2PolygonShape shape;
    if (box)
        shape.SetAsBox(0.5f, 0.5f);
    else
        shape.SetAsBox(0.6f, 0.125f);
    std::vector<b2Body*> bodies;
    b2Body* prev = ground;
    for (int i = 0; i < links; ++i) {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position.Set(box ? 2.0f : static_cast<float>(i) + 0.5f, box ? 10.0f : 25.0f);
        b2Body* body = world.CreateBody(&bd);
        body->CreateFixture(&shape, 20.0f);
        b2RevoluteJointDef jd;
        jd.Initialize(prev, body, box ? b2Vec2(0.0f, 10.0f) : b2Vec2(static_cast<float>(i), 25.0f));
        world.CreateJoint(&jd);
        bodies.push_back(body);
        prev = body;
    }
    Trace t;
    for (int s = 0; s < 60; ++s) {
        world.Step(kDtF, 8, 3);
        std::vector<double> row;
        for (b2Body* b : bodies) Record(row, b, b->GetPosition().x, b->GetPosition().y, b->GetAngle());
        t.push_back(row);
    }
    return t;
}

}  // namespace LOCKBOX_TEST_FILE

namespace lockbox::jt {
namespace LOCKBOX_TEST_FILE {
using Trace = std::vector<std::vector<double>>;

void Record(std::vector<double>& row, double x, double y, double a) {
    row.push_back(x);
    row.push_back(y);
    row.push_back(a);
}

Trace ChainFixed(int links, bool box) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2PolygonShape shape;
    if (box)
        shape.SetAsBox(Fixed(0.5), Fixed(0.5));
    else
        shape.SetAsBox(Fixed(0.6), Fixed(0.125));
    std::vector<b2Body*> bodies;
    b2Body* prev = ground;
    for (int i = 0; i < links; ++i) {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position.Set(box ? Fixed(2) : Fixed(i) + Fixed(0.5), box ? Fixed(10) : Fixed(25));
        b2Body* body = world.CreateBody(&bd);
        body->CreateFixture(&shape, 20);
        b2RevoluteJointDef jd;
        jd.Initialize(prev, body, box ? b2Vec2(0, 10) : b2Vec2(Fixed(i), 25));
        world.CreateJoint(&jd);
        bodies.push_back(body);
        prev = body;
    }
    Trace t;
    for (int s = 0; s < 60; ++s) {
        Step(world);
        std::vector<double> row;
        for (b2Body* b : bodies) Record(row, D(b->GetPosition().x), D(b->GetPosition().y), D(b->GetAngle()));
        t.push_back(row);
    }
    return t;
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::jt

namespace LOCKBOX_TEST_FILE {

TEST(JointDifferential, Pendulum) {
    double angle = 0;
    const double dev = MaxDeviation(ChainFloat(1, true), lb::jt::ChainFixed(1, true), &angle);
    std::printf("[joints] diff pendulum vs Box2D 2.4.1 (60 steps): max position %.6f m, angle %.6f rad\n", dev, angle);
    EXPECT_LT(dev, 0.002);
    EXPECT_LT(angle, 0.002);
}

TEST(JointDifferential, Chain) {
    double angle = 0;
    const double dev = MaxDeviation(ChainFloat(10, false), lb::jt::ChainFixed(10, false), &angle);
    std::printf("[joints] diff 10-link chain vs Box2D 2.4.1 (60 steps): max position %.6f m, angle %.6f rad\n", dev,
                angle);
    EXPECT_LT(dev, 0.01);
    EXPECT_LT(angle, 0.02);
}

// ---- car ------------------------------------------------------------------------------------
// Ground box (top at y = 0), chassis 1.5 x 0.4 half-extents at y = 1.2, wheels of radius 0.4 at
// x = -1, 1, y = 0.45; wheel joints along y at 4 Hz, damping ratio 0.7; the rear motor drives.

Trace CarFloat() {
    b2World world(b2Vec2(0.0f, -10.0f));
    b2BodyDef gd;
    gd.position.Set(0.0f, -0.5f);
    b2Body* ground = world.CreateBody(&gd);
    b2PolygonShape gs;
    gs.SetAsBox(50.0f, 0.5f);
    ground->CreateFixture(&gs, 0.0f);
    b2BodyDef cd;
    cd.type = b2_dynamicBody;
    cd.position.Set(0.0f, 1.2f);
    b2Body* chassis = world.CreateBody(&cd);
    b2PolygonShape cs;
    cs.SetAsBox(1.5f, 0.4f);
    chassis->CreateFixture(&cs, 1.0f);
    std::vector<b2Body*> bodies{chassis};
    for (const float x : {-1.0f, 1.0f}) {
        b2BodyDef wd;
        wd.type = b2_dynamicBody;
        wd.position.Set(x, 0.45f);
        b2Body* wheel = world.CreateBody(&wd);
        b2CircleShape c;
        c.m_radius = 0.4f;
        b2FixtureDef fd;
        fd.shape = &c;
        fd.density = 1.0f;
        fd.friction = 0.9f;
        wheel->CreateFixture(&fd);
        b2WheelJointDef jd;
        jd.Initialize(chassis, wheel, wheel->GetPosition(), b2Vec2(0.0f, 1.0f));
        b2LinearStiffness(jd.stiffness, jd.damping, 4.0f, 0.7f, chassis, wheel);
        jd.enableMotor = x < 0;
        jd.motorSpeed = -10.0f;
        jd.maxMotorTorque = 20.0f;
        world.CreateJoint(&jd);
        bodies.push_back(wheel);
    }
    Trace t;
    for (int s = 0; s < 60; ++s) {
        world.Step(kDtF, 8, 3);
        std::vector<double> row;
        for (b2Body* b : bodies) Record(row, b, b->GetPosition().x, b->GetPosition().y, b->GetAngle());
        t.push_back(row);
    }
    return t;
}

}  // namespace LOCKBOX_TEST_FILE

namespace lockbox::jt {
namespace LOCKBOX_TEST_FILE {

Trace CarFixed() {
    b2World world(b2Vec2(0, -10));
    b2BodyDef gd;
    gd.position.Set(0, Fixed(-0.5));
    b2Body* ground = world.CreateBody(&gd);
    b2PolygonShape gs;
    gs.SetAsBox(50, Fixed(0.5));
    ground->CreateFixture(&gs, 0);
    b2BodyDef cd;
    cd.type = b2_dynamicBody;
    cd.position.Set(0, Fixed(1.2));
    b2Body* chassis = world.CreateBody(&cd);
    b2PolygonShape cs;
    cs.SetAsBox(Fixed(1.5), Fixed(0.4));
    chassis->CreateFixture(&cs, 1);
    std::vector<b2Body*> bodies{chassis};
    for (const int x : {-1, 1}) {
        b2BodyDef wd;
        wd.type = b2_dynamicBody;
        wd.position.Set(x, Fixed(0.45));
        b2Body* wheel = world.CreateBody(&wd);
        b2CircleShape c;
        c.m_radius = Fixed(0.4);
        b2FixtureDef fd;
        fd.shape = &c;
        fd.density = 1;
        fd.friction = Fixed(0.9);
        wheel->CreateFixture(&fd);
        b2WheelJointDef jd;
        jd.Initialize(chassis, wheel, wheel->GetPosition(), b2Vec2(0, 1));
        jd.frequencyHz = 4;
        jd.dampingRatio = Fixed(0.7);
        jd.enableMotor = x < 0;
        jd.motorSpeed = -10;
        jd.maxMotorTorque = 20;
        world.CreateJoint(&jd);
        bodies.push_back(wheel);
    }
    Trace t;
    for (int s = 0; s < 60; ++s) {
        Step(world);
        std::vector<double> row;
        for (b2Body* b : bodies) Record(row, D(b->GetPosition().x), D(b->GetPosition().y), D(b->GetAngle()));
        t.push_back(row);
    }
    return t;
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::jt

namespace LOCKBOX_TEST_FILE {

TEST(JointDifferential, CarOnWheelJoints) {
    const Trace f = CarFloat();
    const Trace x = lb::jt::CarFixed();
    double angle = 0;
    const double dev = MaxDeviation(f, x, &angle);
    std::printf(
        "[joints] diff car vs Box2D 2.4.1 (60 steps): max position %.6f m, angle %.6f rad; chassis x %.4f vs "
        "%.4f\n",
        dev, angle, x.back()[0], f.back()[0]);
    EXPECT_LT(dev, 0.05);
}

}  // namespace LOCKBOX_TEST_FILE
