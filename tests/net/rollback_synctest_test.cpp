// SyncTestSession: a scene game with complete state passes (plain and mispredict mode); a game
// that keeps state outside its save fails at the first re-simulated frame it affects.

#include <gtest/gtest.h>

#include "lockbox/net/RollbackSyncTest.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net {
namespace {

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
class LeakyGame : public replay::Game {
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

}  // namespace
}  // namespace lockbox::net
