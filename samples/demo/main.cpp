// lockbox_demo: the main demo (README's first command).
//
// By default a lockstep match on loopback (LockstepMatch.h): a server and 4 clients on their
// own threads and sockets play a library scene for 600 frames with scripted inputs; every
// second it prints each client's frame, RTT, input delay and state hash, then whether all
// clients agree, and it writes and verifies a replay of the match.
//
//   lockbox_demo [--scene NAME] [--clients N] [--frames N] [--transport udp|enet]
//                [--authoritative] [--input-delay N] [--seed S] [--replay FILE]
//   lockbox_demo --mode rollback [--scene NAME] [--frames N] [--input-delay N] [--window N]
//                [--latency-ms N] [--seed S] [--budget-ms N] a 2-player rollback match (RollbackMatch.h)
//   lockbox_demo --offline [--scene NAME] [--steps N]   Hello World, then one scene, no network
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "LockstepMatch.h"
#include "OfflineRun.h"
#include "RollbackMatch.h"

namespace {

int Usage() {
    std::fprintf(stderr,
                 "usage: lockbox_demo [--scene NAME] [--clients 1..16] [--frames N] [--transport udp|enet]\n"
                 "                    [--authoritative] [--input-delay N] [--seed S] [--replay FILE]\n"
                 "       lockbox_demo --mode rollback [--scene NAME] [--frames N] [--input-delay N] [--window N]\n"
                 "                    [--latency-ms N] [--seed S] [--budget-ms N]\n"
                 "       lockbox_demo --offline [--scene NAME] [--steps N]\n");
    return 2;
}

// Parses a whole decimal argument in [lo, hi]; false otherwise.
bool ParseInt(const char* text, long lo, long hi, long& out) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi) return false;
    out = v;
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    lockbox::demo::MatchOptions match;
    bool offline = false;
    bool rollback = false;
    lockbox::demo::RollbackOptions roll;
    long delay = -1, window = -1, latency = -1, budget = -1;
    std::string scene;
    long steps = -1;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool hasValue = i + 1 < argc;
        long v = 0;
        if (a == "--offline") {
            offline = true;
        } else if (a == "--mode" && hasValue &&
                   (std::strcmp(argv[i + 1], "rollback") == 0 || std::strcmp(argv[i + 1], "lockstep") == 0)) {
            rollback = std::strcmp(argv[++i], "rollback") == 0;
        } else if (a == "--window" && hasValue && ParseInt(argv[i + 1], 1, 64, v)) {
            window = v;
            ++i;
        } else if (a == "--budget-ms" && hasValue && ParseInt(argv[i + 1], 0, 1000, v)) {
            budget = v;
            ++i;
        } else if (a == "--latency-ms" && hasValue && ParseInt(argv[i + 1], 0, 1000, v)) {
            latency = v;
            ++i;
        } else if (a == "--authoritative") {
            match.authoritative = true;
        } else if (a == "--scene" && hasValue) {
            scene = argv[++i];
        } else if (a == "--steps" && hasValue && ParseInt(argv[i + 1], -1, 1000000, v)) {
            steps = v;
            ++i;
        } else if (a == "--clients" && hasValue && ParseInt(argv[i + 1], 1, 16, v)) {
            match.clients = static_cast<int>(v);
            ++i;
        } else if (a == "--frames" && hasValue && ParseInt(argv[i + 1], 1, 1000000, v)) {
            match.frames = static_cast<int>(v);
            ++i;
        } else if (a == "--input-delay" && hasValue && ParseInt(argv[i + 1], 0, 255, v)) {
            delay = v;
            ++i;
        } else if (a == "--seed" && hasValue && ParseInt(argv[i + 1], 0, 2147483647, v)) {
            match.seed = static_cast<uint64_t>(v);
            ++i;
        } else if (a == "--transport" && hasValue &&
                   (std::strcmp(argv[i + 1], "udp") == 0 || std::strcmp(argv[i + 1], "enet") == 0)) {
            match.transport = argv[++i];
        } else if (a == "--replay" && hasValue) {
            match.replayPath = argv[++i];
        } else {
            return Usage();
        }
    }
    if (offline) return RunOffline(scene.empty() ? "pyramid20" : scene, static_cast<int>(steps));
    if (rollback) {
        if (!scene.empty()) roll.scene = scene;
        roll.frames = match.frames;
        roll.seed = match.seed;
        if (delay >= 0) roll.inputDelay = static_cast<int>(delay);
        if (window >= 0) roll.window = static_cast<int>(window);
        if (latency >= 0) roll.latencyMs = static_cast<int>(latency);
        if (budget >= 0) roll.budgetMs = static_cast<int>(budget);
        return lockbox::demo::RunRollbackMatch(roll);
    }
    if (delay >= 0) match.inputDelay = static_cast<int>(delay);
    if (!scene.empty()) match.scene = scene;
    return lockbox::demo::RunLockstepMatch(match);
}
