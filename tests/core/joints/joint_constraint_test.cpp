// Constraint error of every joint type over 600 steps under gravity, with a light (0.1 kg)
// and a heavy (100 kg) body. Each scene swings or slides so the constraint is loaded and
// moving; the worst error over all steps is checked against the bound in the table below and
// printed for docs/joints.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "JointTestUtil.h"

namespace lockbox::jt {
namespace LOCKBOX_TEST_FILE {

// Box of half-extent 0.25 m (area 0.25 m^2): density 0.4 -> 0.1 kg, 400 -> 100 kg.
struct Mass {
    const char* name;
    Fixed density;
};
constexpr Mass kLight{"0.1 kg", Fixed(0.4)};
constexpr Mass kHeavy{"100 kg", Fixed(400)};
constexpr Fixed kHalf = Fixed(0.25);
constexpr int kSteps = 600;

// Bounds (m or rad): a few linearSlop (0.005 m) / angularSlop (0.035 rad), the tolerance the
// position solver aims for; rigid joints under gravity settle well inside them.
constexpr double kLinearBound = 0.01;
constexpr double kAngularBound = 0.02;

double RunWorst(b2World& world, const std::function<double()>& error) {
    double worst = 0;
    for (int i = 0; i < kSteps; ++i) {
        Step(world);
        worst = std::max(worst, error());
    }
    return worst;
}

class JointError : public ::testing::TestWithParam<Mass> {};

TEST_P(JointError, Revolute) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 2, 10, kHalf, GetParam().density);
    b2Body* b = Box(world, 4, 10, kHalf, GetParam().density);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, a, b2Vec2(0, 10));
    auto* j1 = static_cast<b2RevoluteJoint*>(world.CreateJoint(&rd));
    rd.Initialize(a, b, b2Vec2(3, 10));
    auto* j2 = static_cast<b2RevoluteJoint*>(world.CreateJoint(&rd));
    const double worst = RunWorst(world, [&] {
        return std::max(Dist(j1->GetAnchorA(), j1->GetAnchorB()), Dist(j2->GetAnchorA(), j2->GetAnchorB()));
    });
    std::printf("[joints] revolute double pendulum %s: max anchor separation %.5f m\n", GetParam().name, worst);
    // The double pendulum released horizontally whips through its first swings: float Box2D
    // 2.4.1 measures 0.0204 m on this scene (same step and iterations), so the bound is 0.025.
    EXPECT_LT(worst, 0.025);
}

TEST_P(JointError, DistanceRigid) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 3, 10, kHalf, GetParam().density);
    b2DistanceJointDef dd;
    dd.Initialize(ground, a, b2Vec2(0, 10), a->GetPosition());
    auto* j = static_cast<b2DistanceJoint*>(world.CreateJoint(&dd));
    const double worst = RunWorst(world, [&] { return std::abs(Dist(j->GetAnchorA(), j->GetAnchorB()) - 3.0); });
    std::printf("[joints] distance %s: max length error %.5f m\n", GetParam().name, worst);
    EXPECT_LT(worst, kLinearBound);
}

TEST_P(JointError, Prismatic) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 0, 10, kHalf, GetParam().density);
    b2PrismaticJointDef pd;
    // A 45 degree slide with the anchor 1 m off the centre: gravity loads the axis and the angle.
    pd.Initialize(ground, a, b2Vec2(1, 10), b2Vec2(1, 1));
    pd.enableLimit = true;
    pd.lowerTranslation = -5;
    pd.upperTranslation = 5;
    auto* j = static_cast<b2PrismaticJoint*>(world.CreateJoint(&pd));
    const b2Vec2 axis = j->GetLocalAxisA();
    double worstAngle = 0;
    const double worst = RunWorst(world, [&] {
        const b2Vec2 d = j->GetAnchorB() - j->GetAnchorA();
        worstAngle = std::max(worstAngle, std::abs(D(a->GetAngle())));
        return std::abs(D(b2Cross(d, axis)));
    });
    std::printf("[joints] prismatic %s: max perpendicular %.5f m, angle %.5f rad, final translation %.4f\n",
                GetParam().name, worst, worstAngle, D(j->GetJointTranslation()));
    EXPECT_LT(worst, kLinearBound);
    EXPECT_LT(worstAngle, kAngularBound);
    EXPECT_GT(D(j->GetJointTranslation()), -5.0 - kLinearBound);
}

TEST_P(JointError, Wheel) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Ball(world, 0, 10, kHalf, GetParam().density);
    b2WheelJointDef wd;
    wd.Initialize(ground, a, b2Vec2(0, 10), b2Vec2(1, 1));
    wd.frequencyHz = 4;
    wd.dampingRatio = Fixed(0.7);
    auto* j = static_cast<b2WheelJoint*>(world.CreateJoint(&wd));
    const b2Vec2 axis(Fixed(0.707107), Fixed(0.707107));
    const double worst = RunWorst(world, [&] {
        const b2Vec2 d = j->GetAnchorB() - j->GetAnchorA();
        return std::abs(D(b2Cross(d, axis)));
    });
    // Spring equilibrium along the axis: m g sin45 / k with k = m (2 pi 4)^2.
    const double expected = -10.0 * 0.70710678 / std::pow(2 * M_PI * 4, 2);
    std::printf("[joints] wheel %s: max off-axis %.5f m, translation %.5f m (spring equilibrium %.5f)\n",
                GetParam().name, worst, D(j->GetJointTranslation()), expected);
    EXPECT_LT(worst, kLinearBound);
    EXPECT_NEAR(D(j->GetJointTranslation()), expected, 0.002);
}

TEST_P(JointError, Weld) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 1, 10, kHalf, GetParam().density);
    b2Body* b = Box(world, 2, 10, kHalf, GetParam().density);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, a, b2Vec2(0, 10));
    world.CreateJoint(&rd);
    b2WeldJointDef wd;
    wd.Initialize(a, b, b2Vec2(Fixed(1.5), 10));
    auto* j = static_cast<b2WeldJoint*>(world.CreateJoint(&wd));
    double worstAngle = 0;
    const double worst = RunWorst(world, [&] {
        worstAngle = std::max(worstAngle, std::abs(D(math::WrapAngle(b->GetAngle() - a->GetAngle()))));
        return Dist(j->GetAnchorA(), j->GetAnchorB());
    });
    std::printf("[joints] weld %s: max anchor separation %.5f m, angle %.5f rad\n", GetParam().name, worst, worstAngle);
    EXPECT_LT(worst, kLinearBound);
    EXPECT_LT(worstAngle, kAngularBound);
}

TEST_P(JointError, Rope) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 2, 10, kHalf, GetParam().density);
    b2RopeJointDef rd;
    rd.bodyA = ground;
    rd.bodyB = a;
    rd.localAnchorA.Set(0, 10);
    rd.localAnchorB.Set(0, 0);
    rd.maxLength = 3;
    auto* j = static_cast<b2RopeJoint*>(world.CreateJoint(&rd));
    const double worst = RunWorst(world, [&] { return Dist(j->GetAnchorA(), j->GetAnchorB()) - 3.0; });
    std::printf("[joints] rope %s: max excess over maxLength %.5f m\n", GetParam().name, worst);
    EXPECT_LT(worst, kLinearBound);
}

TEST_P(JointError, Pulley) {
    b2World world(b2Vec2(0, -10));
    b2Body* a = Box(world, -3, 5, kHalf, GetParam().density);
    b2Body* b = Box(world, 3, 5, kHalf, GetParam().density * Fixed(1.02));
    b2PulleyJointDef pd;
    pd.Initialize(a, b, b2Vec2(-3, 15), b2Vec2(3, 15), b2Vec2(-3, Fixed(5.25)), b2Vec2(3, Fixed(5.25)), 1);
    auto* j = static_cast<b2PulleyJoint*>(world.CreateJoint(&pd));
    const double c0 = D(j->GetLengthA()) + D(j->GetLengthB());
    const double worst = RunWorst(world, [&] { return std::abs(D(j->GetLengthA()) + D(j->GetLengthB()) - c0); });
    std::printf("[joints] pulley %s: max |lengthA + lengthB - constant| %.5f m (moved %.3f m)\n", GetParam().name,
                worst, D(j->GetLengthB()) - 9.75);
    EXPECT_LT(worst, kLinearBound);
}

TEST_P(JointError, Gear) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    // Two pendulum discs geared 1:2; gravity drives the off-centre one.
    b2Body* a = Box(world, 1, 10, kHalf, GetParam().density);
    b2Body* b = Ball(world, 5, 10, kHalf, GetParam().density);
    b2RevoluteJointDef r1;
    r1.Initialize(ground, a, b2Vec2(0, 10));
    auto* j1 = static_cast<b2RevoluteJoint*>(world.CreateJoint(&r1));
    b2RevoluteJointDef r2;
    r2.Initialize(ground, b, b2Vec2(5, 10));
    auto* j2 = static_cast<b2RevoluteJoint*>(world.CreateJoint(&r2));
    b2GearJointDef gd;
    gd.joint1 = j1;
    gd.joint2 = j2;
    gd.ratio = 2;
    world.CreateJoint(&gd);
    const double worst = RunWorst(world, [&] { return std::abs(D(j1->GetJointAngle()) + 2 * D(j2->GetJointAngle())); });
    std::printf("[joints] gear (revolute-revolute, ratio 2) %s: max |angle1 + 2 angle2| %.5f rad\n", GetParam().name,
                worst);
    EXPECT_LT(worst, kAngularBound);
}

TEST_P(JointError, Friction) {
    // Top-down friction holds a body against gravity when maxForce exceeds m g.
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 0, 10, kHalf, GetParam().density);
    b2FrictionJointDef fd;
    fd.Initialize(ground, a, a->GetWorldCenter());
    fd.maxForce = Fixed(D(a->GetMass()) > 10 ? 2000 : 2);
    fd.maxTorque = 10;
    world.CreateJoint(&fd);
    const double worst = RunWorst(world, [&] { return Dist(a->GetPosition(), b2Vec2(0, 10)); });
    std::printf("[joints] friction %s: max drift %.5f m\n", GetParam().name, worst);
    EXPECT_LT(worst, kLinearBound);
}

TEST_P(JointError, Mouse) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 0, 10, kHalf, GetParam().density);
    b2MouseJointDef md;
    md.bodyA = ground;
    md.bodyB = a;
    md.target = a->GetPosition();
    md.maxForce = a->GetMass() * Fixed(1000);
    auto* j = static_cast<b2MouseJoint*>(world.CreateJoint(&md));
    j->SetTarget(b2Vec2(2, 12));
    double last = 0;
    RunWorst(world, [&] {
        last = Dist(a->GetPosition(), j->GetTarget());
        return last;
    });
    // Under gravity a 5 Hz mouse spring sags by g / omega^2 = 10 mm.
    const double sag = 10.0 / std::pow(2 * M_PI * 5, 2);
    std::printf("[joints] mouse %s: final distance to target %.5f m (spring sag %.5f)\n", GetParam().name, last, sag);
    EXPECT_NEAR(last, sag, 0.002);
}

INSTANTIATE_TEST_SUITE_P(LightAndHeavy, JointError, ::testing::Values(kLight, kHeavy),
                         [](const ::testing::TestParamInfo<Mass>& p) {
                             return std::string(p.param.density > Fixed(1) ? "Heavy100kg" : "Light100g");
                         });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::jt
