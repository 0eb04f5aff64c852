// Rollback frames (b2World::SaveFrame / RestoreFrame): every structural call moves the epoch
// (and motion does not), a restore gives back the saved state and its future across structural
// changes, pool shrinking and full restores in between, and bad frames are refused with the
// world untouched.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "FrameTestUtil.h"
#include "lockbox_internal/WorldInternals.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::AddBox;
using testing_state::FirstDynamic;
using testing_state::Future;
using testing_state::SavedFrame;
using testing_state::SceneRun;

static_assert(sizeof(frame_detail::BodyMotion) == 88, "a body's motion in a frame is 88 bytes");

TEST(WorldFrame, EveryStructuralCallMovesTheEpoch) {
    SceneRun run{"ragdolls"};
    run.Advance(5);
    b2World& w = run.world();
    b2Body* body = FirstDynamic(w);
    ASSERT_NE(body, nullptr);
    b2Fixture* fixture = body->GetFixtureList();
    const std::vector<std::pair<const char*, std::function<void()>>> structural = {
        {"CreateBody", [&] { AddBox(w, b2Vec2(3, 30)); }},
        {"CreateFixture",
         [&] {
             b2CircleShape c;
             c.m_radius = Fixed(1) / 8;
             body->CreateFixture(&c, 1);
         }},
        {"DestroyFixture", [&] { body->DestroyFixture(body->GetFixtureList()); }},
        {"ResetMassData", [&] { body->ResetMassData(); }},
        {"SetMassData",
         [&] {
             b2MassData md;
             body->GetMassData(&md);
             body->SetMassData(&md);
         }},
        {"SetLinearDamping", [&] { body->SetLinearDamping(Fixed(1) / 10); }},
        {"SetAngularDamping", [&] { body->SetAngularDamping(Fixed(1) / 10); }},
        {"SetGravityScale", [&] { body->SetGravityScale(Fixed(1) / 2); }},
        {"Body::SetUserData", [&] { body->SetUserData(7); }},
        {"SetFixedRotation", [&] { body->SetFixedRotation(true); }},
        {"SetType", [&] { body->SetType(b2_kinematicBody); }},
        {"SetActive", [&] { body->SetActive(false); }},
        {"SetSensor", [&] { fixture->SetSensor(true); }},
        {"SetFilterData", [&] { fixture->SetFilterData(b2Filter{}); }},
        {"Fixture::SetUserData", [&] { fixture->SetUserData(9); }},
        {"SetDensity", [&] { fixture->SetDensity(2); }},
        {"SetFriction", [&] { fixture->SetFriction(Fixed(1) / 2); }},
        {"SetRestitution", [&] { fixture->SetRestitution(Fixed(1) / 2); }},
        {"EditShape", [&] { (void)fixture->EditShape(); }},
        {"CreateJoint",
         [&] {
             b2DistanceJointDef jd;
             b2Body* other = AddBox(w, b2Vec2(-3, 30));
             jd.Initialize(other, FirstDynamic(w), other->GetPosition(), FirstDynamic(w)->GetPosition());
             w.CreateJoint(&jd);
         }},
        {"DestroyJoint", [&] { w.DestroyJoint(w.GetJointList()); }},
        {"DestroyBody", [&] { w.DestroyBody(w.GetBodyList()); }},
        {"Restore", [&] { ASSERT_TRUE(w.Restore(w.Save()).ok()); }},
        {"MarkStructureChanged", [&] { test::MarkStructureChanged(w); }},
    };
    std::vector<uint64> seen{test::StructureEpoch(w)};
    for (const auto& [name, call] : structural) {
        const uint64 before = test::StructureEpoch(w);
        call();
        EXPECT_NE(test::StructureEpoch(w), before) << name;
        // Never a value the world gave before: frames of an old epoch stay told apart.
        for (uint64 old : seen) EXPECT_NE(test::StructureEpoch(w), old) << name;
        seen.push_back(test::StructureEpoch(w));
    }
}

TEST(WorldFrame, MotionAndStepsKeepTheEpoch) {
    SceneRun run{"ragdolls"};
    run.Advance(5);
    b2World& w = run.world();
    b2Body* body = FirstDynamic(w);
    const uint64 epoch = test::StructureEpoch(w);
    body->SetLinearVelocity(b2Vec2(1, 2));
    body->SetAngularVelocity(3);
    body->ApplyForceToCenter(b2Vec2(5, 0));
    body->ApplyLinearImpulse(b2Vec2(0, 1), body->GetWorldCenter());
    body->SetTransform(b2Vec2(1, 10), Fixed(1) / 2);
    body->SetAwake(true);
    body->SetBullet(true);
    body->SetSleepingAllowed(true);
    w.SetGravity(b2Vec2(0, -5));
    // Reading a shape, even through a non-const fixture, is not an edit.
    const b2Shape* shape = body->GetFixtureList()->GetShape();
    EXPECT_NE(shape, nullptr);
    run.Advance(30);
    EXPECT_EQ(test::StructureEpoch(w), epoch) << "a step or a motion input marked the structure changed";
}

TEST(WorldFrame, RestoreGivesTheSavedStateAndItsFuture) {
    for (const char* name : {"pyramid20", "ragdolls", "car", "pulley_gear", "rain"}) {
        SceneRun run{name};
        run.Advance(40);
        const uint32 bodies = static_cast<uint32>(run.world().GetBodyCount());
        const SavedFrame saved(run, 20);
        ASSERT_TRUE(run.world().RestoreFrame(saved.frame).ok()) << name;
        saved.ExpectBack(run, name);
        const b2FrameStats stats = saved.frame.Stats();
        EXPECT_EQ(stats.bodyBytes, 88u * bodies) << name;
        EXPECT_GT(stats.structureBytes, 0u) << name;
    }
}

TEST(WorldFrame, RestoreUndoesStructuralChanges) {
    SceneRun run{"ragdolls"};
    run.Advance(20);
    b2World& w = run.world();
    const SavedFrame saved(run, 15);
    // A branch that changes every kind of structure, with steps in between.
    for (int i = 0; i < 6; ++i) AddBox(w, b2Vec2(i, 20));
    run.Advance(3);
    b2Body* body = FirstDynamic(w);
    body->GetFixtureList()->SetDensity(5);
    body->ResetMassData();
    w.GetBodyList()->GetFixtureList()->EditShape()->m_radius = Fixed(1) / 8;
    body->GetFixtureList()->SetFilterData(b2Filter{0x0002, 0xFFFD, 0});
    w.GetBodyList()->GetNext()->SetActive(false);
    b2DistanceJointDef jd;
    jd.Initialize(w.GetBodyList(), body, w.GetBodyList()->GetPosition(), body->GetPosition());
    w.CreateJoint(&jd);
    run.Advance(3);
    w.DestroyBody(body);
    w.DestroyJoint(w.GetJointList());
    run.Advance(3);
    ASSERT_TRUE(w.RestoreFrame(saved.frame).ok());
    EXPECT_TRUE(testing_state::EdgesFollowWorldLists(w));
    saved.ExpectBack(run);
}

TEST(WorldFrame, RestoreUndoesAShapeEdit) {
    // Shapes are structure, which frames share rather than copy: an edit through EditShape
    // after a save must bring the saved shape back, on an older body (the structure image)
    // and on a body created since the frame (undone with its creation).
    for (const bool newBody : {false, true}) {
        SceneRun run{"pyramid20"};
        run.Advance(30);
        b2World& w = run.world();
        const SavedFrame saved(run, 10);
        b2Body* body = newBody ? AddBox(w, b2Vec2(0, 30)) : FirstDynamic(w);
        ASSERT_NE(body, nullptr);
        auto* box = static_cast<b2PolygonShape*>(body->GetFixtureList()->EditShape());
        box->SetAsBox(Fixed(1) / 2, Fixed(1) / 8);
        body->ResetMassData();
        run.Advance(5);
        EXPECT_NE(w.Hash(), saved.hash);
        ASSERT_TRUE(w.RestoreFrame(saved.frame).ok());
        EXPECT_EQ(w.Hash(), saved.hash) << (newBody ? "new body" : "older body");
        saved.ExpectBack(run, newBody ? "new body" : "older body");
    }
}

TEST(WorldFrame, FramesOfOtherEpochsAndShrunkPoolsRestore) {
    // Frame A early (few contacts, a small contact pool), frame B later (many). Restoring A
    // shrinks the pools; B then regrows them at new addresses, and a full Restore in between
    // moves the epoch: each frame still gives back its state and future.
    SceneRun run{"pyramid20"};
    b2World& w = run.world();
    b2WorldFrame a, b;
    w.SaveFrame(a);
    const uint64 hashA = w.Hash();
    run.Advance(60);
    w.SaveFrame(b);
    const uint64 hashB = w.Hash();
    const int stepB = run.step;
    const std::vector<uint64> futureB = Future(run, 10);
    const std::vector<uint8> image = w.Save();
    ASSERT_TRUE(w.RestoreFrame(a).ok());
    EXPECT_EQ(w.Hash(), hashA);
    ASSERT_TRUE(w.RestoreFrame(b).ok());
    EXPECT_EQ(w.Hash(), hashB);
    ASSERT_TRUE(w.Restore(image).ok());
    ASSERT_TRUE(w.RestoreFrame(a).ok());
    EXPECT_EQ(w.Hash(), hashA);
    ASSERT_TRUE(w.RestoreFrame(b).ok());
    run.step = stepB;
    EXPECT_EQ(Future(run, 10), futureB);
}

TEST(WorldFrame, EmptyAndForeignFramesAreRefused) {
    SceneRun run{"ragdolls"};
    SceneRun other{"ragdolls"};
    run.Advance(10);
    other.Advance(10);
    const uint64 before = run.world().Hash();
    b2WorldFrame empty;
    EXPECT_TRUE(empty.IsEmpty());
    b2RestoreResult r = run.world().RestoreFrame(empty);
    EXPECT_EQ(r.error, b2SnapshotError::e_foreignFrame);
    EXPECT_NE(r.message.find("empty"), std::string::npos) << r.message;
    b2WorldFrame foreign;
    other.world().SaveFrame(foreign);
    r = run.world().RestoreFrame(foreign);
    EXPECT_EQ(r.error, b2SnapshotError::e_foreignFrame);
    EXPECT_NE(r.message.find("another world"), std::string::npos) << r.message;
    EXPECT_STREQ(b2SnapshotErrorName(r.error), "foreign frame");
    EXPECT_EQ(run.world().Hash(), before);
}

struct RestoreFrameInsideStep : b2ContactListener {
    b2World* world = nullptr;
    b2WorldFrame frame;
    b2SnapshotError seen = b2SnapshotError::e_ok;
    void BeginContact(b2Contact*) override { seen = world->RestoreFrame(frame).error; }
};

TEST(WorldFrame, RestoreInsideStepIsRefused) {
    const b2AssertHandler previous = b2SetAssertHandler([](const char*, const char*, const char*, int) {});
    SceneRun run{"hello"};
    RestoreFrameInsideStep listener;
    listener.world = &run.world();
    run.world().SaveFrame(listener.frame);
    run.world().SetContactListener(&listener);
    for (int i = 0; i < 120 && listener.seen == b2SnapshotError::e_ok; ++i) run.Advance();
    EXPECT_EQ(listener.seen, b2SnapshotError::e_locked);
    b2SetAssertHandler(previous);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
