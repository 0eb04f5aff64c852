// Catalog scenes as replay games, and the game factory for loaded replays.
#include "TestbedGame.h"

#include "SceneCatalog.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::testbed {

namespace {
constexpr std::string_view kTestbedPrefix = "testbed:";
}

TestbedGame::TestbedGame(std::string_view name, const scenes::RunSettings& settings) : scene_(MakeCatalogScene(name)) {
    if (!scene_) return;
    engine_ = std::make_unique<scenes::LockboxEngine>();
    // The same order as scenes::RunScene: switches, resolved settings, then the bodies.
    scenes::ConfigureWorld(*engine_, scene_->Info(), settings);
    scene_->Prepare(scenes::Resolve(scene_->Info(), settings));
    scene_->Build(*engine_);
}

std::string TestbedGame::GameName() const {
    const std::string name(info().name);
    if (dynamic_cast<const scenes::SceneFileScene*>(scene_.get())) {
        return std::string(replay::kSceneFileGamePrefix) + name;
    }
    return IsLibraryScene(name) ? "scene:" + name : std::string(kTestbedPrefix) + name;
}

std::vector<uint8> TestbedGame::GameParams() const {
    if (const auto* file = dynamic_cast<const scenes::SceneFileScene*>(scene_.get())) {
        return replay::SceneFileParams(file->FileHash());
    }
    return {};
}

void TestbedGame::Apply(b2World& world, int32 frame, std::span<const uint8> inputs) {
    (void)world;
    (void)inputs;
    scene_->BeforeStep(*engine_, frame);
}

ReplayGame MakeReplayGame(const std::string& gameName) {
    ReplayGame out;
    if (gameName.rfind(replay::kSceneFileGamePrefix, 0) == 0) {
        // The seed snapshot holds the world: an empty scene file gives the game.
        auto game = replay::SceneGame::ForSceneFile(
            scenes::SceneFileScene::FromText(gameName.substr(replay::kSceneFileGamePrefix.size()), "{}", nullptr));
        if (!game || !game->ok()) return out;
        out.world = &game->world();
        out.game = std::move(game);
        return out;
    }
    const std::string sceneName = replay::SceneGame::SceneName(gameName);
    if (!sceneName.empty()) {
        auto game = std::make_unique<replay::SceneGame>(sceneName);
        if (!game->ok()) return out;
        out.world = &game->world();
        out.game = std::move(game);
        return out;
    }
    if (gameName.rfind(kTestbedPrefix, 0) == 0) {
        auto game = std::make_unique<TestbedGame>(gameName.substr(kTestbedPrefix.size()), scenes::RunSettings{});
        if (!game->ok()) return out;
        out.world = &game->world();
        out.game = std::move(game);
    }
    return out;
}

}  // namespace lockbox::testbed
