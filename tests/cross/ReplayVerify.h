#pragma once
// Golden replays across builds: replays recorded on one architecture verify on the others.
// The cross driver plays every replay named with --replays through
// lockbox::replay::Player::Verify and prints one line per file; the line (frames, final hash)
// must be the same in every cell, and a replay that does not verify fails the cell.
//
// The cross toolchains have no zstd library, so run.sh builds replay/ with
// LOCKBOX_REPLAY_ZSTD=0 and passes only the corpus files recorded uncompressed (--level 0 in
// tests/golden/replays/record.sh). This header compiles to nothing unless LOCKBOX_CROSS_REPLAY
// is defined.
#if defined(LOCKBOX_CROSS_REPLAY)
#define LOCKBOX_CROSS_HAS_REPLAY 1

#include <cstdio>
#include <string>
#include <string_view>

#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::replay_verify {

/// Verifies one replay file; prints "ok   replay NAME frames=N hash=0x..." or a FAIL line
/// naming the problem. Returns whether it verified.
inline bool VerifyLine(const std::string& path) {
    using namespace lockbox::replay;
    const size_t slash = path.find_last_of('/');
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    ReplayFile file;
    if (Error e = LoadReplay(path, file); !e.ok()) {
        std::printf("FAIL replay %s load: %s\n", name.c_str(), e.Describe().c_str());
        return false;
    }
    SceneGame game(SceneGame::SceneName(file.gameName));
    if (!game.ok()) {
        std::printf("FAIL replay %s: unknown game '%s'\n", name.c_str(), file.gameName.c_str());
        return false;
    }
    Player player(file, game.world(), game);
    const VerifyResult r = player.Verify();
    if (!r.ok) {
        std::printf("FAIL replay %s: %s\n", name.c_str(), r.message.c_str());
        return false;
    }
    std::printf("ok   replay %s frames=%d hash=0x%016llx\n", name.c_str(), r.frames,
                static_cast<unsigned long long>(r.finalHash));
    return true;
}

}  // namespace lockbox::replay_verify

#endif
