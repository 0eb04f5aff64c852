// Rollback frames across spawns (b2World::RestoreFrame, lockbox/state/WorldFrame.h): when every
// structural change since a frame concerned only bodies and joints created since, the restore
// destroys them instead of restoring the frame's structure image; any other change takes the
// image. Either way the state, its future and the ids handed out next are the saved ones.

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
using testing_state::SavedFrame;
using testing_state::SceneRun;

/// Where the frame went: 0 same structure, 1 creations undone, 2 structure image.
int PathOf(const state_detail::FrameRestoreCounts& before, const state_detail::FrameRestoreCounts& after) {
    if (after.sameStructure == before.sameStructure + 1) return 0;
    if (after.undoneCreations == before.undoneCreations + 1) return 1;
    if (after.restoredStructure == before.restoredStructure + 1) return 2;
    return -1;
}

int RestoreAndPath(b2World& w, const b2WorldFrame& frame) {
    const state_detail::FrameRestoreCounts before = test::FrameRestores(w);
    if (!w.RestoreFrame(frame).ok()) return -2;
    return PathOf(before, test::FrameRestores(w));
}

TEST(FrameUndo, RainSpawnsAreUndoneAndRespawnWithTheSameIds) {
    // rain spawns bodies every few frames: each restore 8 frames back crosses a spawn. The
    // future hashes cover the respawned bodies' ids, their fixtures' ids and the pool order.
    SceneRun run{"rain"};
    run.Advance(100);
    b2World& w = run.world();
    for (int round = 0; round < 6; ++round) {
        const int32 bodies = w.GetBodyCount();
        const SavedFrame saved(run, 8);
        ASSERT_GT(w.GetBodyCount(), bodies) << "rain spawned nothing in 8 frames";
        EXPECT_EQ(RestoreAndPath(w, saved.frame), 1) << "round " << round;
        EXPECT_EQ(w.GetBodyCount(), bodies);
        EXPECT_TRUE(testing_state::EdgesFollowWorldLists(w));
        saved.ExpectBack(run);
        run.Advance(3);
    }
}

TEST(FrameUndo, SetUpOfNewBodiesIsUndoneToo) {
    SceneRun run{"ragdolls"};
    run.Advance(20);
    b2World& w = run.world();
    const SavedFrame saved(run, 15);
    // Every body-confined call, on bodies made after the frame, with steps in between.
    std::vector<b2Body*> made;
    for (int i = 0; i < 5; ++i) made.push_back(AddBox(w, b2Vec2(i, 18)));
    run.Advance(2);
    made[0]->SetLinearDamping(Fixed(1) / 10);
    made[0]->SetAngularDamping(Fixed(1) / 10);
    made[1]->SetGravityScale(Fixed(1) / 2);
    made[1]->SetUserData(42);
    made[2]->GetFixtureList()->SetDensity(3);
    made[2]->ResetMassData();
    made[2]->GetFixtureList()->SetFilterData(b2Filter{0x0002, 0xFFFD, 0});
    made[3]->SetType(b2_kinematicBody);
    made[4]->SetActive(false);
    b2CircleShape c;
    c.m_radius = Fixed(1) / 8;
    made[0]->CreateFixture(&c, 1);
    made[0]->DestroyFixture(made[0]->GetFixtureList()->GetNext());
    run.Advance(2);
    w.DestroyBody(made[1]);
    AddBox(w, b2Vec2(2, 25));  // takes the destroyed body's slot
    run.Advance(2);
    EXPECT_EQ(RestoreAndPath(w, saved.frame), 1);
    EXPECT_TRUE(testing_state::EdgesFollowWorldLists(w));
    saved.ExpectBack(run);
}

TEST(FrameUndo, SpawnedRagdollsWithTheirJointsAreUndone) {
    // Bodies spawned with joints among them (a chain with a gear, a weld and a distance joint),
    // one joint destroyed again: all newer than the frame, so undone like bodies.
    SceneRun run{"ragdolls"};
    run.Advance(15);
    b2World& w = run.world();
    const int32 joints = w.GetJointCount();
    const SavedFrame saved(run, 12);
    std::vector<b2Body*> made;
    for (int i = 0; i < 4; ++i) made.push_back(AddBox(w, b2Vec2(Fixed(i) / 2, 24)));
    std::vector<b2Joint*> hinges;
    for (int i = 0; i + 1 < 4; ++i) {
        b2RevoluteJointDef rd;
        rd.Initialize(made[static_cast<size_t>(i)], made[static_cast<size_t>(i) + 1],
                      made[static_cast<size_t>(i)]->GetPosition() + b2Vec2(Fixed(1) / 4, 0));
        hinges.push_back(w.CreateJoint(&rd));
    }
    b2GearJointDef gd;
    gd.bodyA = made[1];
    gd.bodyB = made[2];
    gd.joint1 = hinges[0];
    gd.joint2 = hinges[1];
    gd.ratio = 2;
    w.CreateJoint(&gd);
    run.Advance(3);
    b2WeldJointDef wd;
    wd.Initialize(made[0], made[3], made[0]->GetPosition());
    w.CreateJoint(&wd);
    b2DistanceJointDef dd;
    dd.Initialize(made[0], made[2], made[0]->GetPosition(), made[2]->GetPosition());
    b2Joint* doomed = w.CreateJoint(&dd);
    run.Advance(2);
    w.DestroyJoint(doomed);
    run.Advance(2);
    EXPECT_EQ(RestoreAndPath(w, saved.frame), 1);
    EXPECT_EQ(w.GetJointCount(), joints);
    EXPECT_TRUE(testing_state::EdgesFollowWorldLists(w));
    saved.ExpectBack(run);
}

TEST(FrameUndo, OtherChangesRestoreTheStructureImage) {
    // Changes that touch what the frame had, or are not confined to one body.
    using Change = std::function<void(b2World&, b2Body * older)>;
    const std::vector<std::pair<const char*, Change>> changes = {
        {"damping of an older body", [](b2World&, b2Body* older) { older->SetLinearDamping(Fixed(1) / 10); }},
        {"fixture on an older body",
         [](b2World&, b2Body* older) {
             b2CircleShape c;
             c.m_radius = Fixed(1) / 8;
             older->CreateFixture(&c, 1);
         }},
        {"older body destroyed", [](b2World& w, b2Body* older) { w.DestroyBody(older); }},
        {"older body made inactive", [](b2World&, b2Body* older) { older->SetActive(false); }},
        {"older fixture's shape", [](b2World&, b2Body* older) { (void)older->GetFixtureList()->EditShape(); }},
        {"joint between a new and an older body",
         [](b2World& w, b2Body* older) {
             b2Body* a = AddBox(w, b2Vec2(0, 20));
             b2DistanceJointDef jd;
             jd.Initialize(a, older, a->GetPosition(), older->GetPosition());
             w.CreateJoint(&jd);
         }},
        {"older joint destroyed", [](b2World& w, b2Body*) { w.DestroyJoint(w.GetJointList()); }},
        {"MarkStructureChanged",
         [](b2World& w, b2Body*) {
             AddBox(w, b2Vec2(0, 20));
             test::MarkStructureChanged(w);
         }},
    };
    for (const auto& [name, change] : changes) {
        SceneRun run{"ragdolls"};
        run.Advance(10);
        b2World& w = run.world();
        const SavedFrame saved(run, 10);
        b2Body* older = FirstDynamic(w);
        AddBox(w, b2Vec2(-2, 20));  // a spawn before it, which alone could be undone
        change(w, older);
        run.Advance(3);
        EXPECT_EQ(RestoreAndPath(w, saved.frame), 2) << name;
        saved.ExpectBack(run, name);
    }
}

TEST(FrameUndo, FramesAlongTheBranchAndAfterIt) {
    SceneRun run{"pyramid20"};
    run.Advance(10);
    b2World& w = run.world();
    b2WorldFrame a, b, c;
    w.SaveFrame(a);
    const uint64 hashA = w.Hash();
    AddBox(w, b2Vec2(0, 30));
    run.Advance(2);
    w.SaveFrame(b);
    const uint64 hashB = w.Hash();
    AddBox(w, b2Vec2(1, 30));
    run.Advance(2);
    w.SaveFrame(c);
    const uint64 hashC = w.Hash();
    run.Advance(2);
    // Back along the branch: each step undoes creations.
    EXPECT_EQ(RestoreAndPath(w, b), 1);
    EXPECT_EQ(w.Hash(), hashB);
    EXPECT_EQ(RestoreAndPath(w, a), 1);
    EXPECT_EQ(w.Hash(), hashA);
    // Forward again to a frame of the undone branch: its structure is gone, the image brings it
    // back, and the log starts again there (so b, older, takes its image too).
    EXPECT_EQ(RestoreAndPath(w, c), 2);
    EXPECT_EQ(w.Hash(), hashC);
    EXPECT_EQ(RestoreAndPath(w, b), 2);
    EXPECT_EQ(w.Hash(), hashB);
    // A new branch from b: its spawn undoes to b, not to anything of the old branch.
    AddBox(w, b2Vec2(-1, 30));
    run.Advance(1);
    EXPECT_EQ(RestoreAndPath(w, b), 1);
    EXPECT_EQ(w.Hash(), hashB);
    EXPECT_EQ(RestoreAndPath(w, b), 0);
}

TEST(FrameUndo, ALogTooLongForTheFrameFallsBackToTheImage) {
    SceneRun run{"pyramid20"};
    run.Advance(5);
    b2World& w = run.world();
    const SavedFrame saved(run, 0);
    // Three changes per box (body, fixture, mass): more than the log keeps.
    for (int i = 0; i < 1500; ++i) AddBox(w, b2Vec2(i % 40, 40 + i / 40));
    EXPECT_EQ(RestoreAndPath(w, saved.frame), 2);
    saved.ExpectBack(run);
}

TEST(FrameUndo, WorldsWithoutFramesKeepNoLog) {
    SceneRun run{"pyramid20"};
    b2World& w = run.world();
    for (int i = 0; i < 10; ++i) AddBox(w, b2Vec2(i, 30));
    EXPECT_EQ(test::StructureLogSize(w), 0u);
    b2WorldFrame frame;
    w.SaveFrame(frame);
    AddBox(w, b2Vec2(0, 40));
    EXPECT_EQ(test::StructureLogSize(w), 3u);  // the body, its fixture, its mass
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
