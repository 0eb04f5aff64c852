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
#include <string>

#include "LockstepMatch.h"
#include "OfflineRun.h"
#include "RollbackMatch.h"
#include "lockbox_cli/OptionReader.h"

namespace {

constexpr const char* kUsage =
    "usage: lockbox_demo [--scene NAME] [--clients 1..16] [--frames N] [--transport udp|enet]\n"
    "                    [--authoritative] [--input-delay N] [--seed S] [--replay FILE]\n"
    "       lockbox_demo --mode rollback [--scene NAME] [--frames N] [--input-delay N] [--window N]\n"
    "                    [--latency-ms N] [--seed S] [--budget-ms N]\n"
    "       lockbox_demo --offline [--scene NAME] [--steps N]\n";

}  // namespace

int main(int argc, char** argv) {
    lockbox::demo::MatchOptions match;
    bool offline = false;
    std::string mode = "lockstep";
    lockbox::demo::RollbackOptions roll;
    long delay = -1, window = -1, latency = -1, budget = -1;
    std::string scene;
    long steps = -1;
    long seed = -1;
    lockbox::cli::OptionReader args("lockbox_demo", argc, argv);
    while (args.Next()) {
        if (args.Is("--offline")) {
            offline = true;
        } else if (args.Is("--mode")) {
            args.Choice({"lockstep", "rollback"}, mode);
        } else if (args.Is("--window")) {
            args.Int(1, 64, window);
        } else if (args.Is("--budget-ms")) {
            args.Int(0, 1000, budget);
        } else if (args.Is("--latency-ms")) {
            args.Int(0, 1000, latency);
        } else if (args.Is("--authoritative")) {
            match.authoritative = true;
        } else if (args.Is("--scene")) {
            args.Text(scene);
        } else if (args.Is("--steps")) {
            args.Int(-1, 1000000, steps);
        } else if (args.Is("--clients")) {
            args.Int(1, 16, match.clients);
        } else if (args.Is("--frames")) {
            args.Int(1, 1000000, match.frames);
        } else if (args.Is("--input-delay")) {
            args.Int(0, 255, delay);
        } else if (args.Is("--seed")) {
            if (args.Int(0, 2147483647, seed)) match.seed = static_cast<uint64_t>(seed);
        } else if (args.Is("--transport")) {
            args.Choice({"udp", "enet"}, match.transport);
        } else if (args.Is("--replay")) {
            args.Text(match.replayPath);
        } else {
            args.Unknown();
        }
    }
    if (args.Failed()) return args.Fail(kUsage);
    const bool rollback = mode == "rollback";
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
