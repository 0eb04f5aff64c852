// lockbox_replay: record, inspect, verify, compare and bisect replay files (docs/replay.md).
// Exit codes: 0 success (verify: all hashes match; diff: no difference), 1 a divergence or
// difference was found, 2 a usage error or a file that cannot be read.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/replay/Bisect.h"
#include "lockbox/replay/Diff.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox;
using namespace lockbox::replay;

namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  lockbox_replay record (--scene NAME | --scene-file FILE.json) --out FILE [--frames N] [--players P]\n"
    "                        [--seed S] [--keyframe-interval K] [--hash-interval H] [--stage-hashes] [--level L]\n"
    "  lockbox_replay info FILE\n"
    "  lockbox_replay verify FILE [--scene-file FILE.json]\n"
    "  lockbox_replay diff A B [--scene-file FILE.json]\n"
    "  lockbox_replay bisect FILE [--inject FRAME:STAGE] [--scene-file FILE.json]\n"
    "      (STAGE 0..4: inputs collide solve broadphase toi; --scene-file: the scene file a replay\n"
    "       was recorded on, refused when it is not that file; without it the seed is enough)\n";

std::string Hex(uint64 v) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// The game of a replay recorded on a scene file. With `sceneFile` given it must be the file the
// replay carries the hash of; without it the replay plays from its seed snapshot alone (the
// seed holds the world, and a scene file has no pre-step action), on an empty scene.
bool OpenSceneFileGame(const char* path, const std::string& sceneFile, const ReplayFile& file, uint64 recorded,
                       std::unique_ptr<SceneGame>& game) {
    const std::string stem = file.gameName.substr(kSceneFileGamePrefix.size());
    std::unique_ptr<scenes::SceneFileScene> scene;
    if (sceneFile.empty()) {
        scene = scenes::SceneFileScene::FromText(stem, "{}", nullptr);
    } else {
        scenefile::SceneResult error;
        scene = scenes::SceneFileScene::Open(sceneFile, &error);
        if (!scene) {
            std::printf("%s: %s\n", sceneFile.c_str(), error.Describe().c_str());
            return false;
        }
        if (scene->FileHash() != recorded) {
            std::printf("%s was recorded on scene file \"%s\" with hash %s; %s has hash %s: not the same file\n", path,
                        stem.c_str(), Hex(recorded).c_str(), sceneFile.c_str(), Hex(scene->FileHash()).c_str());
            return false;
        }
    }
    game = SceneGame::ForSceneFile(std::move(scene));
    return game && game->ok();
}

// Parses a file and builds its scene game; prints the error and returns false on failure.
bool Open(const char* path, ReplayFile& file, std::unique_ptr<SceneGame>& game, const std::string& sceneFile = {}) {
    if (Error e = LoadReplay(path, file)) {
        std::printf("%s: %s\n", path, e.Describe().c_str());
        return false;
    }
    uint64 recorded = 0;
    if (SceneFileHashOf(file, recorded)) return OpenSceneFileGame(path, sceneFile, file, recorded, game);
    if (!sceneFile.empty()) {
        std::printf("%s was not recorded on a scene file (game \"%s\")\n", path, file.gameName.c_str());
        return false;
    }
    const std::string scene = SceneGame::SceneName(file.gameName);
    game = std::make_unique<SceneGame>(scene);
    if (scene.empty() || !game->ok()) {
        std::printf("%s: game \"%s\" is not a scene this tool knows\n", path, file.gameName.c_str());
        return false;
    }
    return true;
}

int Record(cli::OptionReader& args) {
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
    if (args.Failed()) return args.Fail(kUsage);
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

int Info(const char* path) {
    ReplayFile f;
    if (Error e = LoadReplay(path, f)) {
        std::printf("%s: %s\n", path, e.Describe().c_str());
        return 2;
    }
    const Header& h = f.header;
    std::printf("file           %s (%llu bytes)\n", path, static_cast<unsigned long long>(f.fileBytes));
    std::printf("format         %u, engine %u.%u.%u, determinism 0x%08x, snapshot format %u\n", h.formatVersion,
                h.engineMajor, h.engineMinor, h.enginePatch, h.determinismVersion, h.snapshotFormatVersion);
    std::printf("game           %s\n", f.gameName.c_str());
    if (uint64 fileHash = 0; SceneFileHashOf(f, fileHash))
        std::printf("scene file     hash %s (give the file with --scene-file to check it)\n", Hex(fileHash).c_str());
    std::printf("tick rate      %u Hz (dt raw %d), iterations %u/%u, world flags 0x%x\n", h.tickRate, h.timeStepRaw,
                h.velocityIterations, h.positionIterations, h.worldFlags);
    std::printf("players        %u x %u input bytes\n", h.playerCount, h.inputBytes);
    std::printf("frames         %d (%.2f s)\n", f.frameCount, static_cast<double>(f.frameCount) / h.tickRate);
    std::printf("hashes         every %u frame(s)%s\n", h.hashInterval,
                f.stageHashes.empty() ? "" : ", with fencepost hashes");
    std::printf("keyframes      %zu (interval %u)\n", f.keyframes.size(), h.keyframeInterval);
    std::printf("seed hash      %s\nfinal hash     %s\n", Hex(f.seed.hash).c_str(), Hex(f.finalHash).c_str());
    std::printf("chunks         type  count      stored         raw\n");
    for (const ChunkStat& s : f.chunkStats)
        std::printf("               %s %6u %11llu %11llu\n", ChunkTagName(s.type).c_str(), s.count,
                    static_cast<unsigned long long>(s.storedBytes), static_cast<unsigned long long>(s.rawBytes));
    if (f.unknownChunks != 0) std::printf("unknown chunks %u (skipped)\n", f.unknownChunks);
    if (f.frameCount > 0) {
        const double seconds = static_cast<double>(f.frameCount) / h.tickRate;
        std::printf("input stream   %.0f bytes/s raw (%zu bytes/frame)\n",
                    static_cast<double>(f.inputs.size()) / seconds, f.FrameInputBytes());
    }
    return 0;
}

int Verify(const char* path, const std::string& sceneFile) {
    ReplayFile file;
    std::unique_ptr<SceneGame> game;
    if (!Open(path, file, game, sceneFile)) return 2;
    Player player(file, game->world(), *game);
    const auto t0 = std::chrono::steady_clock::now();
    const VerifyResult r = player.Verify();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r.error.ok()) {
        std::printf("%s: %s\n", path, r.error.Describe().c_str());
        return 2;
    }
    if (!r.ok) {
        std::printf("%s\n", r.message.c_str());
        return 1;
    }
    const double simulated = static_cast<double>(r.frames) / file.header.tickRate;
    std::printf("%s speed=%.1f\xC3\x97 real time\n", r.message.c_str(), wall > 0 ? simulated / wall : 0.0);
    return 0;
}

int Diff(const char* pathA, const char* pathB, const std::string& sceneFile) {
    ReplayFile fa, fb;
    std::unique_ptr<SceneGame> ga, gb;
    if (!Open(pathA, fa, ga, sceneFile) || !Open(pathB, fb, gb, sceneFile)) return 2;
    Player a(fa, ga->world(), *ga), b(fb, gb->world(), *gb);
    const DiffResult d = DiffReplays(a, b, fa, fb);
    std::printf("%s", d.Describe().c_str());
    if (!d.error.ok()) return 2;
    return d.same ? 0 : 1;
}

// Fault injection for demonstrations: nudges the first dynamic body by 1 raw unit at one
// frame and stage.
class Nudge : public StageHook {
public:
    Nudge(int32 frame, uint32 stage) : m_frame(frame), m_stage(stage) {}
    void OnStage(int32 frame, uint32 stage, b2World& world) override {
        if (frame != m_frame || stage != m_stage) return;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
            if (b->GetType() != b2_dynamicBody) continue;
            b->SetLinearVelocity(b->GetLinearVelocity() + b2Vec2(Fixed::FromRaw(1), Fixed()));
            return;
        }
    }

private:
    int32 m_frame;
    uint32 m_stage;
};

int BisectCommand(const char* path, const std::string& sceneFile, Nudge* nudge) {
    ReplayFile file;
    std::unique_ptr<SceneGame> game;
    if (!Open(path, file, game, sceneFile)) return 2;
    Player player(file, game->world(), *game);
    player.SetStageHook(nudge);
    const BisectResult r = Bisect(player);
    std::printf("%s", r.Describe().c_str());
    if (!r.error.ok()) return 2;
    return r.diverged ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    // The command is argument 0 of the reader; its options and files follow.
    cli::OptionReader args("lockbox_replay", argc - 1, argv + 1);
    if (argc < 2) {
        args.Refuse("give a command: record, info, verify, diff or bisect");
        return args.Fail(kUsage);
    }
    const std::string cmd = argv[1];
    if (cmd == "record") return Record(args);
    size_t wanted = 0;
    if (cmd == "info" || cmd == "verify" || cmd == "bisect") {
        wanted = 1;
    } else if (cmd == "diff") {
        wanted = 2;
    } else {
        args.Refuse("unknown command '" + cmd + "'");
        return args.Fail(kUsage);
    }
    std::vector<const char*> files;
    std::string sceneFile;
    bool inject = false;
    int32 injectFrame = 0;
    uint32 injectStage = 0;
    while (args.Next()) {
        if (args.Is("--scene-file") && cmd != "info") {
            args.Text(sceneFile);
        } else if (args.Is("--inject") && cmd == "bisect") {
            inject = args.IntPair(':', "FRAME:STAGE with STAGE in 0..4", 0, 2147483647, 0, 4, injectFrame, injectStage);
        } else if (!args.Current().empty() && args.Current().front() != '-' && files.size() < wanted) {
            files.push_back(args.Current().data());
        } else {
            args.Unknown();
        }
    }
    if (!args.Failed() && files.size() != wanted)
        args.Refuse(cmd + (wanted == 1 ? " needs a replay file" : " needs two replay files"));
    if (args.Failed()) return args.Fail(kUsage);
    if (cmd == "info") return Info(files[0]);
    if (cmd == "verify") return Verify(files[0], sceneFile);
    if (cmd == "diff") return Diff(files[0], files[1], sceneFile);
    Nudge nudge(injectFrame, injectStage);
    return BisectCommand(files[0], sceneFile, inject ? &nudge : nullptr);
}
