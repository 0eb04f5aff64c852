#pragma once
/// The testbed's scenes as replay games.
///
/// TestbedGame runs any catalog scene (library or testbed-only) the way the recorder and the
/// player expect: Apply runs the scene's own pre-step action for the frame and nothing else,
/// because the testbed records no inputs (every input is zero, "no action"). With zero inputs
/// this is exactly what replay::SceneGame does, so a library scene recorded here is named
/// "scene:NAME" and lockbox_replay verifies it; a scene file is "scenefile:STEM" with the file's
/// hash in the game parameters (lockbox_replay verifies it too); a testbed-only scene is
/// "testbed:NAME" and only the testbed can play it.

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/replay/Game.h"
#include "lockbox/scenes/LockboxScenes.h"

namespace lockbox::testbed {

/// A built catalog scene driven through the WorldGame interface.
class TestbedGame : public WorldGame {
public:
    /// Builds scene `name` with the world switches and step settings of `settings` (check ok()).
    TestbedGame(std::string_view name, const scenes::RunSettings& settings);

    /// False when the name is unknown.
    bool ok() const noexcept { return scene_ != nullptr; }
    /// The scene's world (valid when ok()).
    b2World& world() noexcept { return engine_->world(); }
    /// The scene's defaults.
    const scenes::SceneInfo& info() const noexcept { return scene_->Info(); }
    /// The scene (valid when ok()).
    const scenes::LockboxScene& scene() const noexcept { return *scene_; }
    /// The game name a replay of this scene carries ("scene:NAME", "scenefile:STEM" or
    /// "testbed:NAME").
    std::string GameName() const;
    /// The game parameters a replay of this scene carries (a scene file's hash; else none).
    std::vector<uint8> GameParams() const;

    /// The scene's pre-step action for `frame`; inputs are ignored (the testbed records none).
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override;

private:
    std::unique_ptr<scenes::LockboxScene> scene_;
    std::unique_ptr<scenes::LockboxEngine> engine_;
};

/// A game able to play a replay with this game name, with its world: replay::SceneGame for
/// "scene:NAME" (inputs mean what lockbox_replay recorded) and for "scenefile:STEM" (played from
/// the replay's seed: no file needed), TestbedGame for "testbed:NAME".
struct ReplayGame {
    std::unique_ptr<WorldGame> game;  ///< nullptr when the name is not playable here
    b2World* world = nullptr;         ///< the game's world
};

/// Builds the game for a replay's game name (see ReplayGame).
ReplayGame MakeReplayGame(const std::string& gameName);

}  // namespace lockbox::testbed
