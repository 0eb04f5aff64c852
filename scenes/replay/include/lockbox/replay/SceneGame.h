#pragma once
/// A library scene as a replay game (`lockbox_replay record --scene`): each frame
/// runs the scene's own pre-step action, then every player's 8-byte input: an impulse on a
/// dynamic body, a box or circle spawned, or a spawned body destroyed. ScriptedInputs makes
/// such inputs from a seed, so any scene can make a replay with bodies coming and going.
///
/// A b2dJson scene file is a game too (`lockbox_replay record --scene-file`): its game name is
/// "scenefile:STEM" and META's game parameters carry the file's hash (SceneFileParams), so a
/// player given another file can refuse it. The replay itself needs no file: the seed snapshot
/// holds the world, and a scene file has no pre-step action.

#include <algorithm>
#include <iterator>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/common/Bytes.h"
#include "lockbox/lockbox.h"
#include "lockbox/replay/Game.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox/scenes/SceneFileScene.h"

namespace lockbox::replay {

/// userData of the bodies a SceneGame spawns (only these are destroyed by inputs).
inline constexpr uint64 kSpawnedBodyTag = 0x4C42525053504157ull;  // "LBRPSPAW"

/// Actions of a scene input (byte 0).
enum SceneAction : uint8 { e_actNone = 0, e_actImpulse = 1, e_actSpawnBox = 2, e_actSpawnCircle = 3, e_actDestroy = 4 };

/// One player's input for a scene game: 8 bytes on the wire.
struct SceneInput {
    uint8 action = e_actNone;  ///< SceneAction
    uint8 pick = 0;            ///< which body (index modulo the candidates, in body-list order)
    int16 a = 0;               ///< impulse x in 1/1024 N s, or spawn x in 1/64 m
    int16 b = 0;               ///< impulse y in 1/1024 N s, or spawn y in 1/64 m
    uint16 c = 0;              ///< spawn size selector (low 2 bits)

    static constexpr size_t kBytes = 8;
    void Encode(uint8* out) const noexcept {
        out[0] = action;
        out[1] = pick;
        out[2] = static_cast<uint8>(static_cast<uint16>(a));
        out[3] = static_cast<uint8>(static_cast<uint16>(a) >> 8);
        out[4] = static_cast<uint8>(static_cast<uint16>(b));
        out[5] = static_cast<uint8>(static_cast<uint16>(b) >> 8);
        out[6] = static_cast<uint8>(c);
        out[7] = static_cast<uint8>(c >> 8);
    }
    static SceneInput Decode(const uint8* in) noexcept {
        SceneInput s;
        s.action = in[0];
        s.pick = in[1];
        s.a = static_cast<int16>(static_cast<uint16>(in[2] | (in[3] << 8)));
        s.b = static_cast<int16>(static_cast<uint16>(in[4] | (in[5] << 8)));
        s.c = static_cast<uint16>(in[6] | (in[7] << 8));
        return s;
    }
};

/// The game-name prefix of a replay recorded on a scene file ("scenefile:level1").
inline constexpr std::string_view kSceneFileGamePrefix = "scenefile:";
/// The tag that opens the game parameters of such a replay, before the file's hash.
inline constexpr uint8 kSceneFileParamsTag[4] = {'S', 'F', 'H', '1'};

/// META game parameters of a replay recorded on a scene file: the tag "SFH1", then the file's
/// scenefile::SceneFileHash as 8 bytes, least significant first (12 bytes).
inline std::vector<uint8> SceneFileParams(uint64 fileHash) {
    std::vector<uint8> out(std::begin(kSceneFileParamsTag), std::end(kSceneFileParamsTag));
    bytes::Writer w(out);
    w.U64(fileHash);
    return out;
}

/// The scene-file hash a replay carries; false when the replay was not recorded on a scene file
/// (or its parameters are not in the SceneFileParams layout).
inline bool SceneFileHashOf(const ReplayFile& file, uint64& hash) {
    if (file.gameName.rfind(kSceneFileGamePrefix, 0) != 0) return false;
    bytes::Reader r(file.gameParams);
    const std::span<const uint8> tag = r.Bytes(4);
    const uint64 read = r.U64();
    if (!r.Ok() || !r.AtEnd() || !std::equal(tag.begin(), tag.end(), kSceneFileParamsTag)) return false;
    hash = read;
    return true;
}

/// A built scene driven by replay inputs.
class SceneGame : public Game {
public:
    /// Builds the scene (check ok()). The world switches follow the scene's defaults.
    explicit SceneGame(std::string_view sceneName) : SceneGame(scenes::MakeLockboxScene(sceneName)) {}
    /// The same for a scene made elsewhere (a scene file), recorded under `gameName` with
    /// `gameParams` ("scene:NAME" and none when the name is empty).
    explicit SceneGame(std::unique_ptr<scenes::LockboxScene> scene, std::string gameName = {},
                       std::vector<uint8> gameParams = {})
        : m_scene(std::move(scene)), m_gameName(std::move(gameName)), m_gameParams(std::move(gameParams)) {
        if (!m_scene) return;
        if (m_gameName.empty()) m_gameName = "scene:" + std::string(m_scene->Info().name);
        m_engine = std::make_unique<scenes::LockboxEngine>();
        scenes::ConfigureWorld(*m_engine, m_scene->Info(), scenes::RunSettings{});
        m_scene->Prepare(scenes::Resolve(m_scene->Info(), scenes::RunSettings{}));
        m_scene->Build(*m_engine);
    }
    /// A game for a scene file: "scenefile:STEM", the file's hash in the parameters.
    static std::unique_ptr<SceneGame> ForSceneFile(std::unique_ptr<scenes::SceneFileScene> scene) {
        if (!scene) return nullptr;
        std::string name = std::string(kSceneFileGamePrefix) + std::string(scene->Info().name);
        std::vector<uint8> params = SceneFileParams(scene->FileHash());
        return std::make_unique<SceneGame>(std::move(scene), std::move(name), std::move(params));
    }
    bool ok() const noexcept { return m_scene != nullptr; }
    b2World& world() noexcept { return m_engine->world(); }
    const scenes::SceneInfo& info() const noexcept { return m_scene->Info(); }

    /// The recorder settings of this scene with `players` players (game name "scene:NAME", or
    /// the name and parameters given at construction).
    RecorderConfig Config(uint16 players) const {
        RecorderConfig c;
        c.gameName = m_gameName;
        c.gameParams = m_gameParams;
        c.tickRate = static_cast<uint16>(info().hz);
        c.velocityIterations = static_cast<uint16>(info().velocityIterations);
        c.positionIterations = static_cast<uint16>(info().positionIterations);
        c.playerCount = players;
        c.inputBytes = static_cast<uint16>(SceneInput::kBytes);
        return c;
    }
    /// The scene name in a game name "scene:NAME" ("" when it is not a scene game).
    static std::string SceneName(const std::string& gameName) {
        return gameName.rfind("scene:", 0) == 0 ? gameName.substr(6) : std::string();
    }

    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        m_scene->BeforeStep(*m_engine, frame);
        for (size_t at = 0; at + SceneInput::kBytes <= inputs.size(); at += SceneInput::kBytes)
            ApplyOne(world, SceneInput::Decode(inputs.data() + at));
    }

private:
    static b2Body* Pick(b2World& world, uint8 pick, bool spawnedOnly) {
        int32 count = 0;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext())
            if (b->GetType() == b2_dynamicBody && (!spawnedOnly || b->GetUserData() == kSpawnedBodyTag)) ++count;
        if (count == 0) return nullptr;
        int32 index = pick % count;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
            if (b->GetType() != b2_dynamicBody || (spawnedOnly && b->GetUserData() != kSpawnedBodyTag)) continue;
            if (index-- == 0) return b;
        }
        return nullptr;
    }

    static void ApplyOne(b2World& world, const SceneInput& in) {
        switch (in.action) {
            case e_actImpulse: {
                if (b2Body* b = Pick(world, in.pick, false)) {
                    // 1/1024 N s steps: raw Q16.16 is 64 times the input.
                    const b2Vec2 impulse(Fixed::FromRaw(int32{in.a} * 64), Fixed::FromRaw(int32{in.b} * 64));
                    b->ApplyLinearImpulse(impulse, b->GetWorldCenter());
                }
                return;
            }
            case e_actSpawnBox:
            case e_actSpawnCircle: {
                b2BodyDef bd;
                bd.type = b2_dynamicBody;
                // 1/64 m steps: raw Q16.16 is 1024 times the input.
                bd.position = b2Vec2(Fixed::FromRaw(int32{in.a} * 1024), Fixed::FromRaw(int32{in.b} * 1024));
                bd.userData = kSpawnedBodyTag;
                b2Body* body = world.CreateBody(&bd);
                if (body == nullptr) return;
                // Half sizes 0.25, 0.375, 0.5, 0.625 m.
                const Fixed half = Fixed::FromRatio(2 + (in.c & 3), 8);
                b2FixtureDef fd;
                fd.density = 1;
                fd.friction = Fixed::FromRatio(6, 10);
                b2PolygonShape box;
                b2CircleShape circle;
                if (in.action == e_actSpawnBox) {
                    box.SetAsBox(half, half);
                    fd.shape = &box;
                } else {
                    circle.m_radius = half;
                    fd.shape = &circle;
                }
                body->CreateFixture(&fd);
                return;
            }
            case e_actDestroy:
                if (b2Body* b = Pick(world, in.pick, true)) world.DestroyBody(b);
                return;
            default: return;  // e_actNone, or an action this game does not know: no effect
        }
    }

    std::unique_ptr<scenes::LockboxScene> m_scene;
    std::string m_gameName;
    std::vector<uint8> m_gameParams;
    std::unique_ptr<scenes::LockboxEngine> m_engine;
};

/// Seeded random scene inputs: per player per frame 2.5% impulses, 0.6% boxes, 0.6% circles,
/// 0.4% destroys, otherwise nothing (SplitMix64; the same seed gives the same inputs anywhere).
class ScriptedInputs {
public:
    ScriptedInputs(uint64 seed, uint16 players) : m_state(seed), m_players(players) {}
    /// The next frame's inputs (players * 8 bytes).
    void Next(std::vector<uint8>& out) {
        out.assign(static_cast<size_t>(m_players) * SceneInput::kBytes, 0);
        for (uint16 p = 0; p < m_players; ++p) {
            SceneInput in;
            const uint64 roll = Rand() % 1000;
            if (roll < 25) {
                in.action = e_actImpulse;
                in.pick = static_cast<uint8>(Rand());
                in.a = static_cast<int16>(static_cast<int64_t>(Rand() % 8193) - 4096);  // +-4 N s
                in.b = static_cast<int16>(Rand() % 8193);                               // up to 8 N s
            } else if (roll < 37) {
                in.action = roll < 31 ? e_actSpawnBox : e_actSpawnCircle;
                in.a = static_cast<int16>(static_cast<int64_t>(Rand() % 1921) - 960);  // x in [-15, 15] m
                in.b = static_cast<int16>(640 + Rand() % 1281);                        // y in [10, 30] m
                in.c = static_cast<uint16>(Rand() & 3);
            } else if (roll < 41) {
                in.action = e_actDestroy;
                in.pick = static_cast<uint8>(Rand());
            }
            in.Encode(out.data() + static_cast<size_t>(p) * SceneInput::kBytes);
        }
    }

private:
    uint64 Rand() {
        uint64 z = (m_state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    uint64 m_state;
    uint16 m_players;
};

}  // namespace lockbox::replay
