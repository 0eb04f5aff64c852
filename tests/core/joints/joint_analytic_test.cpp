// Analytic checks: pendulum period, hanging reaction force, spring frequency, pulley and gear
// invariants, motor speed and stall, limits under load, rope length, friction stopping
// distance. Each bound is written next to its check; measured figures are printed for
// docs/joints.md.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "JointTestUtil.h"

namespace lockbox::jt {
namespace LOCKBOX_TEST_FILE {

// Times (s) at which a sampled signal crosses `level` upward, linearly interpolated.
std::vector<double> UpCrossings(const std::vector<double>& s, double level) {
    std::vector<double> t;
    for (size_t i = 1; i < s.size(); ++i) {
        if (s[i - 1] < level && s[i] >= level) {
            const double f = (level - s[i - 1]) / (s[i] - s[i - 1]);
            t.push_back((static_cast<double>(i - 1) + f) * kDtD);
        }
    }
    return t;
}

double MeanPeriod(const std::vector<double>& crossings) {
    return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

// Small-angle pendulum: a 2 cm ball on a 1 m revolute arm, 0.05 rad amplitude. The ball's own
// inertia adds r^2/(2 L^2) = 2e-4 and the amplitude theta^2/16 = 1.6e-4 to the period.
TEST(JointAnalytic, RevolutePendulumPeriod) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    const Fixed L = 1;
    const Fixed theta0 = Fixed(0.05);
    b2Body* ball = Ball(world, L * math::Sin(theta0), Fixed(10) - L * math::Cos(theta0), Fixed(0.02), 10);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, ball, b2Vec2(0, 10));
    world.CreateJoint(&rd);
    std::vector<double> x;
    for (int i = 0; i < 1200; ++i) {
        Step(world);
        x.push_back(D(ball->GetPosition().x));
    }
    const std::vector<double> c = UpCrossings(x, 0.0);
    ASSERT_GE(c.size(), 5u);
    const double period = MeanPeriod(c);
    const double expected = 2 * M_PI * std::sqrt(1.0 / 10.0);
    std::printf("[joints] pendulum period %.5f s vs 2 pi sqrt(L/g) %.5f s: %.3f %%\n", period, expected,
                100 * (period / expected - 1));
    EXPECT_NEAR(period / expected, 1.0, 0.01);
}

// A 2 kg body hanging at rest: the revolute reaction on it is m g upward within 0.5 %.
TEST(JointAnalytic, HangingReactionForce) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* body = Box(world, 0, 9, Fixed(0.5), Fixed(2));  // 1 m^2 * 2 kg/m^2 = 2 kg
    b2RevoluteJointDef rd;
    rd.Initialize(ground, body, b2Vec2(0, 10));
    b2Joint* j = world.CreateJoint(&rd);
    Step(world, 120);
    const b2Vec2 f = j->GetReactionForce(Fixed(1) / kDt);
    const double mg = D(body->GetMass()) * 10;
    std::printf("[joints] hanging reaction %.4f N vs m g %.4f N: %.4f %%\n", D(f.y), mg, 100 * (D(f.y) / mg - 1));
    EXPECT_NEAR(D(f.y) / mg, 1.0, 0.005);
    EXPECT_NEAR(D(f.x), 0.0, 0.005 * mg);
}

// A distance-joint spring (no damping) oscillates at frequencyHz within 5 %. The soft step
// (implicit in the spring) lowers the frequency by about (omega h)^2 / 3: -1.3 % at 2 Hz, and
// -5.3 % at 4 Hz (omega h = 0.42), which is why the checked range stops at 2 Hz at 60 Hz.
TEST(JointAnalytic, DistanceSpringFrequency) {
    for (const Fixed hz : {Fixed(0.5), Fixed(1), Fixed(2)}) {
        b2World world(b2Vec2(0, 0));
        b2Body* ground = Ground(world);
        b2Body* ball = Ball(world, 0, Fixed(-2.2), Fixed(0.1), 10);
        b2DistanceJointDef dd;
        dd.Initialize(ground, ball, b2Vec2(0, 0), ball->GetPosition());
        dd.length = 2;
        dd.frequencyHz = hz;
        world.CreateJoint(&dd);
        std::vector<double> y;
        for (int i = 0; i < 900; ++i) {
            Step(world);
            y.push_back(D(ball->GetPosition().y));
        }
        const std::vector<double> c = UpCrossings(y, -2.0);
        ASSERT_GE(c.size(), 2u);
        const double f = 1.0 / MeanPeriod(c);
        std::printf("[joints] distance spring %.2f Hz: measured %.4f Hz (%.2f %%)\n", D(hz), f, 100 * (f / D(hz) - 1));
        EXPECT_NEAR(f / D(hz), 1.0, 0.05);
    }
}

// Pulley: lengthA + ratio * lengthB stays constant within 0.01 m while the bodies move.
TEST(JointAnalytic, PulleyInvariant) {
    for (const Fixed ratio : {Fixed(1), Fixed(2)}) {
        b2World world(b2Vec2(0, -10));
        b2Body* a = Box(world, -3, 5, Fixed(0.5), 2);
        b2Body* b = Box(world, 3, 5, Fixed(0.5), 1);
        b2PulleyJointDef pd;
        pd.Initialize(a, b, b2Vec2(-3, 15), b2Vec2(3, 15), a->GetPosition(), b->GetPosition(), ratio);
        auto* j = static_cast<b2PulleyJoint*>(world.CreateJoint(&pd));
        const double r = D(ratio);
        const double c0 = D(j->GetLengthA()) + r * D(j->GetLengthB());
        double worst = 0;
        for (int i = 0; i < 300; ++i) {
            Step(world);
            if (D(j->GetLengthA()) < 1 || D(j->GetLengthB()) < 1) break;
            worst = std::max(worst, std::abs(D(j->GetLengthA()) + r * D(j->GetLengthB()) - c0));
        }
        std::printf("[joints] pulley ratio %.0f: max drift of lengthA + ratio lengthB %.5f m\n", r, worst);
        EXPECT_LT(worst, 0.01);
    }
}

// The singular case the manual warns about: one side pulled to zero length stays finite.
TEST(JointAnalytic, PulleyZeroLengthStaysFinite) {
    TrapCounter traps;
    b2World world(b2Vec2(0, -10));
    b2Body* a = Ball(world, -3, 14, Fixed(0.25), 1);
    b2Body* b = Box(world, 3, 5, Fixed(0.5), 20);  // 20 kg against 0.2 kg
    b2PulleyJointDef pd;
    pd.Initialize(a, b, b2Vec2(-3, 15), b2Vec2(3, 15), a->GetPosition(), b->GetPosition(), 1);
    auto* j = static_cast<b2PulleyJoint*>(world.CreateJoint(&pd));
    double minA = 1e9;
    for (int i = 0; i < 600; ++i) {
        Step(world);
        minA = std::min(minA, D(j->GetLengthA()));
        ASSERT_LT(std::abs(D(a->GetPosition().y)), 1000.0);
        ASSERT_LT(std::abs(D(b->GetPosition().y)), 1000.0);
    }
    std::printf("[joints] pulley driven to zero length: min lengthA %.4f m, body B at y %.3f\n", minA,
                D(b->GetPosition().y));
    EXPECT_LT(minA, 0.1);
    EXPECT_EQ(TrapCounter::Events(), 0u);
}

// Gear: angle1 + ratio * translation2 stays constant for a revolute geared to a prismatic.
TEST(JointAnalytic, GearRevolutePrismatic) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* wheel = Ball(world, 0, 10, 1, 1);
    b2Body* rack = Box(world, 3, 10, Fixed(0.5), 1);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, wheel, wheel->GetPosition());
    auto* r = static_cast<b2RevoluteJoint*>(world.CreateJoint(&rd));
    b2PrismaticJointDef pd;
    pd.Initialize(ground, rack, rack->GetPosition(), b2Vec2(0, 1));
    auto* p = static_cast<b2PrismaticJoint*>(world.CreateJoint(&pd));
    b2GearJointDef gd;
    gd.joint1 = r;
    gd.joint2 = p;
    gd.ratio = Fixed(1) / Fixed(1);  // 1 rad per metre
    world.CreateJoint(&gd);
    double worst = 0;
    for (int i = 0; i < 240; ++i) {
        Step(world);
        worst = std::max(worst, std::abs(D(r->GetJointAngle()) + D(p->GetJointTranslation())));
    }
    std::printf("[joints] gear revolute+prismatic: max |angle + translation| %.5f (rack moved %.3f m)\n", worst,
                D(p->GetJointTranslation()));
    EXPECT_LT(worst, 0.01);
    EXPECT_LT(D(p->GetJointTranslation()), -1.0);  // the rack fell and turned the wheel
}

// Motor: reaches its speed under a load below maxMotorTorque; stalls (and pushes with exactly
// maxMotorTorque) above it.
TEST(JointAnalytic, MotorSpeedAndStall) {
    for (const int load : {5, 20}) {
        b2World world(b2Vec2(0, 0));
        b2Body* ground = Ground(world);
        b2Body* wheel = Ball(world, 0, 0, 1, 1);
        b2RevoluteJointDef rd;
        rd.Initialize(ground, wheel, wheel->GetPosition());
        rd.enableMotor = true;
        rd.motorSpeed = 2;
        rd.maxMotorTorque = 10;
        auto* j = static_cast<b2RevoluteJoint*>(world.CreateJoint(&rd));
        for (int i = 0; i < 300; ++i) {
            wheel->ApplyTorque(Fixed(-load));
            Step(world);
        }
        const double speed = D(j->GetJointSpeed());
        const double torque = D(j->GetMotorTorque(Fixed(1) / kDt));
        std::printf("[joints] motor load %d N m (max 10): speed %.4f rad/s, motor torque %.4f N m\n", load, speed,
                    torque);
        if (load < 10) {
            EXPECT_NEAR(speed, 2.0, 0.01);
            EXPECT_NEAR(torque, load, 0.05 * load);
        } else {
            EXPECT_LT(speed, 0.0);  // overpowered: turning backwards
            EXPECT_NEAR(torque, 10.0, 0.05);
        }
    }
}

// Prismatic motor lifts a 1 kg box at 1 m/s against gravity (10 N < 50 N max).
TEST(JointAnalytic, PrismaticMotorLifts) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* box = Box(world, 0, 0, Fixed(0.5), 1);
    b2PrismaticJointDef pd;
    pd.Initialize(ground, box, box->GetPosition(), b2Vec2(0, 1));
    pd.enableMotor = true;
    pd.motorSpeed = 1;
    pd.maxMotorForce = 50;
    auto* j = static_cast<b2PrismaticJoint*>(world.CreateJoint(&pd));
    Step(world, 120);
    std::printf("[joints] prismatic motor: speed %.4f m/s, force %.4f N (m g = 10)\n", D(j->GetJointSpeed()),
                D(j->GetMotorForce(Fixed(1) / kDt)));
    EXPECT_NEAR(D(j->GetJointSpeed()), 1.0, 0.01);
    EXPECT_NEAR(D(j->GetMotorForce(Fixed(1) / kDt)), 10.0, 0.1);
}

// Limits hold under load: a heavy horizontal arm on a revolute limited to [-0.25, 0.25] rad,
// and a box on a vertical prismatic limited to [-1, 1] m. Bound: angularSlop-scale (0.05 rad)
// and linearSlop-scale (0.01 m).
TEST(JointAnalytic, LimitsHoldUnderLoad) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* arm = Box(world, 2, 10, Fixed(0.5), 50);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, arm, b2Vec2(0, 10));
    rd.enableLimit = true;
    rd.lowerAngle = Fixed(-0.25);
    rd.upperAngle = Fixed(0.25);
    auto* r = static_cast<b2RevoluteJoint*>(world.CreateJoint(&rd));
    b2Body* slider = Box(world, 10, 10, Fixed(0.5), 50);
    b2PrismaticJointDef pd;
    pd.Initialize(ground, slider, slider->GetPosition(), b2Vec2(0, 1));
    pd.enableLimit = true;
    pd.lowerTranslation = -1;
    pd.upperTranslation = 1;
    auto* p = static_cast<b2PrismaticJoint*>(world.CreateJoint(&pd));
    double minAngle = 0, minTranslation = 0;
    for (int i = 0; i < 600; ++i) {
        Step(world);
        minAngle = std::min(minAngle, D(r->GetJointAngle()));
        minTranslation = std::min(minTranslation, D(p->GetJointTranslation()));
    }
    std::printf("[joints] limits under load: revolute min angle %.5f (limit -0.25), prismatic min %.5f (limit -1)\n",
                minAngle, minTranslation);
    EXPECT_GT(minAngle, -0.25 - 0.05);
    EXPECT_GT(minTranslation, -1.0 - 0.01);
    EXPECT_NEAR(D(r->GetJointAngle()), -0.25, 0.05);
    EXPECT_NEAR(D(p->GetJointTranslation()), -1.0, 0.01);
}

// A rope never exceeds its max length (by more than linearSlop) while a body falls onto it.
TEST(JointAnalytic, RopeNeverExceedsMaxLength) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* body = Box(world, 0, 10, Fixed(0.25), 10);
    b2RopeJointDef rd;
    rd.bodyA = ground;
    rd.bodyB = body;
    rd.localAnchorA.Set(1, 10);
    rd.localAnchorB.Set(0, 0);
    rd.maxLength = 2;
    auto* j = static_cast<b2RopeJoint*>(world.CreateJoint(&rd));
    double worst = -10;
    for (int i = 0; i < 600; ++i) {
        Step(world);
        worst = std::max(worst, Dist(j->GetAnchorA(), j->GetAnchorB()) - 2.0);
    }
    std::printf("[joints] rope: max length - maxLength %.5f m\n", worst);
    EXPECT_LT(worst, 0.005);   // linearSlop
    EXPECT_GT(worst, -0.005);  // the rope did go taut
}

// Top-down friction: a 1 kg box sliding at v0 = 4 m/s against maxForce 2 N stops after
// v0^2 / (2 F / m) = 4 m, within 5 %.
TEST(JointAnalytic, FrictionStoppingDistance) {
    b2World world(b2Vec2(0, 0));
    b2Body* ground = Ground(world);
    b2Body* box = Box(world, 0, 0, Fixed(0.5), 1);
    b2FrictionJointDef fd;
    fd.Initialize(ground, box, box->GetWorldCenter());
    fd.maxForce = 2;
    fd.maxTorque = 1;
    world.CreateJoint(&fd);
    box->SetLinearVelocity(b2Vec2(4, 0));
    for (int i = 0; i < 300; ++i) Step(world);
    const double d = D(box->GetPosition().x);
    std::printf("[joints] friction stop: %.4f m vs predicted 4 m (%.3f %%), speed %.5f\n", d, 100 * (d / 4 - 1),
                D(box->GetLinearVelocity().x));
    EXPECT_NEAR(d / 4.0, 1.0, 0.05);
    EXPECT_EQ(box->GetLinearVelocity().x, Fixed());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::jt
