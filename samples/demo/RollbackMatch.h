#pragma once
// The rollback demo (`lockbox_demo --mode rollback`): a 2-player peer-to-peer
// rollback match on loopback. Each player is a thread with its own UDP socket on 127.0.0.1,
// its own world (a replay::SceneGame), a RollbackSession, a WorldGameAdapter and a
// RollbackPeer; both push bodies around with scripted inputs at 60 Hz. A fixed one-way delay
// (net::LatencyTransport) sits in front of each socket so predictions are wrong now and then. Every
// second each player prints its frame, rollbacks per second, the deepest rollback and the
// re-simulation time per frame (and, with a budget, the input delay the budget guard chose);
// at the end the demo prints the hash both players agreed on.

#include <cstdint>
#include <string>

namespace lockbox::demo {

/// What the rollback match plays.
struct RollbackOptions {
    std::string scene = "ragdolls";  ///< a library scene (scenes) without scene-side state
    int frames = 600;                ///< frames to play (10 s at 60 Hz), 1 .. 1,000,000
    int inputDelay = 1;              ///< frames, 0 .. 16
    int window = 8;                  ///< prediction window, 1 .. 64
    int latencyMs = 40;              ///< one-way delay each player adds to what it receives, 0 .. 1000
    uint64_t seed = 1;               ///< scripted inputs of player i use seed * 1000 + i
    /// > 0: each player runs a RollbackBudgetGuard with this budget (ms per rollback tick, p99)
    /// on its measured re-simulation times and the players apply each other's delay wish.
    int budgetMs = 0;
};

/// Plays the match; returns the process exit code (0: both players confirmed every frame,
/// agreed on every compared hash and saw no desync; 1: a failure; 2: bad options).
int RunRollbackMatch(const RollbackOptions& options);

}  // namespace lockbox::demo
