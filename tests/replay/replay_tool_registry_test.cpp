// A game's own replay tool (RunTool with a GameRegistry, lockbox/replay/Tool.h): a game that is
// not a library scene registers itself and gets info, verify, diff and bisect with the built-in
// tool's exit codes; a tool that does not know a replay's game refuses it.

#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/Tool.h"

namespace lockbox::replay {
namespace LOCKBOX_TEST_FILE {

// A small game of its own: a floor and a row of boxes that inputs push; its user state counts
// the pushes (state beyond the world, saved with every keyframe).
class PushGame : public Game, public ToolGame {
public:
    explicit PushGame(int32 push = 4) : m_world(b2Vec2(Fixed(0), Fixed(-10))), m_push(push) {
        b2BodyDef ground;
        b2Body* floor = m_world.CreateBody(&ground);
        b2PolygonShape slab;
        slab.SetAsBox(Fixed(20), Fixed::FromRatio(1, 2));
        floor->CreateFixture(&slab, Fixed(0));
        for (int i = 0; i < 4; ++i) {
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            bd.position = b2Vec2(Fixed(i * 2 - 3), Fixed(1 + i));
            b2Body* body = m_world.CreateBody(&bd);
            b2PolygonShape box;
            box.SetAsBox(Fixed::FromRatio(1, 2), Fixed::FromRatio(1, 2));
            body->CreateFixture(&box, Fixed(1));
        }
    }
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        (void)frame;
        int32 index = 0;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext(), ++index) {
            if (b->GetType() != b2_dynamicBody) continue;
            const uint8 in = inputs[static_cast<size_t>(index) % inputs.size()];
            if ((in & 1) == 0) continue;
            b->ApplyLinearImpulse(b2Vec2(Fixed(m_push), Fixed(1)), b->GetWorldCenter());
            ++m_pushes;
        }
    }
    void SaveUserState(std::vector<uint8>& out) const override {
        out.assign(4, 0);
        for (int i = 0; i < 4; ++i) out[static_cast<size_t>(i)] = static_cast<uint8>(m_pushes >> (8 * i));
    }
    void LoadUserState(std::span<const uint8> in) override {
        m_pushes = 0;
        for (size_t i = 0; i < in.size() && i < 4; ++i) m_pushes |= static_cast<uint32>(in[i]) << (8 * i);
    }
    b2World& World() override { return m_world; }
    Game& Logic() override { return *this; }

private:
    b2World m_world;
    int32 m_push;
    uint32 m_pushes = 0;
};

std::string RecordPushReplay(const std::string& name, uint32 keyframes) {
    const std::string path = ::testing::TempDir() + name;
    PushGame game;
    FileSink sink(path);
    RecorderConfig config;
    config.gameName = "push";
    config.playerCount = 2;
    config.inputBytes = 1;
    config.keyframeInterval = keyframes;
    Recorder recorder(game.World(), game, sink, config);
    EXPECT_TRUE(recorder.Begin().ok());
    for (int32 f = 0; f < 180; ++f) {
        const uint8 inputs[2] = {static_cast<uint8>(f % 7 == 0), static_cast<uint8>(f % 11 == 3)};
        recorder.Advance(inputs);
    }
    EXPECT_TRUE(recorder.Finish().ok());
    EXPECT_TRUE(sink.Close());
    return path;
}

int RunToolOn(const GameRegistry& games, std::vector<std::string> args) {
    args.insert(args.begin(), "push_replay");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    return RunTool(static_cast<int>(args.size()), argv.data(), games, "push_replay");
}

// The game's registration: the factory builds the game each replay names.
GameRegistry PushRegistry(int32 push = 4, std::string* seenOption = nullptr) {
    GameRegistry games;
    games.Add("push", [push, seenOption](const ToolGameRequest& request, std::string&) {
        if (seenOption != nullptr) {
            auto it = request.options.find("--rules");
            if (it != request.options.end()) *seenOption = it->second;
        }
        return std::make_unique<PushGame>(push);
    });
    games.AddOption("--rules", "FILE");
    return games;
}

TEST(ReplayToolRegistry, AGameRegisteredWithRunToolVerifiesDiffsAndBisects) {
    const std::string a = RecordPushReplay("push_a.lbr", 60);
    const GameRegistry games = PushRegistry();
    EXPECT_EQ(RunToolOn(games, {"info", a}), 0);
    EXPECT_EQ(RunToolOn(games, {"verify", a}), 0);
    EXPECT_EQ(RunToolOn(games, {"diff", a, a}), 0);
    EXPECT_EQ(RunToolOn(games, {"bisect", a}), 0);
    // A fault injected while re-simulating is found.
    EXPECT_EQ(RunToolOn(games, {"bisect", a, "--inject", "100:2"}), 1);
    std::remove(a.c_str());
}

TEST(ReplayToolRegistry, AnotherBuildOfTheGameDiverges) {
    const std::string a = RecordPushReplay("push_b.lbr", 60);
    // The same game name built with other rules (a stronger push): verify names the divergence.
    EXPECT_EQ(RunToolOn(PushRegistry(5), {"verify", a}), 1);
    std::remove(a.c_str());
}

TEST(ReplayToolRegistry, OptionsReachTheFactoryAndUnknownOnesAreRefused) {
    const std::string a = RecordPushReplay("push_c.lbr", 0);
    std::string seen;
    const GameRegistry games = PushRegistry(4, &seen);
    EXPECT_EQ(RunToolOn(games, {"verify", a, "--rules", "hard.json"}), 0);
    EXPECT_EQ(seen, "hard.json");
    EXPECT_EQ(RunToolOn(games, {"verify", a, "--bogus"}), 2);
    EXPECT_EQ(RunToolOn(games, {"info", a, "--rules", "x"}), 2);  // options are for verify, diff, bisect
    EXPECT_EQ(RunToolOn(games, {"frobnicate", a}), 2);
    EXPECT_EQ(RunToolOn(games, {}), 2);
    std::remove(a.c_str());
}

TEST(ReplayToolRegistry, AGameNotRegisteredIsRefused) {
    const std::string a = RecordPushReplay("push_d.lbr", 60);
    GameRegistry scenesOnly;
    scenesOnly.AddPrefix("scene:", [](const ToolGameRequest&, std::string& error) -> std::unique_ptr<ToolGame> {
        error = "no scenes in this test";
        return nullptr;
    });
    EXPECT_EQ(RunToolOn(scenesOnly, {"verify", a}), 2);
    EXPECT_EQ(RunToolOn(scenesOnly, {"info", a}), 0);  // info needs no game
    std::string error;
    ReplayFile file;
    ASSERT_TRUE(LoadReplay(a, file).ok());
    EXPECT_EQ(scenesOnly.Make(ToolGameRequest{file, a, {}}, error), nullptr);
    EXPECT_NE(error.find("\"push\" is not one this tool knows"), std::string::npos) << error;
    std::remove(a.c_str());
}

TEST(ReplayToolRegistry, ExactNamesComeBeforePrefixesAndTheLongestPrefixWins) {
    int made = 0;
    auto maker = [&made](int id) {
        return [&made, id](const ToolGameRequest&, std::string&) -> std::unique_ptr<ToolGame> {
            made = id;
            return std::make_unique<PushGame>();
        };
    };
    GameRegistry games;
    games.AddPrefix("p", maker(1));
    games.AddPrefix("pu", maker(2));
    games.Add("push", maker(3));
    ReplayFile file;
    file.gameName = "push";
    std::string error;
    EXPECT_NE(games.Make(ToolGameRequest{file, "x", {}}, error), nullptr);
    EXPECT_EQ(made, 3);
    file.gameName = "pull";
    EXPECT_NE(games.Make(ToolGameRequest{file, "x", {}}, error), nullptr);
    EXPECT_EQ(made, 2);
    file.gameName = "pop";
    EXPECT_NE(games.Make(ToolGameRequest{file, "x", {}}, error), nullptr);
    EXPECT_EQ(made, 1);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::replay
