// NUMERICS stability test 4 with joints: a wheel driven at 94 rad/s (the maxRotation cap is
// 94.25 rad/s) for 30 simulated minutes (108 000 steps). The body angle stays in [-pi, pi),
// the joint's continuous angle never saturates, and afterwards a limit at +-10 turns around
// the current angle still holds. A gear on the spinning wheel keeps its invariant too.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "../JointTestUtil.h"

namespace lockbox::jt {
namespace LOCKBOX_TEST_FILE {

TEST(JointSpin, ThirtyMinutesAt94RadPerSecond) {
    TrapCounter traps;
    b2World world(b2Vec2(0, 0));
    b2Body* ground = Ground(world);
    b2Body* wheel = Ball(world, 0, 0, Fixed(0.5), 1);
    b2Body* wheel2 = Ball(world, 3, 0, Fixed(0.5), 1);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, wheel, wheel->GetPosition());
    rd.enableMotor = true;
    rd.motorSpeed = 94;
    rd.maxMotorTorque = 1000;
    auto* j = static_cast<b2RevoluteJoint*>(world.CreateJoint(&rd));
    b2RevoluteJointDef rd2;
    rd2.Initialize(ground, wheel2, wheel2->GetPosition());
    auto* j2 = static_cast<b2RevoluteJoint*>(world.CreateJoint(&rd2));
    b2GearJointDef gd;
    gd.joint1 = j;
    gd.joint2 = j2;
    gd.ratio = 1;
    world.CreateJoint(&gd);

    double worstGear = 0;
    for (int i = 0; i < 108000; ++i) {
        Step(world);
        ASSERT_GE(wheel->GetAngle(), -b2_pi);
        ASSERT_LE(wheel->GetAngle(), b2_pi);
        // The gear keeps wheel2 turning the other way: wB - wA relation on speeds.
        if (i % 100 == 0) worstGear = std::max(worstGear, std::abs(D(j->GetJointSpeed()) + D(j2->GetJointSpeed())));
    }
    std::printf("[joints] spin 30 min at 94 rad/s: joint angle %.4f rad, speed %.4f, gear speed error %.6f\n",
                D(j->GetJointAngle()), D(j->GetJointSpeed()), worstGear);
    EXPECT_NEAR(D(j->GetJointSpeed()), 94.0, 0.01);
    EXPECT_LT(std::abs(D(j->GetJointAngle())), D(kMaxContinuousAngle) + 4);
    EXPECT_LT(worstGear, 0.01);
    EXPECT_EQ(TrapCounter::Events(), 0u);

    // Limit of +-10 turns around the current angle, then wind into it at 10 rad/s.
    const Fixed a0 = j->GetJointAngle();
    const Fixed tenTurns = Fixed(10) * math::kTwoPi;
    j->SetLimits(a0 - tenTurns, a0 + tenTurns);
    j->EnableLimit(true);
    j->SetMotorSpeed(10);
    j->SetMaxMotorTorque(50);
    double maxOver = -1e9;
    for (int i = 0; i < 1200; ++i) {
        Step(world);
        maxOver = std::max(maxOver, D(j->GetJointAngle() - a0 - tenTurns));
    }
    std::printf("[joints] after the spin: +10-turn limit overshoot max %.5f, final %.5f rad\n", maxOver,
                D(j->GetJointAngle() - a0 - tenTurns));
    EXPECT_NEAR(D(j->GetJointAngle() - a0 - tenTurns), 0.0, 0.05);
    EXPECT_LT(maxOver, 10 * kDtD + 0.035 + 0.01);
    EXPECT_EQ(TrapCounter::Events(), 0u);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::jt
