#pragma once
// The main demo: a lockstep match on loopback. A LockstepServer and N
// LockstepClients, each on its own thread with its own socket (UDP or ENet on 127.0.0.1), play
// a library scene for a number of frames; every player pushes bodies around with scripted
// inputs. Every second the demo prints each client's frame, RTT, input delay and state hash;
// at the end it says whether all clients agree on the final hash, writes client 0's confirmed
// frames as a replay and verifies that replay in a fresh world.

#include <cstdint>
#include <string>

namespace lockbox::demo {

/// What the match plays.
struct MatchOptions {
    std::string scene = "ragdolls";  ///< a library scene (scenes)
    int clients = 4;                 ///< players, 1 .. 16
    int frames = 600;                ///< frames to play (10 s at 60 Hz)
    std::string transport = "udp";   ///< "udp" or "enet"
    bool authoritative = false;      ///< the server simulates too (its hash joins the comparison)
    int inputDelay = 0;              ///< frames; 0: automatic from the measured RTT
    uint64_t seed = 1;               ///< scripted inputs of player i use seed + i
    std::string replayPath;          ///< where the replay goes; empty: the system temp folder
};

/// Plays the match; returns the process exit code (0: every client agreed on every compared
/// hash and the replay verified).
int RunLockstepMatch(const MatchOptions& options);

}  // namespace lockbox::demo
