// The bits of every joint path that uses a prepared K (b2WideSolver22/33, built once per step
// in InitVelocityConstraints) or its inverse (b2WideMat22, the revolute, prismatic and weld point
// iterations' product). The golden scenes cover revolute chains, limits and motors; this world
// adds the other paths: prismatic limits (lower, upper, equal) with a motor, revolute equal
// limits, soft and rigid welds, a friction joint and a mouse joint. History of the expected
// hashes: first recorded with the solver that normalised and factored K on every call (the
// prepared solvers reproduced them exactly); since determinism version 0x00020002 the point
// iterations multiply by the point block's inverse, and steps 60 and 300 were recorded anew
// (step 1 did not change); since 0x00030006 a 2x2 K is normalised to 31 significant bits, not
// 36, and all three were recorded anew.
#include <cinttypes>
#include <cstdio>

#include <gtest/gtest.h>

#include "JointTestUtil.h"

namespace lockbox::jt {
namespace LOCKBOX_TEST_FILE {

constexpr Fixed kHalf = Fixed(0.25);

void BuildJointZoo(b2World& world) {
    b2Body* ground = Ground(world);

    // Prismatic sliders: one falling onto its lower limit, one driven by its motor into the
    // upper limit, one with equal limits.
    for (int k = 0; k < 3; ++k) {
        b2Body* slider = Box(world, Fixed(-6 + 2 * k), 10, kHalf, Fixed(1));
        b2PrismaticJointDef pd;
        pd.Initialize(ground, slider, slider->GetPosition(), b2Vec2(Fixed(0.6), Fixed(0.8)));
        pd.enableLimit = true;
        pd.lowerTranslation = k == 2 ? Fixed(0.5) : Fixed(-1);
        pd.upperTranslation = k == 2 ? Fixed(0.5) : Fixed(1.5);
        pd.enableMotor = k == 1;
        pd.motorSpeed = 2;
        pd.maxMotorForce = 40;
        world.CreateJoint(&pd);
    }

    // Revolute pendulums: one swinging into its limits, one held by equal limits.
    for (int k = 0; k < 2; ++k) {
        b2Body* arm = Box(world, Fixed(1 + 3 * k), 10, kHalf, Fixed(2));
        b2RevoluteJointDef rd;
        rd.Initialize(ground, arm, b2Vec2(Fixed(3 * k), 10));
        rd.enableLimit = true;
        rd.lowerAngle = k == 0 ? Fixed(-0.7) : Fixed(0.1);
        rd.upperAngle = k == 0 ? Fixed(0.4) : Fixed(0.1);
        world.CreateJoint(&rd);
    }

    // Welds: a soft one (5 Hz) and a rigid one, each holding a box off a pinned box.
    for (int k = 0; k < 2; ++k) {
        b2Body* a = Box(world, Fixed(8 + 4 * k), 10, kHalf, Fixed(1));
        b2Body* b = Box(world, Fixed(9 + 4 * k), 10, kHalf, Fixed(3));
        b2RevoluteJointDef rd;
        rd.Initialize(ground, a, b2Vec2(Fixed(7 + 4 * k), 10));
        world.CreateJoint(&rd);
        b2WeldJointDef wd;
        wd.Initialize(a, b, b2Vec2(Fixed(8.5) + Fixed(4 * k), 10));
        wd.frequencyHz = k == 0 ? Fixed(5) : Fixed(0);
        wd.dampingRatio = Fixed(0.3);
        world.CreateJoint(&wd);
    }

    // A friction joint (top-down friction) on a box sliding over the ground, pinned off centre
    // so the linear friction solve sees an off-diagonal K.
    b2Body* puck = Box(world, Fixed(-3), 2, kHalf, Fixed(1));
    puck->SetLinearVelocity(b2Vec2(4, 1));
    puck->SetAngularVelocity(Fixed(3));
    b2FrictionJointDef fd;
    fd.Initialize(ground, puck, puck->GetPosition() + b2Vec2(Fixed(0.2), Fixed(0.1)));
    fd.maxForce = Fixed(1);
    fd.maxTorque = Fixed(0.5);
    world.CreateJoint(&fd);

    // A mouse joint dragging a ball towards a target above and to the side.
    b2Body* ball = Ball(world, 0, 4, Fixed(0.3), Fixed(1));
    b2MouseJointDef md;
    md.bodyA = ground;
    md.bodyB = ball;
    md.target = ball->GetPosition();
    md.maxForce = ball->GetMass() * Fixed(500);
    auto* mouse = static_cast<b2MouseJoint*>(world.CreateJoint(&md));
    mouse->SetTarget(b2Vec2(3, 7));
}

TEST(JointSolverBits, JointZooKeepsItsBits) {
    b2World world(b2Vec2(0, -10));
    BuildJointZoo(world);
    struct Check {
        int step;
        uint64_t hash;
    };
    const Check checks[] = {{1, 0x239e74d5fd32bc0full}, {60, 0x0d3ec8bb450a2cfeull}, {300, 0xd655dad5b8b8d671ull}};
    int done = 0;
    for (const Check& c : checks) {
        Step(world, c.step - done);
        done = c.step;
        const uint64_t h = world.Hash();
        std::printf("[joints] solver bits: step %d hash 0x%016" PRIx64 "\n", c.step, h);
        EXPECT_EQ(h, c.hash) << "step " << c.step;
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::jt
