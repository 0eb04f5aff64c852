#pragma once
// Helpers shared by the scene-file tests: a library scene built the way the golden-hash test
// builds it (ConfigureWorld, then Build, no step), and the paths of the committed files.
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/scenefile/SceneFile.h"
#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::scenefile::test {

/// A library scene built into a fresh world with its default settings, not stepped.
struct BuiltScene {
    scenes::LockboxEngine engine;
    std::unique_ptr<scenes::LockboxScene> scene;
    scenes::Resolved run{};
};

inline std::unique_ptr<BuiltScene> BuildLibraryScene(std::string_view name) {
    auto out = std::make_unique<BuiltScene>();
    out->scene = scenes::MakeLockboxScene(name);
    if (!out->scene) return nullptr;
    scenes::RunSettings s;
    s.trackMetrics = false;
    out->run = scenes::Resolve(out->scene->Info(), s);
    scenes::ConfigureWorld(out->engine, out->scene->Info(), s);
    out->scene->Prepare(out->run);
    out->scene->Build(out->engine);
    return out;
}

/// `relative` against the source tree's root (LOCKBOX_SOURCE_DIR, set by tests/CMakeLists.txt:
/// __FILE__ may be relative to the build folder, e.g. under ccache).
inline std::string SourcePath(const std::string& relative) { return std::string(LOCKBOX_SOURCE_DIR) + "/" + relative; }

/// `relative` against this suite's folder (tests/scenefile).
inline std::string TestPath(const std::string& relative) { return SourcePath("tests/scenefile/" + relative); }

/// Reads a whole file ("" when it cannot be read).
inline std::string ReadText(const std::string& path) {
    std::string bytes;
    if (!ReadSceneFileBytes(path, bytes)) return {};
    return bytes;
}

/// The library scenes lockbox builds: the light ones, or the heavy ones (seconds each under the
/// sanitizers: their tests carry the `heavy` label).
inline std::vector<std::string> LibraryNames(bool heavy) {
    std::vector<std::string> names;
    for (std::string_view n : scenes::AllSceneNames()) {
        auto scene = scenes::MakeLockboxScene(n);
        if (scene && scene->Info().heavy == heavy) names.emplace_back(n);
    }
    return names;
}

/// Saves a library scene, loads the text into a new world and checks the state hash and the
/// text of a second save; then, for scenes small enough, 20 steps of both worlds.
inline void CheckLibraryRoundTrip(const std::string& name) {
    auto built = BuildLibraryScene(name);
    ASSERT_TRUE(built);
    b2World& original = built->engine.world();
    const std::string text = SaveScene(original);

    SceneResult r;
    auto loaded = LoadSceneWorld(text, &r);
    ASSERT_TRUE(loaded) << r.Describe();
    EXPECT_EQ(b2WorldHash(*loaded), b2WorldHash(original));
    EXPECT_EQ(SaveScene(*loaded), text);

    // Stepping shows nothing the hash missed; it is left out for large scenes (seconds under the
    // sanitizers) and for scenes whose behaviour is code beside the world: rain spawns bodies
    // before its steps, one_sided_platform disables contacts in a listener.
    if (original.GetBodyCount() > 300 || name == "rain" || built->engine.onPreSolve) return;
    const Fixed dt = Fixed::FromRatio(1, built->run.hz);
    for (int i = 0; i < 20; ++i) {
        original.Step(dt, built->run.velocityIterations, built->run.positionIterations);
        loaded->Step(dt, built->run.velocityIterations, built->run.positionIterations);
    }
    EXPECT_EQ(b2WorldHash(*loaded), b2WorldHash(original)) << "after 20 steps";
}

/// scenes/files/<name>.json, the library scene exported by the saver.
inline std::string LibraryFile(const std::string& name) { return SourcePath("scenes/files/" + name + ".json"); }

/// True when LOCKBOX_REGENERATE_SCENE_FILES=1: the committed-file tests rewrite the files.
inline bool RegeneratingSceneFiles() {
    const char* v = std::getenv("LOCKBOX_REGENERATE_SCENE_FILES");
    return v != nullptr && std::string(v) == "1";
}

/// The committed export of a library scene loads to the C++-built scene's hash and is exactly
/// what the saver writes for it today (or, when regenerating, is rewritten).
inline void CheckCommittedFile(const std::string& name) {
    auto built = BuildLibraryScene(name);
    ASSERT_TRUE(built);
    const b2World& world = built->engine.world();
    const std::string saved = SaveScene(world);
    const std::string path = LibraryFile(name);
    if (RegeneratingSceneFiles()) {
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

}  // namespace lockbox::scenefile::test
