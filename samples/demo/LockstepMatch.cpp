// The lockstep match of the main demo (LockstepMatch.h). One thread per endpoint: the server
// and every client own their socket, and the clients own their world (a replay::SceneGame).
// The main thread only watches: each client publishes the world hash of every frame it steps,
// and the main thread compares them at the newest frame every client has reached.
#include "LockstepMatch.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "lockbox/net/EnetTransport.h"
#include "lockbox/net/LockstepClient.h"
#include "lockbox/net/LockstepServer.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::demo {

namespace {

using Clock = std::chrono::steady_clock;

std::mutex g_print;

template <typename... Args>
void Say(const char* format, Args... args) {
    std::lock_guard<std::mutex> lock(g_print);
    std::printf(format, args...);
    std::fflush(stdout);
}

double Seconds(Clock::time_point from) { return std::chrono::duration<double>(Clock::now() - from).count(); }

/// What a client thread shares with the watcher. hashes[f] is written once, before `frames`
/// moves past f (release), so the watcher may read every index below `frames` (acquire).
struct ClientBoard {
    std::vector<uint64_t> hashes;
    std::atomic<int32_t> frames{0};
    std::atomic<int32_t> slot{-1};
    std::atomic<uint64_t> rttMicros{0};
    std::atomic<uint32_t> inputDelay{0};
    std::atomic<bool> done{false};
    std::atomic<bool> failed{false};
};

/// The endpoint of one thread: a UDP socket or an ENet host, with the server's PeerId for a
/// client.
struct Endpoint {
    std::unique_ptr<net::Transport> transport;
    net::PeerId server = net::kNoPeer;
    uint16_t port = 0;
};

Endpoint OpenServer(const MatchOptions& o, std::string* error) {
    Endpoint e;
    if (o.transport == "enet") {
        auto t = net::EnetTransport::Listen(0, static_cast<size_t>(o.clients) + 4, error);
        if (t) e.port = t->LocalPort();
        e.transport = std::move(t);
    } else {
        auto t = net::UdpTransport::Open("127.0.0.1", 0, error);
        if (t) e.port = t->LocalPort();
        e.transport = std::move(t);
    }
    return e;
}

Endpoint OpenClient(const MatchOptions& o, uint16_t serverPort, std::string* error) {
    Endpoint e;
    if (o.transport == "enet") {
        auto t = net::EnetTransport::Client(error);
        if (t) e.server = t->Connect("127.0.0.1", serverPort, error);
        e.transport = std::move(t);
    } else {
        auto t = net::UdpTransport::Open("127.0.0.1", 0, error);
        if (t) e.server = t->AddPeer("127.0.0.1", serverPort, error);
        e.transport = std::move(t);
    }
    if (e.server == net::kNoPeer) e.transport.reset();
    return e;
}

const char* ServerEventName(net::ServerEvent::Kind k) {
    using K = net::ServerEvent::Kind;
    switch (k) {
        case K::e_joined: return "joined";
        case K::e_started: return "started";
        case K::e_interrupted: return "interrupted";
        case K::e_resumed: return "resumed";
        case K::e_disconnected: return "disconnected";
        case K::e_admitted: return "admitted";
        case K::e_joinFailed: return "join failed";
        case K::e_desync: return "DESYNC";
        case K::e_spoofedInput: return "spoofed input";
    }
    return "?";
}

/// One player: joins, submits scripted inputs when the client asks for them, steps until
/// `frames` frames are done. Client 0 also records the confirmed frames.
void PlayClient(const MatchOptions& o, int index, uint16_t serverPort, ClientBoard& board, replay::Recorder* recorder,
                replay::SceneGame& game, Clock::time_point deadline) {
    std::string error;
    Endpoint e = OpenClient(o, serverPort, &error);
    if (!e.transport) {
        Say("client %d: cannot open its socket: %s\n", index, error.c_str());
        board.failed = true;
        board.done = true;
        return;
    }
    net::ClientConfig config;
    // Client i plays slot i, so the same seed gives the same match (and final hash) every run.
    config.requestedSlot = static_cast<uint8_t>(index);
    config.inputDelay = o.inputDelay > 0 ? o.inputDelay : 0;
    config.velocityIterations = static_cast<uint32_t>(game.info().velocityIterations);
    config.positionIterations = static_cast<uint32_t>(game.info().positionIterations);
    net::LockstepClient client(*e.transport, e.server, config, game.world(), game);
    client.SetConfirmedFrameHook(
        [&](int32_t frame, std::span<const uint8_t> inputs, uint64_t worldHash, const b2World& world) {
            if (frame < 0 || frame >= o.frames) return;
            board.hashes[static_cast<size_t>(frame)] = worldHash;
            if (recorder != nullptr) recorder->AppendConfirmed(inputs, worldHash, &world);
            board.frames.store(frame + 1, std::memory_order_release);
        });

    replay::ScriptedInputs script(o.seed + static_cast<uint64_t>(index), 1);
    std::vector<uint8_t> input;
    while (client.Frame() < o.frames && Clock::now() < deadline && client.State() != net::ClientState::e_closed) {
        client.Update();
        while (client.WantsInput()) {
            script.Next(input);
            if (!client.SubmitLocalInput(input)) break;
        }
        for (const net::ClientEvent& ev : client.TakeEvents()) {
            if (ev.kind == net::ClientEvent::Kind::e_rejected || ev.kind == net::ClientEvent::Kind::e_disconnected ||
                ev.kind == net::ClientEvent::Kind::e_desync) {
                Say("client %d: %s at frame %d\n", index,
                    ev.kind == net::ClientEvent::Kind::e_desync ? "desync reported by the server" : "session ended",
                    ev.frame);
                board.failed = true;
            }
        }
        board.slot = client.Slot();
        board.rttMicros = client.RttMicros();
        board.inputDelay = client.InputDelay();
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    if (client.Frame() < o.frames) {
        Say("client %d: stopped at frame %d of %d\n", index, client.Frame(), o.frames);
        board.failed = true;
    }
    client.Leave();
    board.done = true;
}

/// The newest frame every client has stepped (0 when one has not started).
int32_t CommonFrames(const std::vector<std::unique_ptr<ClientBoard>>& boards) {
    int32_t common = INT32_MAX;
    for (const auto& b : boards) common = std::min(common, b->frames.load(std::memory_order_acquire));
    return common;
}

void PrintStatus(const std::vector<std::unique_ptr<ClientBoard>>& boards, double t, int32_t confirmed) {
    const int32_t common = CommonFrames(boards);
    std::lock_guard<std::mutex> lock(g_print);
    std::printf("[%5.1f s] server confirmed %d frames; every client has stepped %d\n", t, confirmed, common);
    for (size_t i = 0; i < boards.size(); ++i) {
        const ClientBoard& b = *boards[i];
        const int32_t f = b.frames.load(std::memory_order_acquire);
        std::printf("    client %zu (slot %d)  frame %4d  rtt %6.2f ms  delay %u", i, b.slot.load(), f,
                    static_cast<double>(b.rttMicros.load()) / 1000.0, b.inputDelay.load());
        if (common > 0)
            std::printf("  hash@%d 0x%016llx", common - 1,
                        static_cast<unsigned long long>(b.hashes[static_cast<size_t>(common - 1)]));
        std::printf("\n");
    }
    std::fflush(stdout);
}

/// Plays the recorded replay in a fresh world; true when every stored hash matches.
bool VerifyReplay(const std::string& path, uint64_t expectFinal) {
    replay::ReplayFile file;
    if (replay::Error e = replay::LoadReplay(path, file); !e.ok()) {
        Say("replay: cannot load %s: %s\n", path.c_str(), e.Describe().c_str());
        return false;
    }
    replay::SceneGame game(replay::SceneGame::SceneName(file.gameName));
    replay::Player player(file, game.world(), game);
    const replay::VerifyResult r = player.Verify();
    Say("replay: verify %s: %s\n", path.c_str(), r.message.c_str());
    if (r.ok && r.finalHash != expectFinal) {
        Say("replay: final hash 0x%016llx differs from the match's 0x%016llx\n",
            static_cast<unsigned long long>(r.finalHash), static_cast<unsigned long long>(expectFinal));
        return false;
    }
    return r.ok;
}

}  // namespace

int RunLockstepMatch(const MatchOptions& o) {
    auto probe = scenes::MakeLockboxScene(o.scene);
    if (!probe) {
        std::fprintf(stderr, "lockbox_demo: unknown scene '%s'\n", o.scene.c_str());
        return 2;
    }
    const int hz = probe->Info().hz;
    std::printf("== Lockstep match: scene %s, %d clients, %d frames at %d Hz, %s on 127.0.0.1, %s server ==\n",
                o.scene.c_str(), o.clients, o.frames, hz, o.transport.c_str(),
                o.authoritative ? "authoritative" : "relay");

    std::string error;
    Endpoint server = OpenServer(o, &error);
    if (!server.transport) {
        std::fprintf(stderr, "lockbox_demo: cannot open the server socket: %s\n", error.c_str());
        return 2;
    }
    std::unique_ptr<replay::SceneGame> serverGame;
    net::ServerConfig sc;
    sc.playerCount = static_cast<uint32_t>(o.clients);
    sc.inputBytes = replay::SceneInput::kBytes;
    sc.tickRate = static_cast<uint32_t>(hz);
    sc.hashInterval = 10;
    if (o.authoritative) {
        serverGame = std::make_unique<replay::SceneGame>(o.scene);
        sc.world = &serverGame->world();
        sc.game = serverGame.get();
        sc.velocityIterations = static_cast<uint32_t>(serverGame->info().velocityIterations);
        sc.positionIterations = static_cast<uint32_t>(serverGame->info().positionIterations);
    }

    // Each client's world, built before any thread starts; client 0's is also recorded.
    std::vector<std::unique_ptr<replay::SceneGame>> games;
    std::vector<std::unique_ptr<ClientBoard>> boards;
    for (int i = 0; i < o.clients; ++i) {
        games.push_back(std::make_unique<replay::SceneGame>(o.scene));
        boards.push_back(std::make_unique<ClientBoard>());
        boards.back()->hashes.assign(static_cast<size_t>(o.frames), 0);
    }
    const std::string replayPath =
        o.replayPath.empty() ? (std::filesystem::temp_directory_path() / "lockbox_demo.lbr").string() : o.replayPath;
    replay::FileSink sink(replayPath);
    if (!sink.ok()) {
        std::fprintf(stderr, "lockbox_demo: cannot write %s\n", replayPath.c_str());
        return 2;
    }
    replay::RecorderConfig rc = games[0]->Config(static_cast<uint16_t>(o.clients));
    rc.keyframeInterval = 300;
    replay::Recorder recorder(games[0]->world(), *games[0], sink, rc);
    if (replay::Error e = recorder.Begin(); !e.ok()) {
        std::fprintf(stderr, "lockbox_demo: replay: %s\n", e.Describe().c_str());
        return 2;
    }

    const Clock::time_point start = Clock::now();
    const Clock::time_point deadline = start + std::chrono::seconds(30 + o.frames / std::max(hz, 1));
    std::atomic<bool> stopServer{false};
    std::atomic<int32_t> confirmed{0};
    std::atomic<int> desyncs{0};
    net::LockstepServer lockstep(*server.transport, sc);
    std::thread serverThread([&] {
        while (!stopServer) {
            lockstep.Update();
            for (const net::ServerEvent& ev : lockstep.TakeEvents()) {
                if (ev.kind == net::ServerEvent::Kind::e_desync) ++desyncs;
                Say("server: %s (slot %d, frame %d)\n", ServerEventName(ev.kind), ev.slot, ev.frame);
            }
            confirmed = lockstep.ConfirmedFrames();
            std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
        lockstep.Close();
        lockstep.Update();
    });
    std::vector<std::thread> clientThreads;
    for (int i = 0; i < o.clients; ++i) {
        clientThreads.emplace_back(PlayClient, std::cref(o), i, server.port, std::ref(*boards[static_cast<size_t>(i)]),
                                   i == 0 ? &recorder : nullptr, std::ref(*games[static_cast<size_t>(i)]), deadline);
    }

    double nextReport = 1.0;
    for (;;) {
        const bool allDone = std::all_of(boards.begin(), boards.end(), [](const auto& b) { return b->done.load(); });
        if (allDone) break;
        if (Seconds(start) >= nextReport) {
            PrintStatus(boards, Seconds(start), confirmed.load());
            nextReport += 1.0;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    for (std::thread& t : clientThreads) t.join();
    stopServer = true;
    serverThread.join();
    PrintStatus(boards, Seconds(start), confirmed.load());

    // Every client's hash of every frame must agree with client 0's.
    bool agree = true;
    int32_t firstDiff = -1;
    const int32_t common = CommonFrames(boards);
    for (int32_t f = 0; f < common && agree; ++f)
        for (const auto& b : boards)
            if (b->hashes[static_cast<size_t>(f)] != boards[0]->hashes[static_cast<size_t>(f)]) {
                agree = false;
                firstDiff = f;
            }
    const bool complete = common == o.frames;
    const bool failed = std::any_of(boards.begin(), boards.end(), [](const auto& b) { return b->failed.load(); });
    const uint64_t finalHash = complete ? boards[0]->hashes[static_cast<size_t>(o.frames - 1)] : 0;
    if (complete && agree) {
        std::printf(
            "\nAll %d clients agree on the final hash 0x%016llx after %d frames (%.1f s).\n"
            "The same options give this hash on every run, machine, compiler and architecture.\n",
            o.clients, static_cast<unsigned long long>(finalHash), o.frames, Seconds(start));
    } else if (!agree) {
        std::printf("\nClients DISAGREE from frame %d.\n", firstDiff);
    } else {
        std::printf("\nThe match did not complete: every client reached frame %d of %d.\n", common, o.frames);
    }

    if (replay::Error e = recorder.Finish(); !e.ok()) std::printf("replay: %s\n", e.Describe().c_str());
    const bool closed = sink.Close();
    std::printf("replay: %d frames written to %s\n", recorder.Frames(), replayPath.c_str());
    const bool verified = closed && complete && VerifyReplay(replayPath, finalHash);
    const bool ok = complete && agree && !failed && desyncs.load() == 0 && verified;
    std::printf("%s\n", ok ? "OK" : "FAILED");
    return ok ? 0 : 1;
}

}  // namespace lockbox::demo
