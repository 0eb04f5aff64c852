// lockbox_replay: record, inspect, verify, compare and bisect replay files (docs/replay.md).
// The commands other than record are the library call RunTool (lockbox/replay/Tool.h) with the
// library scenes and scene files registered, as a game's own tool registers its game.
// Exit codes: 0 success (verify: all hashes match; diff: no difference), 1 a divergence or
// difference was found, 2 a usage error or a file that cannot be read.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"
#include "lockbox/replay/Tool.h"
#include "lockbox/replay/VerifyDir.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox;
using namespace lockbox::replay;

namespace {

constexpr const char* kRecordUsage =
    "record (--scene NAME | --scene-file FILE.json) --out FILE [--frames N] [--players P]\n"
    "                        [--seed S] [--keyframe-interval K] [--hash-interval H] [--stage-hashes] [--level L]";
constexpr const char* kSceneFileOption = "--scene-file";

std::string Hex(uint64 v) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// A scene game as the tool plays it.
class SceneToolGame : public ToolGame {
public:
    explicit SceneToolGame(std::unique_ptr<SceneGame> game) : m_game(std::move(game)) {}
    b2World& World() override { return m_game->world(); }
    Game& Logic() override { return *m_game; }

private:
    std::unique_ptr<SceneGame> m_game;
};

// The game of a replay recorded on a scene file. With --scene-file given it must be the file
// the replay carries the hash of; without it the replay plays from its seed snapshot alone (the
// seed holds the world, and a scene file has no pre-step action), on an empty scene.
std::unique_ptr<ToolGame> OpenSceneFileGame(const ToolGameRequest& request, std::string& error) {
    const ReplayFile& file = request.file;
    uint64 recorded = 0;
    if (!SceneFileHashOf(file, recorded)) {
        error = request.path + ": game \"" + file.gameName + "\" carries no scene-file hash";
        return nullptr;
    }
    const std::string stem = file.gameName.substr(kSceneFileGamePrefix.size());
    const auto given = request.options.find(kSceneFileOption);
    std::unique_ptr<scenes::SceneFileScene> scene;
    if (given == request.options.end()) {
        scene = scenes::SceneFileScene::FromText(stem, "{}", nullptr);
    } else {
        const std::string& sceneFile = given->second;
        scenefile::SceneResult result;
        scene = scenes::SceneFileScene::Open(sceneFile, &result);
        if (!scene) {
            error = sceneFile + ": " + result.Describe();
            return nullptr;
        }
        if (scene->FileHash() != recorded) {
            error = request.path + " was recorded on scene file \"" + stem + "\" with hash " + Hex(recorded) + "; " +
                    sceneFile + " has hash " + Hex(scene->FileHash()) + ": not the same file";
            return nullptr;
        }
    }
    std::unique_ptr<SceneGame> game = SceneGame::ForSceneFile(std::move(scene));
    if (!game || !game->ok()) return nullptr;
    return std::make_unique<SceneToolGame>(std::move(game));
}

// The game of a replay recorded on a library scene ("scene:NAME").
std::unique_ptr<ToolGame> OpenSceneGame(const ToolGameRequest& request, std::string& error) {
    const ReplayFile& file = request.file;
    if (request.options.count(kSceneFileOption) != 0) {
        error = request.path + " was not recorded on a scene file (game \"" + file.gameName + "\")";
        return nullptr;
    }
    const std::string scene = SceneGame::SceneName(file.gameName);
    auto game = std::make_unique<SceneGame>(scene);
    if (scene.empty() || !game->ok()) {
        error = request.path + ": game \"" + file.gameName + "\" is not a scene this tool knows";
        return nullptr;
    }
    return std::make_unique<SceneToolGame>(std::move(game));
}

int Record(int argc, char** argv) {
    cli::OptionReader args("lockbox_replay", argc, argv);
    std::string scene, sceneFile, out;
    long frames = 600, players = 2, keyframe = 600, hashInterval = 1, level = 3;
    uint64_t seed = 1;
    bool stageHashes = false;
    while (args.Next()) {
        if (args.Is("--scene"))
            args.Text(scene);
        else if (args.Is("--scene-file"))
            args.Text(sceneFile);
        else if (args.Is("--out"))
            args.Text(out);
        else if (args.Is("--frames"))
            args.Int(0, 100000000, frames);
        else if (args.Is("--players"))
            args.Int(1, 64, players);
        else if (args.Is("--seed"))
            args.Uint64(seed);
        else if (args.Is("--keyframe-interval"))
            args.Int(0, 100000000, keyframe);
        else if (args.Is("--hash-interval"))
            args.Int(1, 100000000, hashInterval);
        else if (args.Is("--level"))
            args.Int(-7, 22, level);
        else if (args.Is("--stage-hashes"))
            stageHashes = true;
        else
            args.Unknown();
    }
    if (!args.Failed() && scene.empty() == sceneFile.empty())
        args.Refuse("record needs one of --scene and --scene-file");
    if (!args.Failed() && out.empty()) args.Refuse("record needs --out FILE");
    if (args.Failed()) return args.Fail((std::string("usage: lockbox_replay ") + kRecordUsage + "\n").c_str());
    std::unique_ptr<SceneGame> made;
    if (!sceneFile.empty()) {
        scenefile::SceneResult error;
        made = SceneGame::ForSceneFile(scenes::SceneFileScene::Open(sceneFile, &error));
        if (!made) {
            std::fprintf(stderr, "%s: %s\n", sceneFile.c_str(), error.Describe().c_str());
            return 2;
        }
        scene = std::string(made->info().name);
    } else {
        made = std::make_unique<SceneGame>(scene);
        if (!made->ok()) {
            std::fprintf(stderr, "unknown scene %s\n", scene.c_str());
            return 2;
        }
    }
    SceneGame& game = *made;
    FileSink sink(out);
    if (!sink.ok()) {
        std::fprintf(stderr, "cannot create %s\n", out.c_str());
        return 2;
    }
    RecorderConfig config = game.Config(static_cast<uint16>(players));
    config.keyframeInterval = static_cast<uint32>(keyframe);
    config.hashInterval = static_cast<uint32>(hashInterval);
    config.stageHashes = stageHashes;
    config.compressionLevel = static_cast<int>(level);
    Recorder recorder(game.world(), game, sink, config);
    recorder.Begin();
    ScriptedInputs script(seed, static_cast<uint16>(players));
    std::vector<uint8> inputs;
    for (long f = 0; f < frames; ++f) {
        script.Next(inputs);
        recorder.Advance(inputs);
    }
    Error e = recorder.Finish();
    if (e.ok() && !sink.Close()) e.code = ErrorCode::e_io;
    if (!e.ok()) {
        std::fprintf(stderr, "write failed: %s\n", e.Describe().c_str());
        return 2;
    }
    std::printf("recorded %s: %s=%s frames=%ld players=%ld hash=%s\n", out.c_str(),
                sceneFile.empty() ? "scene" : "scene-file", scene.c_str(), frames, players,
                Hex(game.world().Hash()).c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    GameRegistry games;
    games.AddCommand("record", kRecordUsage, Record);
    games.AddCommand("verify-dir", kVerifyDirUsage, [&games](int commandArgc, char** commandArgv) {
        return RunVerifyDir(commandArgc, commandArgv, games, "lockbox_replay");
    });
    games.AddPrefix("scene:", OpenSceneGame);
    games.AddPrefix(std::string(kSceneFileGamePrefix), OpenSceneFileGame);
    games.AddOption(kSceneFileOption, "FILE.json");
    games.AddInfo([](const ReplayFile& file) -> std::string {
        uint64 fileHash = 0;
        if (!SceneFileHashOf(file, fileHash)) return {};
        return "scene file     hash " + Hex(fileHash) + " (give the file with --scene-file to check it)\n";
    });
    return RunTool(argc, argv, games, "lockbox_replay");
}
