#pragma once
// The demo's offline mode: Hello World, then one library scene in one world (no network).
#include <string>

/// Runs the manual's Hello World and then `scene` for `steps` steps (-1: the scene's default),
/// printing the state hash every 60 steps. Returns the process exit code.
int RunOffline(const std::string& scene, int steps);
