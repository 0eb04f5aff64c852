// first_match: the program docs/first-match.md builds up. Two processes play one rollback
// match over UDP on 127.0.0.1: each pushes its own box around a small arena with scripted
// inputs, the two stay in step through lockbox's rollback netcode, and at the end both print
// the same final hash. `--sync-test` checks the game's rollback on one machine instead.
//
//   first_match --player 0 --port 7000 --peer-port 7001 [--frames N] [--latency-ms N]
//   first_match --player 1 --port 7001 --peer-port 7000 [--frames N] [--latency-ms N]
//   first_match --sync-test [--frames N]
// `--replay FILE` records the match (both players write the same bytes), and
// `first_match replay verify FILE` is the game's own replay tool (lockbox_replay's commands).
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/net/RollbackMatch.h"
#include "lockbox/net/RollbackSyncTest.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/Tool.h"
#include "lockbox/state/WorldGame.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox;

namespace {

constexpr uint32_t kPlayers = 2;
constexpr uint32_t kInputBytes = 1;  // bit 0: push left, bit 1: push right, bit 2: jump
constexpr uint32_t kTickRate = 60;

// The whole game state is the world: two player boxes (user data 1 and 2) and a stack of
// crates on a ground, inside two walls. Inputs push the player boxes.
class TinyGame final : public WorldGame {
public:
    TinyGame() : m_world(b2Vec2(0, -10)) {
        b2BodyDef groundDef;
        b2Body* ground = m_world.CreateBody(&groundDef);
        b2PolygonShape wall;
        wall.SetAsBox(20, 1);  // the floor
        ground->CreateFixture(&wall, 0);
        wall.SetAsBox(1, 10, b2Vec2(-20, 10), 0);  // the walls
        ground->CreateFixture(&wall, 0);
        wall.SetAsBox(1, 10, b2Vec2(20, 10), 0);
        ground->CreateFixture(&wall, 0);
        for (int32_t i = 0; i < 8; ++i) AddBox(b2Vec2(0, 2 + 2 * i), 0);  // crates
        for (uint32_t p = 0; p < kPlayers; ++p) AddBox(b2Vec2(p == 0 ? -10 : 10, 2), p + 1);
    }
    b2World& world() { return m_world; }

    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        (void)frame;
        for (b2Body* b = world.GetBodyList(); b != nullptr; b = b->GetNext()) {
            const uint64_t owner = b->GetUserData();
            if (owner == 0 || owner > kPlayers) continue;
            const uint8 in = inputs[(owner - 1) * kInputBytes];
            const b2Vec2 push((in & 2 ? 2 : 0) - (in & 1 ? 2 : 0), in & 4 ? 8 : 0);
            if (in != 0) b->ApplyLinearImpulse(push, b->GetWorldCenter());
        }
    }

private:
    void AddBox(b2Vec2 at, uint64_t owner) {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position = at;
        b2Body* body = m_world.CreateBody(&def);
        body->SetUserData(owner);
        b2PolygonShape box;
        box.SetAsBox(1, 1);
        b2FixtureDef fixture;
        fixture.shape = &box;
        fixture.density = 1;
        fixture.friction = 0.4;
        body->CreateFixture(&fixture);
    }
    b2World m_world;
};

// Scripted play: a pure function of (player, frame), so every run is the same match. Each
// player sways toward the crates and back, and jumps now and then.
uint8_t Script(uint32_t player, int32_t frame) {
    const int32_t phase = (frame + static_cast<int32_t>(player) * 45) % 120;
    uint8_t in = phase < 50 ? (player == 0 ? 2 : 1) : (phase < 100 ? (player == 0 ? 1 : 2) : 0);
    if ((frame + static_cast<int32_t>(player) * 17) % 97 == 0) in |= 4;
    return in;
}

constexpr const char* kUsage =
    "usage: first_match --player 0|1 --port P --peer-port P [--frames N] [--latency-ms N] [--replay FILE]\n"
    "       first_match --sync-test [--frames N]\n"
    "       first_match replay (info|verify|diff|bisect) ...\n";
constexpr const char* kGameName = "first_match";  // the game name its replays carry

// The game as its replay tool plays it: a fresh TinyGame for each replay.
class TinyToolGame final : public replay::ToolGame {
public:
    b2World& World() override { return m_game.world(); }
    WorldGame& Logic() override { return m_game; }

private:
    TinyGame m_game;
};

// `first_match replay verify FILE` and the other lockbox_replay commands, for this game.
int ReplayTool(int argc, char** argv) {
    replay::GameRegistry games;
    games.Add(kGameName, [](const replay::ToolGameRequest&, std::string&) { return std::make_unique<TinyToolGame>(); });
    return replay::RunTool(argc, argv, games, "first_match replay");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc >= 2 && std::string_view(argv[1]) == "replay") return ReplayTool(argc - 1, argv + 1);
    long player = -1, port = 0, peerPort = 0, frames = 600, latencyMs = 0;
    bool syncTest = false;
    std::string replayPath;
    cli::OptionReader args("first_match", argc, argv);
    while (args.Next()) {
        if (args.Is("--player"))
            args.Int(0, 1, player);
        else if (args.Is("--port"))
            args.Int(1, 65535, port);
        else if (args.Is("--peer-port"))
            args.Int(1, 65535, peerPort);
        else if (args.Is("--frames"))
            args.Int(10, 100000, frames);
        else if (args.Is("--latency-ms"))
            args.Int(0, 500, latencyMs);
        else if (args.Is("--sync-test"))
            syncTest = true;
        else if (args.Is("--replay"))
            args.Text(replayPath);
        else
            args.Unknown();
    }
    if (!args.Failed() && frames % 10 != 0) args.Refuse("--frames must be a multiple of 10 (the desync interval)");
    if (!args.Failed() && !syncTest && (player < 0 || port == 0 || peerPort == 0))
        args.Refuse("a match needs --player, --port and --peer-port");
    if (args.Failed()) return args.Fail(kUsage);

    TinyGame game;
    const WorldStepSettings step{kTickRate, 8, 3};
    if (syncTest) {
        // Every frame is rolled back 8 frames and re-simulated (first with wrong inputs): any
        // state the game forgets to save shows up here, before any network is involved.
        net::SyncTestSessionConfig config;
        config.players = kPlayers;
        config.inputBytes = kInputBytes;
        config.mispredict = true;
        config.step = step;
        auto inputs = [](int32_t frame, std::span<uint8_t> out) {
            for (uint32_t p = 0; p < kPlayers; ++p) out[p] = Script(p, frame);
        };
        const SyncTestResult r =
            net::SyncTestSession(game.world(), game, inputs, config).Run(static_cast<int32_t>(frames));
        std::printf("sync test: %d frames, %d rollbacks: %s\n", r.framesSimulated, r.rollbacks,
                    r.ok ? "ok" : r.message.c_str());
        return r.ok ? 0 : 1;
    }

    const auto me = static_cast<uint32_t>(player);
    net::RollbackMatchBuilder builder;
    builder.Players(kPlayers)
        .LocalPlayer(me)
        .RemotePlayer(1 - me, "127.0.0.1", static_cast<uint16_t>(peerPort))
        .InputBytes(kInputBytes)
        .InputDelay(2)
        .PredictionWindow(8)
        .DesyncInterval(10)
        .StartTimeoutMicros(15000000)  // the other process may start up to 15 s later
        .UdpPort(static_cast<uint16_t>(port))
        .World(game.world(), game, step);
    if (latencyMs > 0) {
        net::LatencyProfile cable;  // what this process receives waits this long
        cable.latencyMicros = static_cast<uint32_t>(latencyMs) * 1000;
        cable.jitterMicros = cable.latencyMicros / 4;
        builder.Latency(cable, 1000 + me);
    }
    net::RollbackMatchBuild built = builder.Build();
    if (!built.match) {
        std::fprintf(stderr, "first_match: %s\n", built.error.message.c_str());
        return 1;
    }
    net::RollbackMatch& match = *built.match;
    std::printf("player %u on port %ld, waiting for 127.0.0.1:%ld\n", me, port, peerPort);
    std::fflush(stdout);

    // The replay: the adapter records each frame once it is final, from the states the match
    // keeps anyway; both players record the same frames with the same settings, so the same bytes.
    std::unique_ptr<replay::FileSink> sink;
    std::unique_ptr<replay::Recorder> recorder;
    if (!replayPath.empty()) {
        sink = std::make_unique<replay::FileSink>(replayPath);
        replay::RecorderConfig rc;
        rc.gameName = kGameName;
        rc.tickRate = kTickRate;
        rc.playerCount = kPlayers;
        rc.inputBytes = kInputBytes;
        rc.keyframeInterval = 120;
        recorder = std::make_unique<replay::Recorder>(game.world(), game, *sink, rc);
        if (!sink->ok() || !match.Adapter().Record(*recorder, static_cast<int32_t>(frames))) {
            std::fprintf(stderr, "first_match: cannot record to %s\n", replayPath.c_str());
            return 1;
        }
    }

    auto inputs = [](uint32_t who, int32_t frame, std::span<uint8_t> out) { out[0] = Script(who, frame); };
    const net::RollbackMatchEnd end = match.PlayTo(static_cast<int32_t>(frames), inputs, 5000000);
    const net::RollbackStats& stats = match.Session().Stats();
    std::printf("%llu rollbacks, deepest %u frames, %llu frames re-simulated\n",
                static_cast<unsigned long long>(stats.rollbacks), stats.deepestRollback,
                static_cast<unsigned long long>(stats.framesResimulated));
    if (!end.Agreed()) {
        std::printf("match did not end in agreement: %s%s\n", end.failure.c_str(), end.timedOut ? "timed out" : "");
        return 1;
    }
    std::printf("final hash 0x%016" PRIx64 " at frame %d\n", end.hash, end.frame);
    if (recorder) {
        if (!match.Adapter().RecordingFinished() || match.Adapter().RecordingFailed() || !sink->Close()) {
            std::printf("replay %s was not written whole\n", replayPath.c_str());
            return 1;
        }
        std::printf("replay %s: %d frames\n", replayPath.c_str(), match.Adapter().RecordedFrames());
    }
    return 0;
}
