#pragma once
/// Verifying a directory of replays on every core (docs/replay.md, "verify-dir"): the core of a
/// replay verification service, e.g. behind a match server that writes one replay per match.
/// Every `*.lbr` file directly in the directory is loaded and played from its seed with the
/// game its registry builds, on worker threads; the results come back sorted by file name, so
/// the output does not depend on the thread count or timing.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "lockbox/replay/Tool.h"

namespace lockbox::replay {

/// What one replay of the directory gave.
struct VerifyDirEntry {
    enum class Outcome : uint8_t {
        e_verified,  ///< every stored hash and the final hash matched
        e_diverged,  ///< the re-simulation differs from `firstBadFrame` on
        e_corrupt,   ///< the file could not be read or played (`reason`)
    };
    std::string name;  ///< the file name, without the directory
    Outcome outcome = Outcome::e_corrupt;
    int32_t frames = 0;          ///< frames played
    int32_t firstBadFrame = -1;  ///< e_diverged: the first frame whose state differs
    std::string reason;          ///< e_corrupt: why (one line)
};

/// The whole directory.
struct VerifyDirReport {
    std::vector<VerifyDirEntry> entries;  ///< sorted by name
    size_t verified = 0, diverged = 0, corrupt = 0;
};

/// Verifies every `*.lbr` file directly in `dir` with `threads` workers (0: one per core).
/// `options` reach the registry's factories (ToolGameRequest::options). False, with `error`,
/// when the directory cannot be listed.
bool VerifyDirectory(const std::string& dir, const GameRegistry& games, unsigned threads,
                     const std::map<std::string, std::string>& options, VerifyDirReport& out, std::string& error);

/// The `verify-dir DIR [--jobs N]` command (argv[0] is "verify-dir"), with the registry's options:
/// one line per replay in name order, then the summary. Exit codes: 0 every replay verified,
/// 1 one diverged or is corrupt, 2 a usage error or a directory that cannot be listed.
int RunVerifyDir(int argc, char** argv, const GameRegistry& games, const std::string& program = "lockbox_replay");

/// The usage line of the command (without the program name).
inline constexpr const char* kVerifyDirUsage = "verify-dir DIR [--jobs N]";

}  // namespace lockbox::replay
