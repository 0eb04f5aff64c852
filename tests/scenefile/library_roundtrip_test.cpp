// Every scene of the library round-trips through b2dJson: the world built from the saved text
// has the C++-built world's state hash (and keeps it for 20 steps), and saving the loaded
// world gives the same text again.
#include <gtest/gtest.h>

#include "SceneFileTestUtil.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::scenefile::test {
namespace {

class LibraryRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(LibraryRoundTrip, SameHashAndSameText) {
    auto built = BuildLibraryScene(GetParam());
    ASSERT_TRUE(built);
    b2World& original = built->engine.world();
    const std::string text = SaveScene(original);

    SceneResult r;
    auto loaded = LoadSceneWorld(text, &r);
    ASSERT_TRUE(loaded) << r.Describe();
    EXPECT_EQ(b2WorldHash(*loaded), b2WorldHash(original));
    EXPECT_EQ(SaveScene(*loaded), text);

    // Stepping shows nothing the hash missed. Heavy scenes are left out (seconds each), and
    // so are scenes whose behaviour is code beside the world: rain spawns bodies before its
    // steps, one_sided_platform disables contacts in a listener.
    if (built->scene->Info().heavy || GetParam() == "rain" || built->engine.onPreSolve) return;
    const Fixed dt = Fixed::FromRatio(1, built->run.hz);
    for (int i = 0; i < 20; ++i) {
        original.Step(dt, built->run.velocityIterations, built->run.positionIterations);
        loaded->Step(dt, built->run.velocityIterations, built->run.positionIterations);
    }
    EXPECT_EQ(b2WorldHash(*loaded), b2WorldHash(original)) << "after 20 steps";
}

std::vector<std::string> LibraryNames() {
    std::vector<std::string> names;
    for (std::string_view n : scenes::AllSceneNames()) {
        if (scenes::MakeLockboxScene(n)) names.emplace_back(n);
    }
    return names;
}

INSTANTIATE_TEST_SUITE_P(AllScenes, LibraryRoundTrip, ::testing::ValuesIn(LibraryNames()),
                         [](const auto& p) { return p.param; });

}  // namespace
}  // namespace lockbox::scenefile::test
