#pragma once
// Helpers shared by the scene-file tests: a library scene built the way the golden-hash test
// builds it (ConfigureWorld, then Build, no step), and the paths of the committed files.
#include <memory>
#include <string>
#include <string_view>

#include "lockbox/scenefile/SceneFile.h"
#include "lockbox/scenes/LockboxScenes.h"

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

}  // namespace lockbox::scenefile::test
