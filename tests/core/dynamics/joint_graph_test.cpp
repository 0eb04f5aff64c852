// The island search reads each body's joints from a copy of the joint lists, rebuilt when they
// change. Every way a joint list changes between steps is made here: a joint made between two
// islands, one destroyed in the middle of a chain, a body destroyed with its joints, a new body
// (in a freed slot) given a joint, a rollback frame that undoes new bodies and their joint, and a
// snapshot restore that brings back a destroyed joint. After each change the world steps on, and
// every step must give the bits of a world restored from the state before it (a fresh world,
// whose copy is built from nothing), and the islands must hold exactly the joints the lists say.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;
using lockbox::test::kDt;
using lockbox::test::MakeDynamicBox;
using lockbox::test::MakeStaticBox;

b2Joint* Pin(b2World& world, b2Body* a, b2Body* b, const b2Vec2& anchor) {
    b2RevoluteJointDef def;
    def.Initialize(a, b, anchor);
    return world.CreateJoint(&def);
}

// A rope of `links` boxes hung from a static anchor at (x, 20), each pinned to the one above.
std::vector<b2Body*> MakeRope(b2World& world, b2Body* anchor, Fixed x, int links) {
    std::vector<b2Body*> rope;
    b2Body* previous = anchor;
    for (int k = 0; k < links; ++k) {
        b2Body* link = MakeDynamicBox(world, x + Fixed(k) + Fixed(0.5), 20, Fixed(0.5), Fixed(0.125));
        Pin(world, previous, link, b2Vec2(x + Fixed(k), 20));
        rope.push_back(link);
        previous = link;
    }
    return rope;
}

// Steps `world` once and checks the step against a world restored from its state before it.
void StepAndCompare(b2World& world, int step) {
    const std::vector<uint8> before = world.Save();
    world.Step(kDt, 8, 3);
    b2World fresh(b2Vec2(0, -10));
    ASSERT_TRUE(fresh.Restore(before).ok()) << "step " << step;
    fresh.Step(kDt, 8, 3);
    ASSERT_EQ(world.Hash(), fresh.Hash()) << "step " << step;
    ASSERT_EQ(world.GetProfile().jointConstraints, fresh.GetProfile().jointConstraints) << "step " << step;
}

// The joints the last step solved, summed over its islands, against the joints between awake
// bodies with mass that the lists hold (every rope here hangs awake).
int32 JointsInLists(b2World& world) {
    int32 count = 0;
    for (b2Joint* j = world.GetJointList(); j != nullptr; j = j->GetNext()) ++count;
    return count;
}

TEST(JointGraph, EveryChangeOfTheJointListsReachesTheIslandSearch) {
    b2World world(b2Vec2(0, -10));
    world.SetAllowSleeping(false);
    MakeStaticBox(world, 0, -1, 50, Fixed(0.5));
    b2Body* anchorA = MakeStaticBox(world, -20, 21, Fixed(0.25), Fixed(0.25));
    b2Body* anchorB = MakeStaticBox(world, 10, 21, Fixed(0.25), Fixed(0.25));
    std::vector<b2Body*> ropeA = MakeRope(world, anchorA, -20, 8);
    std::vector<b2Body*> ropeB = MakeRope(world, anchorB, 10, 6);

    int step = 0;
    const auto run = [&](int steps) {
        for (int i = 0; i < steps; ++i) {
            StepAndCompare(world, step++);
            if (HasFatalFailure()) return;
            ASSERT_EQ(world.GetProfile().jointConstraints, JointsInLists(world)) << "step " << step;
        }
    };
    run(10);

    // Two islands joined by a new joint.
    Pin(world, ropeA.back(), ropeB.back(), ropeA.back()->GetWorldCenter());
    run(10);

    // The first rope cut in the middle.
    b2Joint* middle = nullptr;
    for (b2JointEdge* je = ropeA[4]->GetJointList(); je != nullptr; je = je->next)
        if (je->other == ropeA[3]) middle = je->joint;
    ASSERT_NE(middle, nullptr);
    world.DestroyJoint(middle);
    run(10);

    // A link destroyed with its two joints, then a new body in its slot, pinned to the rope.
    const int32 freed = ropeB[2]->GetId();
    world.DestroyBody(ropeB[2]);
    run(5);
    b2Body* patch = MakeDynamicBox(world, 12, 20, Fixed(0.5), Fixed(0.125));
    EXPECT_EQ(patch->GetId(), freed) << "the new body should take the freed slot";
    Pin(world, ropeB[1], patch, ropeB[1]->GetWorldCenter());
    Pin(world, patch, ropeB[3], ropeB[3]->GetWorldCenter());
    run(5);

    // A frame, then two new bodies pinned together, then the frame back: the frame undoes
    // the creations (both bodies and their joint go).
    b2WorldFrame frame;
    world.SaveFrame(frame);
    const uint64_t atFrame = world.Hash();
    b2Body* left = MakeDynamicBox(world, -10, 15, Fixed(0.5), Fixed(0.5));
    b2Body* right = MakeDynamicBox(world, -9, 15, Fixed(0.5), Fixed(0.5));
    Pin(world, left, right, b2Vec2(Fixed(-9.5), 15));
    run(3);
    ASSERT_TRUE(world.RestoreFrame(frame).ok());
    ASSERT_EQ(world.Hash(), atFrame);
    run(2);
    // A body without joints in a slot the undone ones left.
    const b2Body* loose = MakeDynamicBox(world, -10, 10, Fixed(0.5), Fixed(0.5));
    EXPECT_EQ(loose->GetJointList(), nullptr);
    run(5);

    // A snapshot restored in place rebuilds every joint list: here it brings back a joint
    // destroyed since it was saved.
    const std::vector<uint8> image = world.Save();
    world.DestroyJoint(ropeA[1]->GetJointList()->joint);
    run(3);
    ASSERT_TRUE(world.Restore(image).ok());
    run(10);
}

}  // namespace LOCKBOX_TEST_FILE
