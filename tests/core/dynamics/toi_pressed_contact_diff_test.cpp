// A body pressed deep into a resting contact gets 2.2.1's immediate time-of-impact event: a
// circle on a static ground with a heavy box dropped on it. Float Box2D (2.4.1 here, which
// agrees with 2.2.1 to 1e-5 on this case) raises a TOI event at the start of the sweep once the
// box pushes the circle more than about 3 linearSlop into the ground, and the sub-step lifts
// the circle back: a jump of several millimetres that a "skip slow bodies" shortcut misses.
// Which step crosses that line depends on a tenth of a millimetre of sinking, and that depends
// on how deep each earlier sub-step left the circle (the bound of the sub-step's position
// solve, docs/dynamics.md), so the whole trajectory is compared.
#include <vector>

#include <gtest/gtest.h>

#include "Box2DFloat.h"  // float Box2D without its constant macros
#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

constexpr int kSteps = 45;

std::vector<double> CircleHeightsFloat() {
    b2World world(b2Vec2(0.0f, -10.0f));
    b2BodyDef gd;
    b2Body* ground = world.CreateBody(&gd);
    b2PolygonShape groundBox;
    groundBox.SetAsBox(10.0f, 0.5f);
    ground->CreateFixture(&groundBox, 0.0f);

    b2BodyDef cd;
    cd.type = b2_dynamicBody;
    cd.position.Set(0.0f, 1.25f);
    b2Body* circle = world.CreateBody(&cd);
    b2CircleShape shape;
    shape.m_radius = 0.75f;
    circle->CreateFixture(&shape, 1.0f);

    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(0.0f, 4.0f);
    b2Body* box = world.CreateBody(&bd);
    b2PolygonShape boxShape;
    boxShape.SetAsBox(0.5f, 0.5f);
    box->CreateFixture(&boxShape, 10.0f);

    std::vector<double> y;
    for (int n = 0; n < kSteps; ++n) {
        world.Step(static_cast<float>(lockbox::test::kDtDouble), 8, 3);
        y.push_back(circle->GetPosition().y);
    }
    return y;
}

}  // namespace LOCKBOX_TEST_FILE

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

// The pressed-circle scene, stepped kSteps times; `toiSteps` counts the steps with a TOI call.
struct LockboxRun {
    std::vector<double> y;
    int toiSteps = 0;
    uint64 hash = 0;
};

LockboxRun RunLockbox(bool pressedContactToi) {
    b2World world(b2Vec2(0, -10));
    world.SetPressedContactToi(pressedContactToi);
    b2BodyDef gd;
    b2Body* ground = world.CreateBody(&gd);
    b2PolygonShape groundBox;
    groundBox.SetAsBox(10, Fixed(1) / 2);
    ground->CreateFixture(&groundBox, 0);

    b2BodyDef cd;
    cd.type = b2_dynamicBody;
    cd.position.Set(0, Fixed(5) / 4);
    b2Body* circle = world.CreateBody(&cd);
    b2CircleShape shape;
    shape.m_radius = Fixed(3) / 4;
    circle->CreateFixture(&shape, 1);

    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(0, 4);
    b2Body* box = world.CreateBody(&bd);
    b2PolygonShape boxShape;
    boxShape.SetAsBox(Fixed(1) / 2, Fixed(1) / 2);
    box->CreateFixture(&boxShape, 10);

    LockboxRun run;
    for (int n = 0; n < kSteps; ++n) {
        world.Step(kDt, 8, 3);
        run.y.push_back(circle->GetPosition().y.ToDouble());
        if (world.GetProfile().toiCalls > 0) ++run.toiSteps;
    }
    run.hash = world.Hash();
    return run;
}

std::vector<double> CircleHeightsLockbox() { return RunLockbox(true).y; }

// The lift: the first step after the box lands (step 34) at which the circle rises by more
// than 5 mm, the immediate event's sub-step pushing it out of the ground (-1: none).
int LiftStep(const std::vector<double>& y) {
    for (size_t i = 34; i < y.size(); ++i)
        if (y[i] - y[i - 1] > 0.005) return static_cast<int>(i) + 1;
    return -1;
}

TEST(DifferentialToi, PressedCircleGetsTheImmediateEvent) {
    const std::vector<double> ref = CircleHeightsFloat();
    const std::vector<double> got = CircleHeightsLockbox();
    // The same step lifts the circle, and every step (the box's landing at step 34, the sink
    // at 38, the lift at 40 and the settling after it) puts it where float does.
    const int floatLift = LiftStep(ref);
    ASSERT_GT(floatLift, 0);
    EXPECT_EQ(LiftStep(got), floatLift);
    for (int n = 1; n <= kSteps; ++n) {
        const auto i = static_cast<size_t>(n - 1);
        EXPECT_NEAR(got[i], ref[i], 0.0005) << "step " << n;
    }
}

// Switched off, the pressed circle gets no event: it stays pressed (no lift), fewer steps
// query a time of impact, and the world's state says so (the switch is hashed).
TEST(PressedContactToi, SwitchedOffTheCircleStaysPressed) {
    const LockboxRun on = RunLockbox(true);
    const LockboxRun off = RunLockbox(false);
    EXPECT_GT(LiftStep(on.y), 0);
    EXPECT_EQ(LiftStep(off.y), -1);
    EXPECT_LT(off.toiSteps, on.toiSteps);
    EXPECT_NE(off.hash, on.hash);
}

TEST(PressedContactToi, IsWorldStateInSnapshotsAndFrames) {
    b2World world(b2Vec2(0, -10));
    EXPECT_TRUE(world.GetPressedContactToi());  // 2.2.1's behaviour by default
    const uint64 hashOn = world.Hash();
    world.SetPressedContactToi(false);
    EXPECT_FALSE(world.GetPressedContactToi());
    EXPECT_NE(world.Hash(), hashOn);

    // A snapshot carries the switch.
    const std::vector<uint8> image = world.Save();
    b2World restored(b2Vec2(0, -10));
    ASSERT_TRUE(restored.Restore(image).ok());
    EXPECT_FALSE(restored.GetPressedContactToi());
    EXPECT_EQ(restored.Hash(), world.Hash());

    // So does a rollback frame.
    b2WorldFrame frame;
    world.SaveFrame(frame);
    world.SetPressedContactToi(true);
    ASSERT_TRUE(world.RestoreFrame(frame).ok());
    EXPECT_FALSE(world.GetPressedContactToi());

    world.SetPressedContactToi(true);
    EXPECT_EQ(world.Hash(), hashOn);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
