// lockbox_replay verify-dir (lockbox/replay/VerifyDir.h): a directory with verified, diverged
// and corrupt replays gives the same report, sorted by name, on one thread and on several.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/VerifyDir.h"

namespace lockbox::replay {
namespace LOCKBOX_TEST_FILE {

namespace fs = std::filesystem;

// Boxes on a floor that inputs push with a strength the game is built with: a build with
// another strength diverges from the first push on.
class ShoveGame : public Game, public ToolGame {
public:
    explicit ShoveGame(int32 strength) : m_world(b2Vec2(Fixed(0), Fixed(-10))), m_strength(strength) {
        b2BodyDef ground;
        b2Body* floor = m_world.CreateBody(&ground);
        b2PolygonShape slab;
        slab.SetAsBox(Fixed(20), Fixed::FromRatio(1, 2));
        floor->CreateFixture(&slab, Fixed(0));
        for (int i = 0; i < 3; ++i) {
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            bd.position = b2Vec2(Fixed(i * 2 - 2), Fixed(2 + i));
            b2PolygonShape box;
            box.SetAsBox(Fixed::FromRatio(1, 2), Fixed::FromRatio(1, 2));
            m_world.CreateBody(&bd)->CreateFixture(&box, Fixed(1));
        }
    }
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        (void)frame;
        if ((inputs[0] & 1) == 0) return;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext())
            if (b->GetType() == b2_dynamicBody)
                b->ApplyLinearImpulse(b2Vec2(Fixed(m_strength), Fixed(0)), b->GetWorldCenter());
    }
    b2World& World() override { return m_world; }
    Game& Logic() override { return *this; }

private:
    b2World m_world;
    int32 m_strength;
};

void Record(const fs::path& path, int32 strength) {
    ShoveGame game(strength);
    FileSink sink(path.string());
    RecorderConfig config;
    config.gameName = strength == 3 ? "shove" : "shove-strong";
    config.playerCount = 1;
    config.inputBytes = 1;
    Recorder recorder(game.World(), game, sink, config);
    ASSERT_TRUE(recorder.Begin().ok());
    for (int32 f = 0; f < 90; ++f) {
        const uint8 input = static_cast<uint8>(f % 10 == 5);
        recorder.Advance(std::span<const uint8>(&input, 1));
    }
    ASSERT_TRUE(recorder.Finish().ok());
    ASSERT_TRUE(sink.Close());
}

// "shove" plays with strength 3, as recorded; "shove-strong" was recorded with 5 and is played
// with 3, so it diverges at its first push (frame 5).
GameRegistry Games() {
    GameRegistry games;
    for (const char* name : {"shove", "shove-strong"})
        games.Add(name, [](const ToolGameRequest&, std::string&) { return std::make_unique<ShoveGame>(3); });
    return games;
}

TEST(VerifyDir, ReportsEveryReplaySortedTheSameOnAnyThreadCount) {
    const fs::path dir = fs::path(::testing::TempDir()) / "verify_dir_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    Record(dir / "c_good.lbr", 3);
    Record(dir / "a_good.lbr", 3);
    Record(dir / "b_diverged.lbr", 5);
    {
        // A cut copy of a good replay, a file that is no replay at all, and a file that is not
        // a replay's name (skipped).
        const auto size = fs::file_size(dir / "a_good.lbr");
        fs::copy_file(dir / "a_good.lbr", dir / "d_cut.lbr");
        fs::resize_file(dir / "d_cut.lbr", size / 2);
        std::ofstream(dir / "e_junk.lbr") << "not a replay";
        std::ofstream(dir / "notes.txt") << "skipped";
    }
    const GameRegistry games = Games();
    VerifyDirReport one, four;
    std::string error;
    ASSERT_TRUE(VerifyDirectory(dir.string(), games, 1, {}, one, error)) << error;
    ASSERT_TRUE(VerifyDirectory(dir.string(), games, 4, {}, four, error)) << error;
    ASSERT_EQ(one.entries.size(), 5u);
    EXPECT_EQ(one.verified, 2u);
    EXPECT_EQ(one.diverged, 1u);
    EXPECT_EQ(one.corrupt, 2u);
    const std::vector<std::string> names = {"a_good.lbr", "b_diverged.lbr", "c_good.lbr", "d_cut.lbr", "e_junk.lbr"};
    for (size_t i = 0; i < names.size(); ++i) {
        EXPECT_EQ(one.entries[i].name, names[i]);
        EXPECT_EQ(four.entries[i].name, names[i]);
        EXPECT_EQ(one.entries[i].outcome, four.entries[i].outcome) << names[i];
        EXPECT_EQ(one.entries[i].reason, four.entries[i].reason) << names[i];
    }
    using O = VerifyDirEntry::Outcome;
    EXPECT_EQ(one.entries[0].outcome, O::e_verified);
    EXPECT_EQ(one.entries[0].frames, 90);
    EXPECT_EQ(one.entries[1].outcome, O::e_diverged);
    EXPECT_EQ(one.entries[1].firstBadFrame, 5);
    EXPECT_EQ(one.entries[3].outcome, O::e_corrupt);
    EXPECT_FALSE(one.entries[3].reason.empty());
    EXPECT_EQ(one.entries[4].outcome, O::e_corrupt);

    // The command: one line per replay in name order, the summary, exit code 1.
    std::string dirArg = dir.string();
    char cmd[] = "verify-dir", jobs[] = "--jobs", three[] = "3";
    char* argv[] = {cmd, dirArg.data(), jobs, three};
    ::testing::internal::CaptureStdout();
    const int rc = RunVerifyDir(4, argv, games);
    const std::string printed = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(rc, 1);
    EXPECT_EQ(printed.find("a_good.lbr: verified, 90 frames\nb_diverged.lbr: diverged at frame 5\n"), 0u) << printed;
    EXPECT_NE(printed.find("5 replays: 2 verified, 1 diverged, 2 corrupt\n"), std::string::npos) << printed;
    fs::remove_all(dir);
}

TEST(VerifyDir, RefusesAMissingDirectoryAndBadOptions) {
    const GameRegistry games = Games();
    VerifyDirReport report;
    std::string error;
    EXPECT_FALSE(VerifyDirectory("/nonexistent/lockbox", games, 2, {}, report, error));
    EXPECT_FALSE(error.empty());
    char cmd[] = "verify-dir", bogus[] = "--bogus";
    char* argv[] = {cmd, bogus};
    EXPECT_EQ(RunVerifyDir(2, argv, games), 2);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::replay
