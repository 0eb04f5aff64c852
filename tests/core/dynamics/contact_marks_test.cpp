// A contact keeps two marks derived from its fixtures and bodies: whether either fixture is a
// sensor, and whether either body is a bullet or not dynamic (the time-of-impact search's body
// filter). The island search and the time-of-impact filters read them through the contact
// graph's edges instead of visiting both fixtures and the other body. Edits to what they are
// derived from must carry over to the contacts that exist: a world edited between steps must
// step exactly as a copy restored from its snapshot just after the edit, since a restore
// derives every mark afresh. Debug and checked builds also assert the marks as the step reads
// them.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using test::kDt;

struct Scene {
    std::vector<b2Body*> boxes;  // the pyramid, bottom row first
    std::vector<b2Body*> balls;  // the circles resting on top of it
};

/// A pyramid of boxes with circles on top: the bottom row is pressed into the ground, so the
/// time-of-impact stage examines pressed pairs, and every body has contacts to edit.
Scene BuildScene(b2World& world) {
    Scene scene;
    test::MakeStaticBox(world, 0, Fixed(-0.5), 40, Fixed(0.5));
    constexpr int kRows = 7;
    for (int row = 0; row < kRows; ++row) {
        for (int k = 0; k < kRows - row; ++k) {
            scene.boxes.push_back(test::MakeDynamicBox(world, Fixed(k - kRows / 2) + Fixed::FromRatio(row, 2),
                                                       Fixed::FromRatio(50 + 100 * row, 100), Fixed(0.5), Fixed(0.5),
                                                       Fixed(4)));
        }
    }
    for (int k = 0; k < 3; ++k)
        scene.balls.push_back(test::MakeDynamicCircle(world, Fixed::FromRatio(k - 1, 3), Fixed(kRows + 1), Fixed(0.3)));
    return scene;
}

int32 ContactCount(b2Body& body) {
    int32 count = 0;
    for (b2ContactEdge* ce = body.GetContactList(); ce; ce = ce->next) ++count;
    return count;
}

/// Steps `world` and a copy restored from its snapshot now, `steps` times, and expects the same
/// hash after every step.
void ExpectStepsAsRestored(b2World& world, int steps, const char* what) {
    b2World restored(b2Vec2(0, -10));
    ASSERT_TRUE(restored.Restore(world.Save()).ok()) << what;
    ASSERT_EQ(restored.Hash(), world.Hash()) << what;
    for (int i = 0; i < steps; ++i) {
        world.Step(kDt, 8, 3);
        restored.Step(kDt, 8, 3);
        ASSERT_EQ(world.Hash(), restored.Hash()) << what << ", step " << i + 1 << " after the edit";
    }
}

TEST(ContactMarks, EditsBetweenStepsStepAsARestoredCopy) {
    b2World world(b2Vec2(0, -10));
    Scene scene = BuildScene(world);
    for (int i = 0; i < 60; ++i) world.Step(kDt, 8, 3);

    // Every edited body touches others, so the edits reach existing contacts.
    b2Body* bullet = scene.boxes[3];
    b2Body* sensor = scene.boxes[9];
    b2Body* anchored = scene.boxes[15];
    b2Body* kinematic = scene.balls[1];
    for (b2Body* b : {bullet, sensor, anchored, kinematic}) ASSERT_GT(ContactCount(*b), 0);

    bullet->SetBullet(true);
    ExpectStepsAsRestored(world, 30, "a bullet");
    sensor->GetFixtureList()->SetSensor(true);
    ExpectStepsAsRestored(world, 30, "a sensor");
    anchored->SetType(b2_staticBody);
    ExpectStepsAsRestored(world, 30, "a dynamic body made static");
    kinematic->SetType(b2_kinematicBody);
    kinematic->SetLinearVelocity(b2Vec2(Fixed(0.5), 0));
    ExpectStepsAsRestored(world, 30, "a dynamic body made kinematic");

    // And back.
    bullet->SetBullet(false);
    ExpectStepsAsRestored(world, 30, "no longer a bullet");
    sensor->GetFixtureList()->SetSensor(false);
    ExpectStepsAsRestored(world, 30, "no longer a sensor");
    anchored->SetType(b2_dynamicBody);
    kinematic->SetType(b2_dynamicBody);
    ExpectStepsAsRestored(world, 60, "dynamic again");
}

/// The pressed circle of the time-of-impact reproduction (docs/dynamics.md): a heavy box lands
/// on a circle and presses it into the body below, closer than the query's target, which 2.2.1
/// answers with an immediate event. Here the body below starts dynamic, on a static floor, and
/// the edit makes it static, kinematic or a bullet while its contact with the circle exists: the
/// pressed pair passes the body filter only through the edit.
void ExpectPressedPairFollows(void (*edit)(b2Body&), const char* what) {
    b2World world(b2Vec2(0, -10));
    test::MakeStaticBox(world, 0, Fixed(-1), 10, Fixed(0.5));
    b2Body* platform = test::MakeDynamicBox(world, 0, 0, 10, Fixed(0.5));
    test::MakeDynamicCircle(world, 0, Fixed(1.25), Fixed(0.75));
    test::MakeDynamicBox(world, 0, 4, Fixed(0.5), Fixed(0.5), Fixed(10));
    for (int i = 0; i < 5; ++i) world.Step(kDt, 8, 3);
    ASSERT_EQ(ContactCount(*platform), 2);  // the floor and the circle
    edit(*platform);
    ExpectStepsAsRestored(world, 90, what);
}

TEST(ContactMarks, PressedPairFollowsItsBodies) {
    ExpectPressedPairFollows([](b2Body& b) { b.SetType(b2_staticBody); }, "made static");
    ExpectPressedPairFollows([](b2Body& b) { b.SetType(b2_kinematicBody); }, "made kinematic");
    ExpectPressedPairFollows([](b2Body& b) { b.SetBullet(true); }, "made a bullet");
}

TEST(ContactMarks, RestoringAFrameUndoesTheEdits) {
    b2World world(b2Vec2(0, -10));
    b2World twin(b2Vec2(0, -10));
    Scene scene = BuildScene(world);
    BuildScene(twin);
    for (int i = 0; i < 60; ++i) {
        world.Step(kDt, 8, 3);
        twin.Step(kDt, 8, 3);
    }

    b2WorldFrame frame;
    world.SaveFrame(frame);
    scene.boxes[3]->SetBullet(true);
    scene.boxes[9]->GetFixtureList()->SetSensor(true);
    scene.boxes[15]->SetType(b2_staticBody);
    for (int i = 0; i < 10; ++i) world.Step(kDt, 8, 3);
    ASSERT_TRUE(world.RestoreFrame(frame).ok());

    ASSERT_EQ(world.Hash(), twin.Hash());
    for (int i = 0; i < 60; ++i) {
        world.Step(kDt, 8, 3);
        twin.Step(kDt, 8, 3);
        ASSERT_EQ(world.Hash(), twin.Hash()) << "step " << i + 1 << " after the frame";
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
