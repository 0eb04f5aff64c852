// SyncTestSession on every library scene with mispredicted branches, through rollback frames
// (the adapter's restore path) and through the requests a live session makes, executed by the
// adapter: a scene whose state a rollback frame misses fails here.

#include <algorithm>
#include <cctype>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/RollbackSyncTest.h"
#include "lockbox/replay/SceneGame.h"
#include "lockbox/scenes/Registry.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

class SyncTestScenes : public ::testing::TestWithParam<std::string> {};

SyncTestSessionConfig Config(const replay::SceneGame& game) {
    SyncTestSessionConfig c;
    c.players = 2;
    c.inputBytes = replay::SceneInput::kBytes;
    c.mispredict = true;
    // 12 frames rolled back 4 each, twice (wrong branch, right one): the dense scenes of a
    // thousand bodies and more keep this to seconds.
    c.checkDistance = 4;
    c.step =
        WorldStepSettings{static_cast<uint32_t>(game.info().hz), static_cast<uint32_t>(game.info().velocityIterations),
                          static_cast<uint32_t>(game.info().positionIterations)};
    return c;
}

SyncTestInputSource Scripted(uint64_t seed) {
    auto script = std::make_shared<replay::ScriptedInputs>(seed, 2);
    auto row = std::make_shared<std::vector<uint8_t>>();
    return [script, row](int32_t, std::span<uint8_t> out) {
        script->Next(*row);
        std::copy(row->begin(), row->end(), out.begin());
    };
}

TEST_P(SyncTestScenes, PassesThroughRollbackFrames) {
    replay::SceneGame game(GetParam());
    ASSERT_TRUE(game.ok());
    SyncTestSession session(game.world(), game, Scripted(21), Config(game));
    const SyncTestResult r = session.Run(12);
    EXPECT_TRUE(r.ok) << GetParam() << ": " << r.message;
    const SyncTestFrameRestores& f = r.frameRestores;
    EXPECT_EQ(f.sameStructure + f.undoneCreations + f.restoredStructure, 2u * static_cast<uint64_t>(r.rollbacks));
}

TEST_P(SyncTestScenes, PassesThroughTheAdaptersRequests) {
    replay::SceneGame game(GetParam());
    ASSERT_TRUE(game.ok());
    SyncTestSession session(game.world(), game, Scripted(22), Config(game));
    const SyncTestResult r = session.RunRequests(12);
    EXPECT_TRUE(r.ok) << GetParam() << ": " << r.message;
    EXPECT_EQ(session.RequestCounts().loads, 2u * static_cast<uint64_t>(r.rollbacks));
}

std::vector<std::string> Scenes() {
    std::vector<std::string> out;
    for (std::string_view n : scenes::AllSceneNames()) out.emplace_back(n);
    return out;
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SyncTestScenes, ::testing::ValuesIn(Scenes()),
                         [](const ::testing::TestParamInfo<std::string>& scene) {
                             std::string name = scene.param;
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
