// SyncTestSession on every library scene through rollback frames (the adapter's restore path),
// with mispredicted branches: a scene whose state a rollback frame misses fails here.

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
namespace {

class SyncTestScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(SyncTestScenes, PassesThroughRollbackFrames) {
    replay::SceneGame game(GetParam());
    ASSERT_TRUE(game.ok());
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
    auto script = std::make_shared<replay::ScriptedInputs>(21, 2);
    auto row = std::make_shared<std::vector<uint8_t>>();
    SyncTestSession session(
        game.world(), game,
        [script, row](int32_t, std::span<uint8_t> out) {
            script->Next(*row);
            std::copy(row->begin(), row->end(), out.begin());
        },
        c);
    const SyncTestResult r = session.Run(12);
    EXPECT_TRUE(r.ok) << GetParam() << ": " << r.message;
    const SyncTestFrameRestores& f = r.frameRestores;
    EXPECT_EQ(f.sameStructure + f.undoneCreations + f.restoredStructure, 2u * static_cast<uint64_t>(r.rollbacks));
}

std::vector<std::string> Scenes() {
    std::vector<std::string> out;
    for (std::string_view n : scenes::AllSceneNames()) out.emplace_back(n);
    return out;
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SyncTestScenes, ::testing::ValuesIn(Scenes()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param;
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

}  // namespace
}  // namespace lockbox::net
