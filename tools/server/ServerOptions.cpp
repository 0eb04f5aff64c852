// Command line and config file of lockbox_server (ServerOptions.h). One table of options serves
// both: a config line "key = value" is read as the option "--key value".

#include "ServerOptions.h"

#include <cstdio>
#include <fstream>
#include <string_view>

#include "lockbox/net/RelayWire.h"
#include "lockbox_cli/OptionReader.h"

namespace lockbox::server {

namespace {

constexpr const char* kUsage =
    "usage: lockbox_server --token-key-file FILE [options]\n"
    "Runs many matches on one UDP port (lockstep, relayed or authoritative, or rollback peers\n"
    "through a relay), admitting only clients with a signed admission token (lockbox_token mint).\n"
    "\n"
    "  --config FILE           read options from FILE: one 'key = value' per line, keys are the\n"
    "                          option names without '--', '#' starts a comment; options after\n"
    "                          --config override the file's\n"
    "  --bind HOST             numeric address of the game socket (default 127.0.0.1)\n"
    "  --port N                UDP port, 0 .. 65535 (default 0: any free port, see --port-file)\n"
    "  --port-file FILE        write the bound UDP port to FILE once listening\n"
    "  --http-port N           /healthz, /readyz and /metrics on 127.0.0.1:N (default 0: off)\n"
    "  --token-key-file FILE   the key shared with the matchmaker, 64 hex digits (required)\n"
    "  --matches ID,ID,...     the match ids this server hosts (default: any id a token names)\n"
    "  --max-matches N         matches at once, 1 .. 100000 (default 64)\n"
    "  --max-players N         admitted clients at once, 1 .. 1000000 (default 256)\n"
    "  --match-kind KIND       what every match runs (default lockstep-relay):\n"
    "                          lockstep-relay: the server relays inputs, the clients simulate;\n"
    "                          lockstep-authoritative: the server also simulates --scene and\n"
    "                          checks the clients' hashes against its own;\n"
    "                          rollback-relay: rollback peers exchange inputs through the server\n"
    "                          (RelayedTransport), which records them for the replay\n"
    "  --players-per-match N   slots of every match, 1 .. 64 (rollback-relay: 2 .. 64; default 2)\n"
    "  --spectators-per-match N  rollback-relay: relay slots for spectators after the players'\n"
    "                          (tokens for slots players .. players + N - 1), taken in turn: a\n"
    "                          new spectator is seated once the last one was silent 2 s;\n"
    "                          players + N <= 64 (default 0)\n"
    "  --peer-bandwidth N      bytes a second one admitted client may send per stream, one\n"
    "                          second's worth at once; more is dropped and counted,\n"
    "                          0 .. 1000000000 (default 65536; 0: no limit). A lockstep client\n"
    "                          or a spectator sends one stream; a rollback-relay player one to\n"
    "                          each other player, and slot 0 one more per spectator slot\n"
    "  --spectator-host-bandwidth N  rollback-relay with spectator slots: the budget of slot 0,\n"
    "                          the player that hosts the spectators (it sends each of them the\n"
    "                          confirmed inputs and a joining one a snapshot), 0 .. 1000000000\n"
    "                          (default --peer-bandwidth x (players - 1 + spectators); 0: no\n"
    "                          limit)\n"
    "  --input-bytes N         input bytes per player per frame, 1 .. 256 (default 8)\n"
    "  --tick-rate N           frames per second, 1 .. 1000 (default 60)\n"
    "  --hash-interval N       clients report a state hash every N frames, 1 .. 100000 (default 30)\n"
    "  --start-timeout S       a match not full S seconds after its first client ends,\n"
    "                          1 .. 86400 (default 60)\n"
    "  --token-max-lifetime S  refuse tokens expiring more than S seconds ahead, 1 .. 86400\n"
    "                          (default 3600)\n"
    "  --replay-cache N        admitted token nonces remembered at once, 1 .. 10000000\n"
    "                          (default 65536)\n"
    "  --rate-limit N          datagrams per second one source address may send before it is\n"
    "                          admitted, 1 .. 1000000 (default 20)\n"
    "  --rate-burst N          ... in one burst, 1 .. 1000000 (default 40)\n"
    "  --drain-seconds S       on SIGTERM: stop admitting, let matches run up to S seconds,\n"
    "                          0 .. 86400 (default 30)\n"
    "  --log FILE              JSON-lines log, '-' for standard output (default -)\n"
    "  --scene NAME            the library scene the clients play (needed by --replay-dir)\n"
    "  --replay-dir DIR        write each finished match's replay to DIR/match-ID.lbr\n"
    "  --agones-health-seconds S  when AGONES_SDK_HTTP_PORT is set (an Agones sidecar): the\n"
    "                          health ping interval, 1 .. 300 (default 2); the server also calls\n"
    "                          /ready once listening, labels 'matches' and 'players' as they\n"
    "                          change, and /shutdown after its last match\n"
    "  --help                  this text\n"
    "\n"
    "Exit codes: 0 after a drain (SIGTERM or SIGINT), 1 when the socket or a file cannot be\n"
    "opened, 2 for a bad option or config file.\n";

bool ReadMatchList(lockbox::cli::OptionReader& args, std::vector<uint32_t>& out) {
    std::string text;
    if (!args.Text(text)) return false;
    std::vector<uint32_t> ids;
    size_t at = 0;
    while (at <= text.size()) {
        const size_t comma = std::min(text.find(',', at), text.size());
        const std::string_view item = std::string_view(text).substr(at, comma - at);
        uint64_t v = 0;
        bool ok = !item.empty() && item.size() <= 10;
        for (char c : item) {
            ok = ok && c >= '0' && c <= '9';
            if (ok) v = v * 10 + static_cast<uint64_t>(c - '0');
        }
        if (!ok || v > 0xFFFFFFFFull)
            return args.Refuse("--matches needs match ids 0 .. 4294967295 separated by commas, not '" + text + "'");
        ids.push_back(static_cast<uint32_t>(v));
        at = comma + 1;
    }
    out = std::move(ids);
    return true;
}

// Applies the current option of `args`; false when it is not one of ours (Unknown() is called).
void ApplyOption(lockbox::cli::OptionReader& args, ServerOptions& o) {
    if (args.Is("--bind"))
        args.Text(o.bindHost);
    else if (args.Is("--port"))
        args.Int(0, 65535, o.port);
    else if (args.Is("--port-file"))
        args.Text(o.portFile);
    else if (args.Is("--http-port"))
        args.Int(0, 65535, o.httpPort);
    else if (args.Is("--token-key-file"))
        args.Text(o.tokenKeyFile);
    else if (args.Is("--matches"))
        ReadMatchList(args, o.matchIds);
    else if (args.Is("--max-matches"))
        args.Int(1, 100000, o.maxMatches);
    else if (args.Is("--max-players"))
        args.Int(1, 1000000, o.maxPlayers);
    else if (args.Is("--match-kind"))
        args.Choice({"lockstep-relay", "lockstep-authoritative", "rollback-relay"}, o.matchKind);
    else if (args.Is("--spectators-per-match"))
        args.Int(0, lockbox::net::kRelayMaxSlots - 2, o.spectatorsPerMatch);
    else if (args.Is("--peer-bandwidth"))
        args.Int(0, 1000000000, o.peerBytesPerSecond);
    else if (args.Is("--spectator-host-bandwidth")) {
        uint32_t v = 0;
        if (args.Int(0, 1000000000, v)) o.spectatorHostBytesPerSecond = v;
    } else if (args.Is("--players-per-match"))
        args.Int(1, 64, o.playersPerMatch);
    else if (args.Is("--input-bytes"))
        args.Int(1, 256, o.inputBytes);
    else if (args.Is("--tick-rate"))
        args.Int(1, 1000, o.tickRate);
    else if (args.Is("--hash-interval"))
        args.Int(1, 100000, o.hashInterval);
    else if (args.Is("--start-timeout"))
        args.Int(1, 86400, o.startTimeoutSeconds);
    else if (args.Is("--token-max-lifetime"))
        args.Int(1, 86400, o.tokenMaxLifetimeSeconds);
    else if (args.Is("--replay-cache"))
        args.Int(1, 10000000, o.replayCacheSize);
    else if (args.Is("--rate-limit"))
        args.Int(1, 1000000, o.rateLimitPerSecond);
    else if (args.Is("--rate-burst"))
        args.Int(1, 1000000, o.rateLimitBurst);
    else if (args.Is("--drain-seconds"))
        args.Int(0, 86400, o.drainSeconds);
    else if (args.Is("--log"))
        args.Text(o.logFile);
    else if (args.Is("--scene"))
        args.Text(o.scene);
    else if (args.Is("--replay-dir"))
        args.Text(o.replayDir);
    else if (args.Is("--agones-health-seconds"))
        args.Int(1, 300, o.agonesHealthSeconds);
    else
        args.Unknown();
}

std::string_view Trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

// Reads a config file into `o`; false after printing "lockbox_server: FILE:LINE: why".
bool ReadConfigFile(const std::string& path, ServerOptions& o) {
    std::ifstream in(path);
    if (!in) {
        std::fprintf(stderr, "lockbox_server: cannot open the config file '%s'\n", path.c_str());
        return false;
    }
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::string_view text = line;
        if (const size_t hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);
        text = Trim(text);
        if (text.empty()) continue;
        const size_t eq = text.find('=');
        const std::string where = path + ":" + std::to_string(number) + ": ";
        if (eq == std::string_view::npos) {
            std::fprintf(stderr, "lockbox_server: %sexpected 'key = value', not '%s'\n", where.c_str(),
                         std::string(text).c_str());
            return false;
        }
        std::string key = "--" + std::string(Trim(text.substr(0, eq)));
        std::string value(Trim(text.substr(eq + 1)));
        if (key == "--config" || key == "--help") {
            std::fprintf(stderr, "lockbox_server: %s'%s' is not allowed in a config file\n", where.c_str(),
                         key.c_str() + 2);
            return false;
        }
        std::string program = "lockbox_server";
        char* argv[] = {program.data(), key.data(), value.data()};
        lockbox::cli::OptionReader args("lockbox_server", 3, argv);
        while (args.Next()) ApplyOption(args, o);
        if (args.Failed()) {
            std::string error = args.Error();
            // "unknown option '--x'" reads better as "unknown key 'x'" in a file.
            if (error.rfind("unknown option", 0) == 0)
                error = "unknown key '" + key.substr(2) + "'";
            else if (error.rfind("--", 0) == 0)
                error = error.substr(2);
            std::fprintf(stderr, "lockbox_server: %s%s\n", where.c_str(), error.c_str());
            return false;
        }
    }
    return true;
}

}  // namespace

const char* UsageText() { return kUsage; }

int ReadOptions(int argc, char** argv, ServerOptions& out) {
    lockbox::cli::OptionReader args("lockbox_server", argc, argv);
    ServerOptions o;
    while (args.Next()) {
        if (args.Is("--help")) {
            std::fputs(kUsage, stdout);
            return 1;
        }
        if (args.Is("--config")) {
            std::string path;
            if (args.Text(path) && !ReadConfigFile(path, o)) return 2;
            continue;
        }
        ApplyOption(args, o);
    }
    if (!args.Failed() && o.tokenKeyFile.empty()) args.Refuse("--token-key-file is required");
    if (!args.Failed() && !o.replayDir.empty() && o.scene.empty()) args.Refuse("--replay-dir needs --scene");
    if (!args.Failed() && o.matchKind == "lockstep-authoritative" && o.scene.empty())
        args.Refuse("--match-kind lockstep-authoritative needs --scene");
    if (!args.Failed() && o.matchKind == "rollback-relay" &&
        (o.playersPerMatch < 2 || o.playersPerMatch + o.spectatorsPerMatch > lockbox::net::kRelayMaxSlots))
        args.Refuse(
            "--match-kind rollback-relay needs --players-per-match of at least 2 and at most 64 slots with "
            "--spectators-per-match");
    if (!args.Failed() && o.matchKind != "rollback-relay" && o.spectatorsPerMatch != 0)
        args.Refuse("--spectators-per-match needs --match-kind rollback-relay");
    if (args.Failed()) return args.Fail(kUsage);
    out = std::move(o);
    return 0;
}

}  // namespace lockbox::server
