// SyncTestSession: a scene game with complete state passes (plain and mispredict mode); a game
// that keeps state outside its save fails at the first re-simulated frame it affects.

#include <map>

#include <gtest/gtest.h>

#include "lockbox/net/RollbackSyncTest.h"
#include "lockbox/net/StateHash.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

SyncTestSessionConfig ConfigFor(const replay::SceneGame& g, bool mispredict) {
    SyncTestSessionConfig c;
    c.players = 2;
    c.inputBytes = replay::SceneInput::kBytes;
    c.mispredict = mispredict;
    c.step = WorldStepSettings{static_cast<uint32_t>(g.info().hz), static_cast<uint32_t>(g.info().velocityIterations),
                               static_cast<uint32_t>(g.info().positionIterations)};
    return c;
}

SyncTestInputSource Scripted(uint64_t seed) {
    auto script = std::make_shared<replay::ScriptedInputs>(seed, 2);
    auto buffer = std::make_shared<std::vector<uint8_t>>();
    return [script, buffer](int32_t, std::span<uint8_t> out) {
        script->Next(*buffer);
        std::copy(buffer->begin(), buffer->end(), out.begin());
    };
}

TEST(RollbackSyncTest, SceneGamePassesBothModes) {
    for (bool mispredict : {false, true}) {
        SCOPED_TRACE(::testing::Message() << "seed=11 mispredict=" << mispredict);
        replay::SceneGame game("vertical_stack");
        ASSERT_TRUE(game.ok());
        SyncTestSession session(game.world(), game, Scripted(11), ConfigFor(game, mispredict));
        const SyncTestResult r = session.Run(80);
        EXPECT_TRUE(r.ok) << r.message;
        EXPECT_EQ(r.framesSimulated, 80);
        EXPECT_GT(r.rollbacks, 60);
    }
}

// Pushes the first dynamic body by an amount that grows with a counter the save misses.
class LeakyGame : public WorldGame {
public:
    explicit LeakyGame(replay::SceneGame& inner) : m_inner(inner) {}
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        ++m_hidden;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext())
            if (b->GetType() == b2_dynamicBody) {
                b->ApplyLinearImpulse(b2Vec2(Fixed::FromRaw(m_hidden * 64), Fixed::FromRaw(0)), b->GetWorldCenter());
                break;
            }
        m_inner.Apply(world, frame, inputs);
    }

private:
    replay::SceneGame& m_inner;
    int32 m_hidden = 0;
};

TEST(RollbackSyncTest, ConfigFromTheSessionBuilder) {
    RollbackSessionBuilder b;
    b.Players(3).InputBytes(4).CheckDistance(5);
    const SyncTestSessionConfig c = SyncTestConfigFrom(b.Config(), WorldStepSettings{30, 6, 2}, true);
    EXPECT_EQ(c.players, 3u);
    EXPECT_EQ(c.inputBytes, 4u);
    EXPECT_EQ(c.checkDistance, 5u);
    EXPECT_TRUE(c.mispredict);
    EXPECT_EQ(c.step.tickRate, 30u);
}

TEST(RollbackSyncTest, StateOutsideTheSaveIsCaught) {
    SCOPED_TRACE("seed=12");
    replay::SceneGame scene("vertical_stack");
    LeakyGame game(scene);
    SyncTestSession session(scene.world(), game, Scripted(12), ConfigFor(scene, false));
    const SyncTestResult r = session.Run(60);
    EXPECT_FALSE(r.ok);
    EXPECT_GE(r.firstBadFrame, 1);
    EXPECT_LE(r.firstBadFrame, 9);
    EXPECT_FALSE(r.message.empty());
}

TEST(RollbackSyncTest, FramesAreTheDefaultPathAndTheCountersSayWhichRan) {
    for (SyncTestRestore restore : {SyncTestRestore::e_frames, SyncTestRestore::e_images}) {
        replay::SceneGame game("rain");  // spawns, so some restores undo creations
        SyncTestSessionConfig config = ConfigFor(game, true);
        if (restore == SyncTestRestore::e_images) config.restore = restore;
        EXPECT_EQ(SyncTestSessionConfig{}.restore, SyncTestRestore::e_frames);
        SyncTestSession session(game.world(), game, Scripted(13), config);
        const SyncTestResult r = session.Run(40);
        EXPECT_TRUE(r.ok) << r.message;
        const SyncTestFrameRestores& f = r.frameRestores;
        const uint64_t frameRestores = f.sameStructure + f.undoneCreations + f.restoredStructure;
        if (restore == SyncTestRestore::e_frames) {
            // Every rollback restores twice in mispredict mode (wrong branch, then right one).
            EXPECT_EQ(frameRestores, 2u * static_cast<uint64_t>(r.rollbacks));
            EXPECT_GT(f.undoneCreations, 0u);
        } else {
            EXPECT_EQ(frameRestores, 0u);
        }
    }
}

// A game that keeps a fuel gauge per body and forgets it in its save: the body it pushes
// drifts on re-simulation, and the sync test names that body.
class ForgetfulGame : public WorldGame {
public:
    ForgetfulGame(replay::SceneGame& inner, int32 bodyId) : m_inner(inner), m_bodyId(bodyId) {}
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        m_inner.Apply(world, frame, inputs);
        ++m_burned;
        if (b2Body* b = world.GetBody(m_bodyId))
            b->ApplyLinearImpulse(b2Vec2(Fixed::FromRaw(0), Fixed::FromRaw(m_burned * 256)), b->GetWorldCenter());
    }
    // The save holds the frame count but forgets the fuel burned.
    void SaveUserState(std::vector<uint8>& out) const override { out.assign(1, 7); }
    void LoadUserState(std::span<const uint8>) override {}

private:
    replay::SceneGame& m_inner;
    int32 m_bodyId;
    int32 m_burned = 0;
};

TEST(RollbackSyncTest, AForgottenPieceOfStateIsNamedByBody) {
    for (SyncTestRestore restore : {SyncTestRestore::e_frames, SyncTestRestore::e_images}) {
        replay::SceneGame scene("vertical_stack");
        // The third dynamic body of the list is the one the game pushes.
        int32 target = -1, seen = 0;
        for (b2Body* b = scene.world().GetBodyList(); b && target < 0; b = b->GetNext())
            if (b->GetType() == b2_dynamicBody && ++seen == 3) target = b->GetId();
        ASSERT_GE(target, 0);
        ForgetfulGame game(scene, target);
        SyncTestSessionConfig config = ConfigFor(scene, false);
        config.restore = restore;
        SyncTestSession session(scene.world(), game, Scripted(14), config);
        const SyncTestResult r = session.Run(40);
        ASSERT_FALSE(r.ok);
        EXPECT_EQ(r.where.category, b2HashCategory::e_bodies) << r.message;
        EXPECT_EQ(r.where.bodyId, target) << r.message;
        EXPECT_NE(r.message.find("body " + std::to_string(target)), std::string::npos) << r.message;
    }
}

TEST(RollbackSyncTest, RequestsDriveTheAdapterAsALiveSessionDoes) {
    for (const char* name : {"vertical_stack", "rain"})
        for (bool mispredict : {false, true}) {
            SCOPED_TRACE(::testing::Message() << name << " mispredict=" << mispredict);
            replay::SceneGame game(name);
            SyncTestSession session(game.world(), game, Scripted(15), ConfigFor(game, mispredict));
            const SyncTestResult r = session.RunRequests(40);
            EXPECT_TRUE(r.ok) << r.message;
            EXPECT_EQ(r.framesSimulated, 40);
            EXPECT_EQ(r.rollbacks, 40 - 8 + 1);
            const SyncTestRequestCounts& c = session.RequestCounts();
            const uint64_t branches = mispredict ? 2u : 1u;
            EXPECT_EQ(c.loads, branches * static_cast<uint64_t>(r.rollbacks));
            EXPECT_EQ(c.advances, 40u + branches * 8u * static_cast<uint64_t>(r.rollbacks));
            EXPECT_EQ(c.predictedAdvances, mispredict ? 8u * static_cast<uint64_t>(r.rollbacks) : 0u);
        }
}

TEST(RollbackSyncTest, RequestsNameTheBodyAGameForgetsToSave) {
    replay::SceneGame scene("vertical_stack");
    int32 target = -1, seen = 0;
    for (b2Body* b = scene.world().GetBodyList(); b && target < 0; b = b->GetNext())
        if (b->GetType() == b2_dynamicBody && ++seen == 2) target = b->GetId();
    ForgetfulGame game(scene, target);
    SyncTestSession session(scene.world(), game, Scripted(16), ConfigFor(scene, true));
    const SyncTestResult r = session.RunRequests(40);
    ASSERT_FALSE(r.ok);
    EXPECT_EQ(r.where.category, b2HashCategory::e_bodies) << r.message;
    EXPECT_EQ(r.where.bodyId, target) << r.message;
    EXPECT_NE(r.message.find("body " + std::to_string(target)), std::string::npos) << r.message;
}

// A game's own executor: portable images in a map, the folded hash, and (when broken) a load
// that forgets the game's own state.
class ImageExecutor {
public:
    ImageExecutor(b2World& world, WorldGame& game, WorldStepSettings step)
        : m_world(world), m_game(game), m_step(step) {}
    bool operator()(std::span<const RollbackRequest> requests, const RollbackHashReport& report) {
        for (const RollbackRequest& r : requests) {
            if (const auto* s = std::get_if<SaveState>(&r)) {
                Saved& to = m_saved[s->frame];
                m_world.Save(to.image);
                m_game.SaveUserState(to.user);
                if (s->wantHash) report(s->frame, FoldedStateHash(m_world, m_game));
            } else if (const auto* l = std::get_if<LoadState>(&r)) {
                auto it = m_saved.find(l->frame);
                if (it == m_saved.end() || !m_world.Restore(it->second.image).ok()) return false;
                if (!forgetUserState) m_game.LoadUserState(it->second.user);
            } else if (const auto* a = std::get_if<AdvanceRequest>(&r)) {
                m_game.Apply(m_world, a->frame, a->inputs);
                m_world.Step(Fixed::FromRatio(1, static_cast<int32>(m_step.tickRate)),
                             static_cast<int32>(m_step.velocityIterations),
                             static_cast<int32>(m_step.positionIterations));
            }
        }
        return true;
    }
    bool forgetUserState = false;

private:
    struct Saved {
        std::vector<uint8_t> image, user;
    };
    b2World& m_world;
    WorldGame& m_game;
    WorldStepSettings m_step;
    std::map<int32_t, Saved> m_saved;
};

// A scene game that counts its frames in its user state (the count changes nothing in the world).
class CountingGame : public WorldGame {
public:
    explicit CountingGame(replay::SceneGame& inner) : m_inner(inner) {}
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        ++m_count;
        m_inner.Apply(world, frame, inputs);
    }
    void SaveUserState(std::vector<uint8>& out) const override { out.assign(1, m_count); }
    void LoadUserState(std::span<const uint8> in) override { m_count = in.empty() ? 0 : in[0]; }

private:
    replay::SceneGame& m_inner;
    uint8 m_count = 0;
};

TEST(RollbackSyncTest, TheGamesOwnExecutorIsWhatRuns) {
    for (bool broken : {false, true}) {
        SCOPED_TRACE(::testing::Message() << "broken=" << broken);
        replay::SceneGame scene("vertical_stack");
        CountingGame game(scene);
        const SyncTestSessionConfig config = ConfigFor(scene, true);
        ImageExecutor executor(scene.world(), game, config.step);
        executor.forgetUserState = broken;
        SyncTestSession session(scene.world(), game, Scripted(17), config);
        const SyncTestResult r =
            session.RunRequests(30, [&executor](std::span<const RollbackRequest> q, const RollbackHashReport& report) {
                return executor(q, report);
            });
        EXPECT_EQ(r.ok, !broken) << r.message;
        if (broken) {
            EXPECT_EQ(r.where.category, b2HashCategory::e_count);
            EXPECT_NE(r.message.find("user state"), std::string::npos) << r.message;
        }
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
