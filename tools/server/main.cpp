// lockbox_server: many lockstep matches on one UDP port for clients the matchmaker admitted
// (docs/deploy.md). `lockbox_server --help` documents every option.

#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "AgonesLifecycle.h"
#include "MatchHost.h"
#include "Metrics.h"
#include "OpsHttp.h"
#include "ServerOptions.h"
#include "lockbox/replay/SceneGame.h"

namespace {

volatile std::sig_atomic_t g_stopSignals = 0;

extern "C" void OnStopSignal(int) { g_stopSignals = g_stopSignals + 1; }

bool ReadKey(const std::string& path, lockbox::admission::TokenKey& key) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    const auto parsed = lockbox::admission::ParseKeyHex(text.str());
    if (!in || !parsed) return false;
    key = *parsed;
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace lockbox;
    server::ServerOptions options;
    const int rc = server::ReadOptions(argc, argv, options);
    if (rc == 1) return 0;
    if (rc != 0) return rc;

    server::HostConfig config;
    if (!ReadKey(options.tokenKeyFile, config.key)) {
        std::fprintf(stderr, "lockbox_server: --token-key-file %s does not hold a key (64 hex digits)\n",
                     options.tokenKeyFile.c_str());
        return 2;
    }
    if (!options.scene.empty() && !replay::SceneGame(options.scene).ok()) {
        std::fprintf(stderr, "lockbox_server: --scene %s is not a library scene\n", options.scene.c_str());
        return 2;
    }
    std::FILE* logFile = stdout;
    if (options.logFile != "-") {
        logFile = std::fopen(options.logFile.c_str(), "a");
        if (logFile == nullptr) {
            std::fprintf(stderr, "lockbox_server: cannot open the log %s\n", options.logFile.c_str());
            return 1;
        }
    }
    server::JsonLog log(logFile);

    std::string error;
    // The peer table holds the admitted clients plus the senders of one poll being refused.
    const size_t maxPeers =
        std::min<size_t>(65536, size_t{options.maxPlayers} + 2 * net::UdpTransport::kMaxPollPerCall);
    auto socket = net::UdpTransport::Open(options.bindHost, options.port, &error, maxPeers);
    if (!socket) {
        std::fprintf(stderr, "lockbox_server: %s\n", error.c_str());
        return 1;
    }
    const uint16_t port = socket->LocalPort();
    net::UdpTransport* socketView = socket.get();

    config.matchIds = options.matchIds;
    config.maxMatches = options.maxMatches;
    config.maxPlayers = options.maxPlayers;
    config.kind = options.matchKind == "lockstep-authoritative" ? server::MatchKind::e_lockstepAuthoritative
                  : options.matchKind == "rollback-relay"       ? server::MatchKind::e_rollbackRelay
                                                                : server::MatchKind::e_lockstepRelay;
    config.peerBytesPerSecond = options.peerBytesPerSecond;
    config.spectatorsPerMatch = options.spectatorsPerMatch;
    config.spectatorHostBytesPerSecond = options.spectatorHostBytesPerSecond;
    config.match.playerCount = options.playersPerMatch;
    config.match.inputBytes = options.inputBytes;
    config.match.tickRate = options.tickRate;
    config.match.hashInterval = options.hashInterval;
    config.startTimeoutMicros = uint64_t{options.startTimeoutSeconds} * 1'000'000;
    config.tokenMaxLifetimeSeconds = options.tokenMaxLifetimeSeconds;
    config.replayCacheSize = options.replayCacheSize;
    config.rateLimitPerSecond = options.rateLimitPerSecond;
    config.rateLimitBurst = options.rateLimitBurst;
    config.scene = options.scene;
    config.replayDir = options.replayDir;
    server::MatchHost host(std::move(socket), std::move(config), log);

    server::OpsHttp http;
    if (options.httpPort != 0 && !http.Start(options.httpPort, error)) {
        std::fprintf(stderr, "lockbox_server: %s\n", error.c_str());
        return 1;
    }
    struct sigaction action {};
    action.sa_handler = OnStopSignal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGTERM, &action, nullptr);
    sigaction(SIGINT, &action, nullptr);

    if (!options.portFile.empty()) {
        // Written whole under another name, then renamed: a reader never sees half a number.
        const std::string partial = options.portFile + ".partial";
        std::FILE* f = std::fopen(partial.c_str(), "w");
        if (f == nullptr || std::fprintf(f, "%u\n", port) < 0 || std::fclose(f) != 0 ||
            std::rename(partial.c_str(), options.portFile.c_str()) != 0) {
            std::fprintf(stderr, "lockbox_server: cannot write %s\n", options.portFile.c_str());
            return 1;
        }
    }
    log.Event("listening").Str("bind", options.bindHost).Num("port", port).Num("http_port", options.httpPort);
    std::unique_ptr<server::AgonesLifecycle> agones;
    if (const uint16_t agonesPort = server::AgonesPortFromEnvironment(); agonesPort != 0) {
        agones = std::make_unique<server::AgonesLifecycle>(agonesPort, options.agonesHealthSeconds * 1000, log);
        agones->Ready();
    }

    uint64_t drainDeadline = 0;
    uint64_t lastPublish = 0;
    for (;;) {
        host.Update();
        const uint64_t now = socketView->NowMicros();
        if (g_stopSignals > 0 && !host.Draining()) {
            host.BeginDrain();
            drainDeadline = now + uint64_t{options.drainSeconds} * 1'000'000;
        }
        if (host.Draining() && (host.MatchCount() == 0 || now >= drainDeadline || g_stopSignals > 1)) {
            host.CloseAll();
            break;
        }
        if (now - lastPublish >= 200'000) {
            lastPublish = now;
            http.Publish(server::RenderMetrics(host), !host.Draining());
            if (agones) agones->Counts(host.MatchCount(), host.PlayerCount());
        }
        socketView->WaitReadable(1);
    }
    http.Publish(server::RenderMetrics(host), false);
    if (agones) {
        // Every match has ended: the fleet may now replace this server.
        agones->Counts(host.MatchCount(), host.PlayerCount());
        agones->Finish(3000);
    }
    log.Event("stopped")
        .Num("matches_ended", host.Stats().matchesEnded)
        .Num("replays_written", host.Stats().replaysWritten);
    http.Stop();
    if (logFile != stdout) std::fclose(logFile);
    return 0;
}
