#pragma once
// Golden scene hashes shared by tests/scenes/golden_hash_test.cpp (GoogleTest) and the
// standalone cross-build driver (tests/cross/cross_driver.cpp): which scenes and steps are
// recorded, how a scene is run for them, and the line format of tests/golden/hashes.txt:
//   <scene> step1=0x<16 hex> step60=0x<16 hex> step600=0x<16 hex>
// (step120 instead of step600 for the heavy scenes). Lines starting with '#' are comments.
// Besides the scene library, the hand-written scene files (scenes/files/handmade) are
// recorded as `file/<name>`: loaded with the scene-file loader, stepped at their own settings.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/scenefile/SceneFile.h"
#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::golden {

/// One scene's recorded steps.
struct ScenePlan {
    std::string name;
    std::vector<int> steps;  ///< ascending step counts after which the hash is recorded
    bool heavy = false;      ///< one of the four heavy SCENES.md scenes
};

/// True for large_pyramid, many_pyramids, joint_grid and rain (recorded at 1, 60, 120).
inline bool IsHeavyScene(std::string_view name) {
    return name == "large_pyramid" || name == "many_pyramids" || name == "joint_grid" || name == "rain";
}

/// The hand-written scene files recorded as `file/<name>` (scenes/files/handmade).
inline const std::vector<std::string>& GoldenSceneFiles() {
    static const std::vector<std::string> kFiles{"bodies", "shapes", "joints", "rube_bridge"};
    return kFiles;
}

/// The folder holding those files; the golden test and the cross driver set it.
inline std::string& SceneFileDir() {
    static std::string dir;
    return dir;
}

/// Every scene of the library (registry order) that lockbox can build, with its steps, then
/// the scene files.
inline std::vector<ScenePlan> GoldenPlan() {
    std::vector<ScenePlan> plan;
    for (std::string_view name : scenes::AllSceneNames()) {
        if (!scenes::MakeLockboxScene(name)) continue;
        const bool heavy = IsHeavyScene(name);
        plan.push_back({std::string(name), heavy ? std::vector<int>{1, 60, 120} : std::vector<int>{1, 60, 600}, heavy});
    }
    for (const std::string& file : GoldenSceneFiles()) plan.push_back({"file/" + file, {1, 60, 600}, false});
    return plan;
}

/// Called on a scene's fresh world before anything is built in it (worker settings, ...).
using WorldSetup = std::function<void(b2World&)>;

/// Loads scene file `file/<name>` into a new world and returns b2WorldHash after each step count
/// in `steps`, stepping at the file's rate and iterations. Empty when the file cannot be loaded.
inline std::vector<uint64_t> RunSceneFileHashes(const std::string& name, const std::vector<int>& steps,
                                                const WorldSetup& setup = nullptr) {
    std::vector<uint64_t> out;
    std::string bytes;
    if (!scenefile::ReadSceneFileBytes(SceneFileDir() + "/" + name + ".json", bytes)) return out;
    scenefile::SceneMetadata meta;
    auto world = scenefile::LoadSceneWorld(bytes, nullptr, &meta);
    if (!world || steps.empty()) return out;
    if (setup) setup(*world);
    const Fixed dt = meta.step.TimeStep();
    size_t next = 0;
    for (int i = 0; i < steps.back() && next < steps.size(); ++i) {
        world->Step(dt, meta.step.VelocityIterationsOr(), meta.step.PositionIterationsOr());
        if (i + 1 == steps[next]) {
            out.push_back(b2WorldHash(*world));
            ++next;
        }
    }
    return out;
}

/// Runs the scene from a fresh world with its default settings (as RunScene does, without
/// metrics) and returns b2WorldHash after each step count in `steps`. `setup`, when given, is
/// called on the world before the scene builds it.
inline std::vector<uint64_t> RunSceneHashes(std::string_view name, const std::vector<int>& steps,
                                            const WorldSetup& setup = nullptr) {
    if (name.substr(0, 5) == "file/") return RunSceneFileHashes(std::string(name.substr(5)), steps, setup);
    std::vector<uint64_t> out;
    auto scene = scenes::MakeLockboxScene(name);
    if (!scene || steps.empty()) return out;
    scenes::LockboxEngine e;
    scenes::RunSettings s;
    s.steps = steps.back();
    s.trackMetrics = false;
    const scenes::Resolved r = scenes::Resolve(scene->Info(), s);
    scenes::ConfigureWorld(e, scene->Info(), s);
    if (setup) setup(e.world());
    scene->Prepare(r);
    scene->Build(e);
    size_t next = 0;
    for (int i = 0; i < r.steps && next < steps.size(); ++i) {
        scene->BeforeStep(e, i);
        e.Step(r.hz, r.velocityIterations, r.positionIterations);
        if (i + 1 == steps[next]) {
            out.push_back(b2WorldHash(e.world()));
            ++next;
        }
    }
    return out;
}

/// The golden-file line of one scene.
inline std::string FormatLine(const ScenePlan& p, const std::vector<uint64_t>& hashes) {
    std::string line = p.name;
    for (size_t i = 0; i < p.steps.size() && i < hashes.size(); ++i) {
        char buf[64];
        std::snprintf(buf, sizeof buf, " step%d=0x%016llx", p.steps[i], static_cast<unsigned long long>(hashes[i]));
        line += buf;
    }
    return line;
}

/// The golden file as scene name -> whole line (comments and blank lines skipped). Empty
/// when the file cannot be read.
inline std::map<std::string, std::string> ReadGolden(const std::string& path) {
    std::map<std::string, std::string> lines;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#') continue;
        std::istringstream words(line);
        std::string name;
        words >> name;
        lines[name] = line;
    }
    return lines;
}

/// Runs scene `p` up to the recorded steps <= maxStep and compares with its golden line (a
/// shortened run must match the golden line's leading fields). Returns the computed line in
/// *computed. `setup` as in RunSceneHashes.
inline bool MatchesGolden(ScenePlan p, int maxStep, const std::string& goldenLine, std::string* computed,
                          const WorldSetup& setup = nullptr) {
    const size_t full = p.steps.size();
    while (!p.steps.empty() && p.steps.back() > maxStep) p.steps.pop_back();
    *computed = FormatLine(p, RunSceneHashes(p.name, p.steps, setup));
    if (p.steps.size() == full) return goldenLine == *computed;
    return goldenLine.compare(0, computed->size() + 1, *computed + " ") == 0;
}

/// `relative` resolved against the directory of `sourceFile` (pass __FILE__).
inline std::string GoldenPathFrom(const std::string& sourceFile, const char* relative) {
    const size_t slash = sourceFile.find_last_of("/\\");
    const std::string dir = slash == std::string::npos ? std::string(".") : sourceFile.substr(0, slash);
    return dir + relative;
}

/// True when LOCKBOX_REGENERATE_GOLDEN=1: the golden test rewrites the file.
inline bool Regenerating() {
    const char* v = std::getenv("LOCKBOX_REGENERATE_GOLDEN");
    return v != nullptr && std::string(v) == "1";
}

/// Header comment of the golden file.
inline std::string GoldenHeader() {
    return "# Golden b2WorldHash values (hash definition version " + std::to_string(b2_hashVersion) +
           ", docs/determinism.md) of every scene\n"
           "# after the listed step counts: light scenes 1/60/600, heavy scenes 1/60/120.\n"
           "# Regenerate: LOCKBOX_REGENERATE_GOLDEN=1 ./lockbox_scenes_tests --gtest_filter='GoldenHash*'\n";
}

}  // namespace lockbox::golden
