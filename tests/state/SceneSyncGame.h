#pragma once
// A library scene as a WorldGame: each frame runs the scene's pre-step action, and the tool
// steps once with the scene's settings (Step()). Scenes keep no state outside the world that a later frame
// reads, so there is no user state to save.

#include <string_view>
#include <vector>

#include "StateTestUtil.h"
#include "lockbox/state/SyncTest.h"

namespace lockbox::testing_state {

class SceneSyncGame : public WorldGame {
public:
    explicit SceneSyncGame(SceneRun& run) : run_(run) {}
    void Apply(b2World&, int32 frame, std::span<const uint8>) override { run_.scene->BeforeStep(*run_.engine, frame); }
    /// The scene's step settings.
    WorldStepSettings Step() const {
        const auto& info = run_.scene->Info();
        return {static_cast<uint32>(info.hz), static_cast<uint32>(info.velocityIterations),
                static_cast<uint32>(info.positionIterations)};
    }

private:
    SceneRun& run_;
};

/// The scenes the sync tests treat as heavy (120 frames, rollback windows tiling the run):
/// the four largest (large_pyramid, many_pyramids, joint_grid, rain) plus tumbler, whose
/// 2000 bodies cost as much per step as rain's.
inline bool IsLargeScene(const scenes::LockboxScene& scene) {
    const auto name = scene.Info().name;
    return scene.Info().heavy || name == "rain" || name == "joint_grid" || name == "tumbler";
}

/// The library scenes on one side of IsLargeScene, in library order.
inline std::vector<std::string_view> SceneNames(bool large) {
    std::vector<std::string_view> names;
    for (auto name : scenes::AllSceneNames()) {
        auto scene = scenes::MakeLockboxScene(name);
        if (scene && IsLargeScene(*scene) == large) names.push_back(name);
    }
    return names;
}

/// Runs the sync test on a freshly built scene; returns its result. stride as in
/// SyncTestConfig.
inline SyncTestResult RunSceneSyncTest(std::string_view name, int32 frames, bool mispredict, int32 stride = 1,
                                       bool useFrames = false) {
    SceneRun run(name);
    if (!run.scene) {
        SyncTestResult missing;
        missing.ok = false;
        missing.message = "no such scene";
        return missing;
    }
    SceneSyncGame game(run);
    SyncTestConfig config;
    config.mispredict = mispredict;
    config.stride = stride;
    config.frames = useFrames;
    config.step = game.Step();
    SyncTest test(run.world(), game, {}, config);
    return test.Run(frames);
}

}  // namespace lockbox::testing_state
