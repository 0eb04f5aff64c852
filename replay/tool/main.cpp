// lockbox_replay: record, inspect, verify, compare and bisect replay files (docs/replay.md).
// Exit codes: 0 success (verify: all hashes match; diff: no difference), 1 a divergence or
// difference was found, 2 a usage error or a file that cannot be read.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/replay/Bisect.h"
#include "lockbox/replay/Diff.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

using namespace lockbox;
using namespace lockbox::replay;

namespace {

int Usage() {
    std::fprintf(
        stderr,
        "usage:\n"
        "  lockbox_replay record (--scene NAME | --scene-file FILE.json) --out FILE [--frames N] [--players P]\n"
        "                        [--seed S] [--keyframe-interval K] [--hash-interval H] [--stage-hashes] [--level L]\n"
        "  lockbox_replay info FILE\n"
        "  lockbox_replay verify FILE [--scene-file FILE.json]\n"
        "  lockbox_replay diff A B [--scene-file FILE.json]\n"
        "  lockbox_replay bisect FILE [--inject FRAME:STAGE] [--scene-file FILE.json]\n"
        "      (STAGE 0..4: inputs collide solve broadphase toi; --scene-file: the scene file a replay\n"
        "       was recorded on, refused when it is not that file; without it the seed is enough)\n");
    return 2;
}

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

int Record(int argc, char** argv) {
    std::string scene, sceneFile, out;
    long frames = 600, players = 2, keyframe = 600, hashInterval = 1, level = 3;
    unsigned long long seed = 1;
    bool stageHashes = false;
    for (int i = 0; i < argc; ++i) {
        const std::string a = argv[i];
        const bool more = i + 1 < argc;
        if (a == "--scene" && more)
            scene = argv[++i];
        else if (a == "--scene-file" && more)
            sceneFile = argv[++i];
        else if (a == "--out" && more)
            out = argv[++i];
        else if (a == "--frames" && more)
            frames = std::strtol(argv[++i], nullptr, 10);
        else if (a == "--players" && more)
            players = std::strtol(argv[++i], nullptr, 10);
        else if (a == "--seed" && more)
            seed = std::strtoull(argv[++i], nullptr, 0);
        else if (a == "--keyframe-interval" && more)
            keyframe = std::strtol(argv[++i], nullptr, 10);
        else if (a == "--hash-interval" && more)
            hashInterval = std::strtol(argv[++i], nullptr, 10);
        else if (a == "--level" && more)
            level = std::strtol(argv[++i], nullptr, 10);
        else if (a == "--stage-hashes")
            stageHashes = true;
        else
            return Usage();
    }
    if (scene.empty() == sceneFile.empty() || out.empty() || frames < 0 || players < 1 || players > 64 ||
        keyframe < 0 || hashInterval < 1)
        return Usage();
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
            b->m_linearVelocity.x = Fixed::FromRaw(b->m_linearVelocity.x.Raw() + 1);
            return;
        }
    }

private:
    int32 m_frame;
    uint32 m_stage;
};

int BisectCommand(int argc, char** argv, const std::string& sceneFile) {
    if (argc < 1) return Usage();
    ReplayFile file;
    std::unique_ptr<SceneGame> game;
    if (!Open(argv[0], file, game, sceneFile)) return 2;
    std::unique_ptr<Nudge> nudge;
    for (int i = 1; i < argc; ++i) {
        long frame = 0, stage = 0;
        if (std::strcmp(argv[i], "--inject") == 0 && i + 1 < argc &&
            std::sscanf(argv[i + 1], "%ld:%ld", &frame, &stage) == 2 && stage >= 0 && stage < 5) {
            nudge = std::make_unique<Nudge>(static_cast<int32>(frame), static_cast<uint32>(stage));
            ++i;
        } else {
            return Usage();
        }
    }
    Player player(file, game->world(), *game);
    player.SetStageHook(nudge.get());
    const BisectResult r = Bisect(player);
    std::printf("%s", r.Describe().c_str());
    if (!r.error.ok()) return 2;
    return r.diverged ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return Usage();
    const std::string cmd = argv[1];
    if (cmd == "record") return Record(argc - 2, argv + 2);
    // `--scene-file FILE.json` may follow the file arguments of the other commands.
    std::string sceneFile;
    std::vector<char*> args(argv + 2, argv + argc);
    for (size_t i = 0; i + 1 < args.size(); ++i) {
        if (std::strcmp(args[i], "--scene-file") != 0) continue;
        sceneFile = args[i + 1];
        args.erase(args.begin() + static_cast<std::ptrdiff_t>(i), args.begin() + static_cast<std::ptrdiff_t>(i) + 2);
        break;
    }
    const int n = static_cast<int>(args.size());
    if (cmd == "info" && n == 1) return Info(args[0]);
    if (cmd == "verify" && n == 1) return Verify(args[0], sceneFile);
    if (cmd == "diff" && n == 2) return Diff(args[0], args[1], sceneFile);
    if (cmd == "bisect") return BisectCommand(n, args.data(), sceneFile);
    return Usage();
}
