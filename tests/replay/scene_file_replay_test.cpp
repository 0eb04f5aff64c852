// Replays recorded on a b2dJson scene file: the game is "scenefile:STEM", META's parameters
// carry the file's hash (SceneFileParams), and the replay verifies with a game made from the
// same file or, since its seed holds the world, from no file at all. Replays of library scenes
// carry no parameters, as before (their bytes are unchanged: replay_golden_test).
#include <string>

#include <gtest/gtest.h>

#include "lockbox/replay/Player.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::replay {
namespace LOCKBOX_TEST_FILE {

std::string HandmadeFile(const char* name) {
    return std::string(LOCKBOX_SOURCE_DIR) + "/scenes/files/handmade/" + name + ".json";
}

std::unique_ptr<SceneGame> FileGame(const char* name) {
    scenefile::SceneResult error;
    auto game = SceneGame::ForSceneFile(scenes::SceneFileScene::Open(HandmadeFile(name), &error));
    EXPECT_TRUE(game) << error.Describe();
    return game;
}

std::vector<uint8> Record(SceneGame& game, int32 frames) {
    MemorySink sink;
    RecorderConfig config = game.Config(2);
    config.keyframeInterval = 30;
    Recorder recorder(game.world(), game, sink, config);
    EXPECT_TRUE(recorder.Begin().ok());
    ScriptedInputs script(7, 2);
    std::vector<uint8> inputs;
    for (int32 f = 0; f < frames; ++f) {
        script.Next(inputs);
        recorder.Advance(inputs);
    }
    EXPECT_TRUE(recorder.Finish().ok());
    return sink.bytes();
}

TEST(SceneFileReplay, CarriesTheFileHashAndVerifies) {
    auto game = FileGame("joints");
    ASSERT_TRUE(game);
    const std::vector<uint8> bytes = Record(*game, 90);
    ReplayFile file;
    ASSERT_TRUE(ParseReplay(bytes, file).ok());
    EXPECT_EQ(file.gameName, "scenefile:joints");
    uint64 carried = 0;
    ASSERT_TRUE(SceneFileHashOf(file, carried));

    // The same file: the hash matches and the replay verifies.
    auto same = FileGame("joints");
    ASSERT_TRUE(same);
    std::string text;
    ASSERT_TRUE(scenefile::ReadSceneFileBytes(HandmadeFile("joints"), text));
    EXPECT_EQ(carried, scenefile::SceneFileHash(text));
    Player player(file, same->world(), *same);
    const VerifyResult r = player.Verify();
    EXPECT_TRUE(r.error.ok()) << r.error.Describe();
    EXPECT_TRUE(r.ok) << r.message;

    // Another file has another hash (lockbox_replay refuses it).
    std::string other;
    ASSERT_TRUE(scenefile::ReadSceneFileBytes(HandmadeFile("shapes"), other));
    EXPECT_NE(scenefile::SceneFileHash(other), carried);

    // No file: the seed holds the world, an empty scene gives the game.
    auto empty = SceneGame::ForSceneFile(scenes::SceneFileScene::FromText("joints", "{}", nullptr));
    ASSERT_TRUE(empty && empty->ok());
    Player seedOnly(file, empty->world(), *empty);
    const VerifyResult s = seedOnly.Verify();
    EXPECT_TRUE(s.ok) << s.message;
}

TEST(SceneFileReplay, LibraryScenesCarryNoParameters) {
    SceneGame game("pyramid20");
    ASSERT_TRUE(game.ok());
    EXPECT_EQ(game.Config(1).gameName, "scene:pyramid20");
    EXPECT_TRUE(game.Config(1).gameParams.empty());
    ReplayFile file;
    file.gameName = "scene:pyramid20";
    uint64 hash = 0;
    EXPECT_FALSE(SceneFileHashOf(file, hash));
    file.gameName = "scenefile:x";
    file.gameParams = SceneFileParams(0x0123456789abcdefull);
    ASSERT_TRUE(SceneFileHashOf(file, hash));
    EXPECT_EQ(hash, 0x0123456789abcdefull);
    file.gameParams.pop_back();
    EXPECT_FALSE(SceneFileHashOf(file, hash));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::replay
