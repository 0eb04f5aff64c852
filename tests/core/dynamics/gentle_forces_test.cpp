// Forces and impulses below the Q16.16 velocity quantum (1/65536 m/s per step) accumulate as
// they do in float: the solver's velocities are Q32.32 and a body keeps the part below Q16.16
// between steps. Each case is checked against its closed form; with velocities rounded to
// Q16.16 every step, the first never moves, the slope is 4 % fast and the turntable box at
// 2.1 m stays on.
#include <cmath>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;
using lockbox::test::kDt;
using lockbox::test::kDtDouble;

b2Body* UnitBox(b2World& world, Fixed x, Fixed y, Fixed angle, Fixed friction) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(x, y);
    bd.angle = angle;
    bd.allowSleep = false;  // the cases are slower than the sleep tolerance
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(Fixed(0.5), Fixed(0.5));  // 1 m^2 at density 1: 1 kg
    b2FixtureDef fd;
    fd.shape = &box;
    fd.density = 1;
    fd.friction = friction;
    body->CreateFixture(&fd);
    return body;
}

struct ForceCase {
    Fixed force;  // N
    double newtons;
};

class GentleForce : public testing::TestWithParam<ForceCase> {};

TEST_P(GentleForce, ConstantForceGivesFtOverM) {
    const ForceCase c = GetParam();
    b2World world(b2Vec2(0, 0));
    b2Body* box = UnitBox(world, 0, 0, 0, Fixed(0.2));
    ASSERT_EQ(box->GetMass(), Wide(1));
    constexpr int kSteps = 600;
    for (int i = 0; i < kSteps; ++i) {
        box->ApplyForceToCenter(b2Vec2(c.force, 0));
        world.Step(kDt, 8, 3);
    }
    const double expected = c.newtons * kSteps * kDtDouble;  // F t / m
    const double v = box->GetLinearVelocity().x.ToDouble();
    EXPECT_NEAR(v, expected, 0.01 * expected) << "F = " << c.newtons << " N";
    EXPECT_EQ(box->GetLinearVelocity().y, Fixed());
}

INSTANTIATE_TEST_SUITE_P(BelowOneQuantumPerStep, GentleForce,
                         testing::Values(ForceCase{Fixed(0.0004), 0.0004}, ForceCase{Fixed(0.0008), 0.0008},
                                         ForceCase{Fixed(0.0012), 0.0012}));

TEST(GentleForce, ImpulsesBelowOneQuantumAddUp) {
    b2World world(b2Vec2(0, 0));
    b2Body* box = UnitBox(world, 0, 0, 0, Fixed(0.2));
    // 1e-6 N*s on 1 kg is 0.066 of the Q16.16 velocity quantum.
    for (int i = 0; i < 1000; ++i) box->ApplyLinearImpulse(b2Vec2(Fixed(0.000001), 0), box->GetWorldCenter());
    EXPECT_NEAR(box->GetLinearVelocity().x.ToDouble(), 1000 * Fixed(0.000001).ToDouble(), 1.0 / 65536);
}

// A frictionless box on a 0.02 degree slope accelerates at g sin(theta). The slope's angle is
// itself Q16.16 (23 raw, 0.5 % steeper than 0.02 degrees), inside the 1 % bound.
TEST(GentleForce, ShallowSlopeAcceleratesAtGSinTheta) {
    b2World world(b2Vec2(0, -10));
    const double theta = 0.02 * M_PI / 180.0;
    const Fixed angle = Fixed::FromRaw(static_cast<int32_t>(std::lround(theta * 65536.0)));
    lockbox::test::MakeStaticBox(world, 0, 0, 50, Fixed(0.5), angle, Fixed(0));
    b2Body* box = UnitBox(world, 0, 1, angle, Fixed(0));
    box->GetFixtureList()->SetFriction(0);

    constexpr int kSettle = 60, kSteps = 600;
    auto speed = [&] {
        const b2Vec2 v = box->GetLinearVelocity();
        return std::hypot(v.x.ToDouble(), v.y.ToDouble());
    };
    for (int i = 0; i < kSettle; ++i) world.Step(kDt, 8, 3);
    const double v0 = speed();
    for (int i = 0; i < kSteps; ++i) world.Step(kDt, 8, 3);
    const double a = (speed() - v0) / (kSteps * kDtDouble);
    const double expected = 10.0 * std::sin(theta);
    EXPECT_NEAR(a, expected, 0.01 * expected);
    EXPECT_LT(box->GetLinearVelocity().x, Fixed());  // downhill: the slope rises to the right
}

// A 1 kg box held by a friction joint (1 mN normal force, mu 0.8: at most 0.8 mN) on a
// kinematic platform turning at 0.02 rad/s. It needs m w^2 r, so it stays on up to
// r = 0.0008 / 0.0004 = 2 m and slides off beyond.
double TurntableRadiusAfter(Fixed radius, int steps) {
    b2World world(b2Vec2(0, 0));
    b2BodyDef pd;
    pd.type = b2_kinematicBody;
    pd.angularVelocity = Fixed(0.02);
    b2Body* platform = world.CreateBody(&pd);
    b2CircleShape disc;
    disc.m_radius = 5;
    b2FixtureDef pfd;
    pfd.shape = &disc;
    pfd.isSensor = true;  // the joint alone holds the box
    platform->CreateFixture(&pfd);

    b2Body* box = UnitBox(world, radius, 0, 0, Fixed(0));
    box->SetLinearVelocity(b2Vec2(0, MulToFixed(Wide(Fixed(0.02)), radius)));  // moving with the platform
    b2FrictionJointDef jd;
    jd.Initialize(platform, box, box->GetWorldCenter());
    jd.maxForce = Fixed(0.0008);
    jd.maxTorque = 0;
    world.CreateJoint(&jd);

    for (int i = 0; i < steps; ++i) world.Step(kDt, 8, 3);
    return box->GetWorldCenter().Length().ToDouble();
}

TEST(GentleForce, SlowTurntableKeepsTheBoxInsideTheClosedFormRadius) {
    constexpr int kSteps = 12000;  // 200 s, about two thirds of a turn
    const double inside = TurntableRadiusAfter(Fixed(1.9), kSteps);
    const double outside = TurntableRadiusAfter(Fixed(2.1), kSteps);
    EXPECT_NEAR(inside, 1.9, 0.01) << "the box at 1.9 m must stay on";
    EXPECT_GT(outside, 2.2) << "the box at 2.1 m must slide off (it drifts outward, ever faster)";
}

}  // namespace LOCKBOX_TEST_FILE
