#pragma once
// lockbox_server's settings: read from the command line and from a config file of the same
// options (key=value lines), with the program's usage text documenting every one.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace lockbox::server {

/// Every setting of the server, with its default.
struct ServerOptions {
    std::string bindHost = "127.0.0.1";        ///< numeric address of the game socket
    uint16_t port = 0;                         ///< UDP port of the game socket (0: any free port)
    uint16_t httpPort = 0;                     ///< localhost port of /healthz, /readyz, /metrics (0: off)
    std::string tokenKeyFile;                  ///< file with the shared token key (64 hex digits); required
    std::vector<uint32_t> matchIds;            ///< matches this server hosts; empty: any match a token names
    uint32_t maxMatches = 64;                  ///< matches at once
    uint32_t maxPlayers = 256;                 ///< admitted clients at once, all matches together
    std::string matchKind = "lockstep-relay";  ///< lockstep-relay, lockstep-authoritative or rollback-relay
    uint32_t playersPerMatch = 2;              ///< slots of each match, 1 .. 64 (rollback relay: 2 .. 64)
    uint32_t spectatorsPerMatch = 0;           ///< rollback-relay: spectator slots after the players'
    uint32_t peerBytesPerSecond = 65536;       ///< bytes a second per stream a client sends (0: no limit)
    uint32_t inputBytes = 8;                   ///< per player per frame, 1 .. 256
    uint32_t tickRate = 60;                    ///< frames per second
    uint32_t hashInterval = 30;                ///< clients report a state hash every this many frames
    uint32_t startTimeoutSeconds = 60;         ///< a match whose slots did not all fill by then ends
    uint32_t tokenMaxLifetimeSeconds = 3600;   ///< tokens expiring later than this are refused
    uint32_t replayCacheSize = 65536;          ///< admitted token nonces remembered at once
    uint32_t rateLimitPerSecond = 20;          ///< unauthenticated datagrams per source address per second
    uint32_t rateLimitBurst = 40;              ///< ... and in one burst
    uint32_t drainSeconds = 30;                ///< on SIGTERM: how long running matches may go on
    std::string logFile = "-";                 ///< JSON-lines log ("-": standard output)
    std::string replayDir;                     ///< where finished matches' replays go (needs scene)
    std::string scene;                         ///< library scene the clients play (for replays)
    std::string portFile;                      ///< when set, the bound UDP port is written there
    uint32_t agonesHealthSeconds = 2;          ///< Agones health ping interval (AGONES_SDK_HTTP_PORT set)
    /// Rollback relay with spectator slots: bytes a second slot 0 (the spectators' host) may
    /// send (0: no limit); unset: peerBytesPerSecond x (players - 1 + spectatorsPerMatch).
    std::optional<uint32_t> spectatorHostBytesPerSecond;
};

/// Reads the command line (argv[1..]) into `out`, `--config FILE` lines included where it
/// appears. Returns 0 to run, 1 after printing --help, 2 after printing a usage error that
/// names the option or the file and line.
int ReadOptions(int argc, char** argv, ServerOptions& out);

/// The usage text (every option, one paragraph each).
const char* UsageText();

}  // namespace lockbox::server
