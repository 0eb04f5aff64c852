#pragma once
// Helpers for the replay tests: record a library scene with scripted inputs into memory, parse
// it, and play it back on a freshly built copy of the scene.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/replay/Player.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::replay::testing {

/// Recording options for RecordScene.
struct RecordOptions {
    int32 frames = 120;
    uint16 players = 2;
    uint64 seed = 1;
    uint32 keyframeInterval = 30;
    uint32 hashInterval = 1;
    bool stageHashes = false;
    int compressionLevel = 3;
};

/// Records a scene into memory; also returns the hash after every frame in `hashes`.
inline std::vector<uint8> RecordScene(std::string_view scene, const RecordOptions& o = {},
                                      std::vector<uint64>* hashes = nullptr) {
    SceneGame game(scene);
    EXPECT_TRUE(game.ok()) << scene;
    if (!game.ok()) return {};
    MemorySink sink;
    RecorderConfig config = game.Config(o.players);
    config.keyframeInterval = o.keyframeInterval;
    config.hashInterval = o.hashInterval;
    config.stageHashes = o.stageHashes;
    config.compressionLevel = o.compressionLevel;
    Recorder recorder(game.world(), game, sink, config);
    EXPECT_TRUE(recorder.Begin().ok());
    ScriptedInputs script(o.seed, o.players);
    std::vector<uint8> inputs;
    for (int32 f = 0; f < o.frames; ++f) {
        script.Next(inputs);
        recorder.Advance(inputs);
        if (hashes != nullptr) hashes->push_back(game.world().Hash());
    }
    EXPECT_TRUE(recorder.Finish().ok());
    return sink.bytes();
}

/// A parsed replay with a built scene and a player on it.
struct Playback {
    ReplayFile file;
    std::unique_ptr<SceneGame> game;
    std::unique_ptr<Player> player;
    Error error;

    explicit Playback(std::span<const uint8> bytes) {
        error = ParseReplay(bytes, file);
        if (!error.ok()) return;
        game = std::make_unique<SceneGame>(SceneGame::SceneName(file.gameName));
        player = std::make_unique<Player>(file, game->world(), *game);
    }
    /// After the file was edited in memory (tests that tamper with it).
    void Rebind() { player = std::make_unique<Player>(file, game->world(), *game); }
};

/// Nudges the first dynamic body's x velocity (or the one with `bodyId`) by one raw unit at
/// one frame and stage: a fault the size of one rounding difference.
class NudgeHook : public StageHook {
public:
    NudgeHook(int32 frame, uint32 stage, int32 bodyId = -1) : m_frame(frame), m_stage(stage), m_bodyId(bodyId) {}
    void OnStage(int32 frame, uint32 stage, b2World& world) override {
        if (frame != m_frame || stage != m_stage) return;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
            if (b->GetType() != b2_dynamicBody || (m_bodyId >= 0 && b->GetId() != m_bodyId)) continue;
            b->SetLinearVelocity(b->GetLinearVelocity() + b2Vec2(Fixed::FromRaw(1), Fixed()));
            touched = b->GetId();
            return;
        }
    }
    int32 touched = -1;  ///< id of the body nudged (-1: not yet)

private:
    int32 m_frame;
    uint32 m_stage;
    int32 m_bodyId;
};

}  // namespace lockbox::replay::testing
