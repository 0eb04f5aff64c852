// The scene library exported as b2dJson files (samples/scenes/files/<scene>.json, written by
// the saver): each loads to the C++-built scene's state hash, and is exactly what the saver
// writes for that scene today. LOCKBOX_REGENERATE_SCENE_FILES=1 rewrites them instead (after a
// deliberate change of a scene or of the saver's output).
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "SceneFileTestUtil.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::scenefile::test {
namespace {

bool Regenerating() {
    const char* v = std::getenv("LOCKBOX_REGENERATE_SCENE_FILES");
    return v != nullptr && std::string(v) == "1";
}

std::string LibraryFile(const std::string& name) { return SourcePath("samples/scenes/files/" + name + ".json"); }

class CommittedSceneFiles : public ::testing::TestWithParam<std::string> {};

TEST_P(CommittedSceneFiles, LoadToTheBuiltHashAndMatchTheSaver) {
    auto built = BuildLibraryScene(GetParam());
    ASSERT_TRUE(built);
    const b2World& world = built->engine.world();
    const std::string saved = SaveScene(world);
    const std::string path = LibraryFile(GetParam());
    if (Regenerating()) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out << saved;
        ASSERT_TRUE(out.good()) << path;
        GTEST_SKIP() << "regenerated " << path;
    }
    const std::string committed = ReadText(path);
    ASSERT_FALSE(committed.empty()) << path << " is missing (LOCKBOX_REGENERATE_SCENE_FILES=1 writes it)";
    SceneResult r;
    auto loaded = LoadSceneWorld(committed, &r);
    ASSERT_TRUE(loaded) << path << ": " << r.Describe();
    EXPECT_EQ(b2WorldHash(*loaded), b2WorldHash(world)) << path;
    EXPECT_TRUE(committed == saved) << path << " differs from what the saver writes for the scene now "
                                    << "(LOCKBOX_REGENERATE_SCENE_FILES=1 rewrites it)";
}

std::vector<std::string> LibraryNames() {
    std::vector<std::string> names;
    for (std::string_view n : scenes::AllSceneNames()) {
        if (scenes::MakeLockboxScene(n)) names.emplace_back(n);
    }
    return names;
}

INSTANTIATE_TEST_SUITE_P(Library, CommittedSceneFiles, ::testing::ValuesIn(LibraryNames()),
                         [](const auto& p) { return p.param; });

}  // namespace
}  // namespace lockbox::scenefile::test
