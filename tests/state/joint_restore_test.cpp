// Joint restore (SnapshotApply.cpp, JointState.h): a joint of the image's id and type that
// the world still has is refilled where it is; any other is made afresh, and gear joints
// point at the final objects either way.

#include <vector>

#include <gtest/gtest.h>

#include "StateTestUtil.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::DescribeDifference;
using testing_state::EdgesFollowWorldLists;
using testing_state::SceneRun;

/// Every gear joint of the world is geared to joints the world holds under their ids.
::testing::AssertionResult GearsPointIntoWorld(b2World& world) {
    for (b2Joint* j = world.GetJointList(); j; j = j->GetNext()) {
        if (j->GetType() != e_gearJoint) continue;
        auto* gear = static_cast<b2GearJoint*>(j);
        for (b2Joint* geared : {gear->GetJoint1(), gear->GetJoint2()}) {
            if (geared == nullptr || world.GetJoint(geared->GetId()) != geared) {
                return ::testing::AssertionFailure() << "gear " << j->GetId() << " points outside the world";
            }
        }
    }
    return ::testing::AssertionSuccess();
}

std::vector<const b2Joint*> JointList(b2World& world) {
    std::vector<const b2Joint*> joints;
    for (const b2Joint* j = world.GetJointList(); j; j = j->GetNext()) joints.push_back(j);
    return joints;
}

TEST(JointRestore, InPlaceKeepsEveryJointObject) {
    for (const char* name : {"ragdolls", "pulley_gear"}) {
        SceneRun run(name);
        ASSERT_TRUE(run.scene) << name;
        run.Advance(20);
        const std::vector<uint8> image = run.world().Save();
        const uint64 savedHash = run.world().Hash();
        const std::vector<const b2Joint*> joints = JointList(run.world());
        ASSERT_FALSE(joints.empty()) << name;
        run.Advance(25);
        const b2RestoreResult result = run.world().Restore(image);
        ASSERT_TRUE(result.ok()) << name << ": " << result.message;
        EXPECT_EQ(run.world().Hash(), savedHash) << name;
        EXPECT_EQ(JointList(run.world()), joints) << name << ": a joint moved in memory";
        EXPECT_TRUE(GearsPointIntoWorld(run.world())) << name;
        EXPECT_TRUE(EdgesFollowWorldLists(run.world())) << name;
        EXPECT_EQ(run.world().Save(), image) << name;
    }
}

b2Body* Ball(b2World& world, int x) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(Fixed(x), Fixed(5));
    b2Body* body = world.CreateBody(&bd);
    b2CircleShape c;
    c.m_radius = Fixed(1);
    body->CreateFixture(&c, Fixed(1));
    return body;
}

void Step(b2World& world, int n) {
    for (int i = 0; i < n; ++i) world.Step(Fixed::FromRaw(1092), 8, 3);
}

// Joints 0 and 2 of the image (a revolute and the gear on it) have other types in the world
// at restore time: both are made afresh, and the gear must reach the new revolute.
TEST(JointRestore, ChangedTypesAreMadeAfreshAndGearsFollow) {
    b2World world(b2Vec2(Fixed(0), Fixed(-10)));
    b2BodyDef groundDef;
    b2Body* ground = world.CreateBody(&groundDef);
    b2Body* a = Ball(world, 0);
    b2Body* b = Ball(world, 3);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, a, a->GetPosition());
    b2Joint* revolute = world.CreateJoint(&rd);
    b2PrismaticJointDef pd;
    pd.Initialize(ground, b, b->GetPosition(), b2Vec2(Fixed(0), Fixed(1)));
    b2Joint* prismatic = world.CreateJoint(&pd);
    b2GearJointDef gd;
    gd.joint1 = revolute;
    gd.joint2 = prismatic;
    gd.ratio = Fixed(2);
    ASSERT_NE(world.CreateJoint(&gd), nullptr);
    a->ApplyAngularImpulse(Fixed(3));
    Step(world, 30);
    const std::vector<uint8> image = world.Save();
    const uint64 savedHash = world.Hash();

    // The continuation from the image in a fresh world is the reference.
    b2World reference(b2Vec2(Fixed(0), Fixed(-10)));
    ASSERT_TRUE(reference.Restore(image).ok());
    Step(reference, 30);

    // Ids 0 and 2 freed (the gear dies with its revolute), then reused by other types.
    world.DestroyJoint(revolute);
    b2DistanceJointDef dd;
    dd.Initialize(a, b, a->GetPosition(), b->GetPosition());
    ASSERT_EQ(world.CreateJoint(&dd)->GetId(), 0);
    b2WeldJointDef wd;
    wd.Initialize(ground, b, b->GetPosition());
    ASSERT_EQ(world.CreateJoint(&wd)->GetId(), 2);
    Step(world, 5);

    const b2RestoreResult result = world.Restore(image);
    ASSERT_TRUE(result.ok()) << result.message;
    EXPECT_EQ(world.Hash(), savedHash);
    EXPECT_EQ(world.Save(), image);
    ASSERT_EQ(world.GetJointCount(), 3);
    EXPECT_EQ(world.GetJoint(0)->GetType(), e_revoluteJoint);
    EXPECT_EQ(world.GetJoint(1), prismatic);  // same id and type: kept where it was
    ASSERT_EQ(world.GetJoint(2)->GetType(), e_gearJoint);
    auto* gear = static_cast<b2GearJoint*>(world.GetJoint(2));
    EXPECT_EQ(gear->GetJoint1(), world.GetJoint(0));
    EXPECT_EQ(gear->GetJoint2(), prismatic);
    EXPECT_TRUE(EdgesFollowWorldLists(world));
    Step(world, 30);
    EXPECT_EQ(world.Hash(), reference.Hash()) << DescribeDifference(world, reference);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
