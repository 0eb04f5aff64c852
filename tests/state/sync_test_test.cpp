// SyncTest over the light scenes of the library (short runs; the heavy suite runs 600 frames
// and the heavy scenes), in both modes, plus checks that the sync test does catch a leak.

#include <gtest/gtest.h>

#include "SceneSyncGame.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::RunSceneSyncTest;

// Rolls back 4 frames after every frame; wrong inputs first when `mispredict` is set.
SyncTestConfig EveryFrame(bool mispredict, uint64 seed) {
    SyncTestConfig config;
    config.checkDistance = 4;
    config.stride = 1;
    config.mispredict = mispredict;
    config.seed = seed;
    return config;
}

class SceneSync : public ::testing::TestWithParam<std::string_view> {};

#ifdef NDEBUG
constexpr int32 kFrames = 90;
#else
constexpr int32 kFrames = 24;  // sanitizer and debug builds are ~10x slower
#endif

TEST_P(SceneSync, RollbackReproducesEveryFrame) {
    const SyncTestResult r = RunSceneSyncTest(GetParam(), kFrames, /*mispredict=*/false);
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.framesSimulated, kFrames);
    EXPECT_EQ(r.framesResimulated, (kFrames - 7) * 8);
}

TEST_P(SceneSync, MispredictedBranchLeavesNoTrace) {
    const SyncTestResult r = RunSceneSyncTest(GetParam(), kFrames, /*mispredict=*/true);
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.rollbacks, kFrames - 7);
}

TEST_P(SceneSync, RollbackThroughFramesReproducesEveryFrame) {
    const SyncTestResult r = RunSceneSyncTest(GetParam(), kFrames, /*mispredict=*/false, 1, /*useFrames=*/true);
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.framesResimulated, (kFrames - 7) * 8);
}

TEST_P(SceneSync, MispredictThroughFramesLeavesNoTrace) {
    const SyncTestResult r = RunSceneSyncTest(GetParam(), kFrames, /*mispredict=*/true, 1, /*useFrames=*/true);
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.rollbacks, kFrames - 7);
    // Both ways across a structural change ran: spawn-only branches undone, the others through
    // the structure image.
    EXPECT_GT(r.frameRestores.undoneCreations, 0u);
    EXPECT_GT(r.frameRestores.restoredStructure, 0u);
}

// After create/destroy churn (the mispredicted branches) and restores, every body's edge lists
// still follow the world lists: the invariant that lets snapshots leave them out.
TEST(SyncTestTool, EdgeListsFollowWorldListsAfterChurn) {
    for (const char* name : {"ragdolls", "pulley_gear", "bullet_stack_dynamic", "car"}) {
        testing_state::SceneRun run(name);
        testing_state::SceneSyncGame game(run);
        SyncTestConfig config = EveryFrame(true, 99);
        config.step = game.Step();
        SyncTest test(run.world(), game, {}, config);
        const SyncTestResult r = test.Run(40);
        EXPECT_TRUE(r.ok) << name << ": " << r.message;
        EXPECT_TRUE(testing_state::EdgesFollowWorldLists(run.world())) << name;
        // And in the middle of a mispredicted branch (bodies and joints made and destroyed).
        for (int i = 0; i < 10; ++i) {
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            bd.position.Set(i, 3);
            b2Body* body = run.world().CreateBody(&bd);
            b2CircleShape circle;
            circle.m_radius = Fixed(1) / 2;
            body->CreateFixture(&circle, 1);
            b2DistanceJointDef jd;
            jd.Initialize(body, run.world().GetBodyList()->GetNext(), body->GetPosition(), b2Vec2(0, 0));
            if (run.world().GetBodyList()->GetNext() != body) run.world().CreateJoint(&jd);
            AdvanceWorldFrame(run.world(), game, 40 + i, {}, game.Step());
            if (i % 3 == 0) run.world().DestroyBody(run.world().GetBodyList()->GetNext());
        }
        EXPECT_TRUE(testing_state::EdgesFollowWorldLists(run.world())) << name;
    }
}

INSTANTIATE_TEST_SUITE_P(Light, SceneSync, ::testing::ValuesIn(testing_state::SceneNames(/*large=*/false)),
                         [](const ::testing::TestParamInfo<std::string_view>& p) { return std::string(p.param); });

// A game that keeps a counter outside the world but does not save it: the sync test must
// catch it (the counter feeds the inputs of later frames).
class LeakyGame : public WorldGame {
public:
    explicit LeakyGame(b2Body* body) : body_(body) {}
    // The sync test's default step settings: 1/60 s, 8 and 3 iterations.
    void Apply(b2World&, int32, std::span<const uint8>) override {
        ++pushes_;
        body_->SetLinearVelocity(b2Vec2(Fixed(pushes_) / 16, 0));
    }
    void SaveUserState(std::vector<uint8>& out) const override {
        if (saves_) out.push_back(static_cast<uint8>(pushes_));
    }
    void LoadUserState(std::span<const uint8> in) override {
        if (saves_ && !in.empty()) pushes_ = in[0];
    }
    bool saves_ = false;

private:
    b2Body* body_;
    int32 pushes_ = 0;
};

b2Body* MakeBox(b2World& world) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(0, 2);
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(Fixed(1) / 2, Fixed(1) / 2);
    body->CreateFixture(&box, 1);
    return body;
}

TEST(SyncTestTool, CatchesStateOutsideTheSnapshot) {
    b2World world(b2Vec2(0, -10));
    LeakyGame game(MakeBox(world));
    SyncTest test(world, game);
    const SyncTestResult r = test.Run(30);
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.firstBadFrame, 1) << r.message;
    EXPECT_EQ(r.where.category, b2HashCategory::e_bodies) << r.message;
}

TEST(SyncTestTool, PassesWhenTheGameSavesItsState) {
    b2World world(b2Vec2(0, -10));
    LeakyGame game(MakeBox(world));
    game.saves_ = true;
    SyncTest test(world, game, {}, EveryFrame(true, 7));
    const SyncTestResult r = test.Run(30);
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.rollbacks, 27);
}

// A game that reads its inputs: a push per frame, from the frame's first byte.
class PushGame : public WorldGame {
public:
    explicit PushGame(b2Body* body) : body_(body) {}
    void Apply(b2World&, int32, std::span<const uint8> inputs) override {
        body_->ApplyLinearImpulse(b2Vec2(Fixed(inputs[0]) / 64, Fixed(inputs[1]) / 64), body_->GetWorldCenter());
    }

private:
    b2Body* body_;
};

TEST(SyncTestTool, AsksTheInputSourceOncePerFrame) {
    b2World world(b2Vec2(0, -10));
    PushGame game(MakeBox(world));
    // Not a pure function of the frame: a re-simulation must get the first run's bytes back.
    int32 calls = 0;
    std::vector<int32> frames;
    SyncTestConfig config = EveryFrame(true, 7);
    config.inputBytes = 2;
    config.step = {30, 6, 2};
    SyncTest test(
        world, game,
        [&](int32 frame, std::span<uint8> out) {
            frames.push_back(frame);
            out[0] = static_cast<uint8>(++calls * 37);
            out[1] = static_cast<uint8>(calls * 11);
        },
        config);
    const SyncTestResult r = test.Run(20);
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(calls, 20);
    for (int32 f = 0; f < 20; ++f) EXPECT_EQ(frames[static_cast<size_t>(f)], f);
}

TEST(SyncTestTool, StepsWithTheConfiguredSettings) {
    // The same pushes stepped by hand at 30 Hz with 6 and 2 iterations end where the sync test
    // leaves the world (it ends on a re-simulation of the last frames).
    auto run = [](bool byHand) {
        b2World world(b2Vec2(0, -10));
        PushGame game(MakeBox(world));
        const auto source = [](int32 frame, std::span<uint8> out) {
            out[0] = static_cast<uint8>(frame * 13);
            out[1] = static_cast<uint8>(frame * 7);
        };
        SyncTestConfig config = EveryFrame(false, 7);
        config.inputBytes = 2;
        config.step = {30, 6, 2};
        if (byHand) {
            std::vector<uint8> in(2);
            for (int32 f = 0; f < 12; ++f) {
                source(f, in);
                AdvanceWorldFrame(world, game, f, in, config.step);
            }
        } else {
            SyncTest test(world, game, source, config);
            EXPECT_TRUE(test.Run(12).ok);
        }
        return world.Hash();
    };
    EXPECT_EQ(run(true), run(false));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
