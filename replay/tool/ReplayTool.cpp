// RunTool: the info, verify, diff and bisect commands of a replay tool, on the games a
// GameRegistry knows (docs/replay.md).
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/replay/Bisect.h"
#include "lockbox/replay/Diff.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/Tool.h"
#include "lockbox_cli/OptionReader.h"

namespace lockbox::replay {

void GameRegistry::Add(std::string gameName, ToolGameFactory make) { m_exact[std::move(gameName)] = std::move(make); }

void GameRegistry::AddPrefix(std::string prefix, ToolGameFactory make) {
    m_prefixes[std::move(prefix)] = std::move(make);
}

void GameRegistry::AddOption(std::string option, std::string valueName) {
    m_options.push_back({std::move(option), std::move(valueName)});
}

void GameRegistry::AddInfo(std::function<std::string(const ReplayFile& file)> describe) {
    m_infos.push_back(std::move(describe));
}

void GameRegistry::AddCommand(std::string name, std::string usage, ToolCommandRun run) {
    m_commands.push_back({std::move(name), std::move(usage), std::move(run)});
}

std::unique_ptr<ToolGame> GameRegistry::Make(const ToolGameRequest& request, std::string& error) const {
    const std::string& name = request.file.gameName;
    const ToolGameFactory* make = nullptr;
    if (auto it = m_exact.find(name); it != m_exact.end()) {
        make = &it->second;
    } else {
        size_t longest = 0;
        for (const auto& [prefix, factory] : m_prefixes)
            if (name.rfind(prefix, 0) == 0 && (make == nullptr || prefix.size() > longest)) {
                make = &factory;
                longest = prefix.size();
            }
    }
    if (make == nullptr) {
        error = request.path + ": game \"" + name + "\" is not one this tool knows (a game's own tool registers it)";
        return nullptr;
    }
    error.clear();
    std::unique_ptr<ToolGame> game = (*make)(request, error);
    if (!game && error.empty()) error = request.path + ": game \"" + name + "\" could not be built";
    return game;
}

namespace {

std::string Hex(uint64 v) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
    return buf;
}

struct Context {
    const GameRegistry& games;
    std::map<std::string, std::string> options;
};

// Parses a file and builds its game; prints the error and returns false on failure.
bool Open(const Context& ctx, const char* path, ReplayFile& file, std::unique_ptr<ToolGame>& game) {
    if (Error e = LoadReplay(path, file); !e.ok()) {
        std::printf("%s: %s\n", path, e.Describe().c_str());
        return false;
    }
    ToolGameRequest request{file, path, ctx.options};
    std::string error;
    game = ctx.games.Make(request, error);
    if (!game) std::printf("%s\n", error.c_str());
    return game != nullptr;
}

int Info(const GameRegistry& games, const char* path) {
    ReplayFile f;
    if (Error e = LoadReplay(path, f); !e.ok()) {
        std::printf("%s: %s\n", path, e.Describe().c_str());
        return 2;
    }
    const Header& h = f.header;
    std::printf("file           %s (%llu bytes)\n", path, static_cast<unsigned long long>(f.fileBytes));
    std::printf("format         %u, engine %u.%u.%u, determinism 0x%08x, snapshot format %u\n", h.formatVersion,
                h.engineMajor, h.engineMinor, h.enginePatch, h.determinismVersion, h.snapshotFormatVersion);
    std::printf("game           %s\n", f.gameName.c_str());
    for (const auto& describe : games.Infos()) std::printf("%s", describe(f).c_str());
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

int Verify(const Context& ctx, const char* path) {
    ReplayFile file;
    std::unique_ptr<ToolGame> game;
    if (!Open(ctx, path, file, game)) return 2;
    Player player(file, game->World(), game->Logic());
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

int DiffCommand(const Context& ctx, const char* pathA, const char* pathB) {
    ReplayFile fa, fb;
    std::unique_ptr<ToolGame> ga, gb;
    if (!Open(ctx, pathA, fa, ga) || !Open(ctx, pathB, fb, gb)) return 2;
    Player a(fa, ga->World(), ga->Logic()), b(fb, gb->World(), gb->Logic());
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

int BisectCommand(const Context& ctx, const char* path, Nudge* nudge) {
    ReplayFile file;
    std::unique_ptr<ToolGame> game;
    if (!Open(ctx, path, file, game)) return 2;
    Player player(file, game->World(), game->Logic());
    player.SetStageHook(nudge);
    const BisectResult r = Bisect(player);
    std::printf("%s", r.Describe().c_str());
    if (!r.error.ok()) return 2;
    return r.diverged ? 1 : 0;
}

std::string Usage(const GameRegistry& games, const std::string& program) {
    std::string options;
    for (const GameRegistry::Option& o : games.Options()) options += " [" + o.name + " " + o.valueName + "]";
    std::string u = "usage:\n";
    for (const GameRegistry::Command& c : games.Commands()) u += "  " + program + " " + c.usage + "\n";
    u += "  " + program + " info FILE\n";
    u += "  " + program + " verify FILE" + options + "\n";
    u += "  " + program + " diff A B" + options + "\n";
    u += "  " + program + " bisect FILE [--inject FRAME:STAGE]" + options + "\n";
    u += "      (STAGE 0..4: inputs collide solve broadphase toi)\n";
    return u;
}

}  // namespace

int RunTool(int argc, char** argv, const GameRegistry& games, const std::string& program) {
    const std::string usage = Usage(games, program);
    // The command is argument 0 of the reader; its options and files follow.
    cli::OptionReader args(program, argc - 1, argv + 1);
    if (argc < 2) {
        std::string names;
        for (const GameRegistry::Command& c : games.Commands()) names += c.name + ", ";
        args.Refuse("give a command: " + names + "info, verify, diff or bisect");
        return args.Fail(usage.c_str());
    }
    const std::string cmd = argv[1];
    for (const GameRegistry::Command& c : games.Commands())
        if (c.name == cmd) return c.run(argc - 1, argv + 1);
    size_t wanted = 0;
    if (cmd == "info" || cmd == "verify" || cmd == "bisect") {
        wanted = 1;
    } else if (cmd == "diff") {
        wanted = 2;
    } else {
        args.Refuse("unknown command '" + cmd + "'");
        return args.Fail(usage.c_str());
    }
    Context ctx{games, {}};
    std::vector<const char*> files;
    bool inject = false;
    int32 injectFrame = 0;
    uint32 injectStage = 0;
    while (args.Next()) {
        const GameRegistry::Option* option = nullptr;
        for (const GameRegistry::Option& o : games.Options())
            if (args.Is(o.name)) option = &o;
        if (option != nullptr && cmd != "info") {
            args.Text(ctx.options[option->name]);
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
    if (args.Failed()) return args.Fail(usage.c_str());
    if (cmd == "info") return Info(games, files[0]);
    if (cmd == "verify") return Verify(ctx, files[0]);
    if (cmd == "diff") return DiffCommand(ctx, files[0], files[1]);
    Nudge nudge(injectFrame, injectStage);
    return BisectCommand(ctx, files[0], inject ? &nudge : nullptr);
}

}  // namespace lockbox::replay
