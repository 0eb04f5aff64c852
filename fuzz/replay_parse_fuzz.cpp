// libFuzzer target for the replay parser: any byte string must parse or be refused
// with an error, never crash, hang or allocate without bound. A file that parses and names a
// scene is also played for up to 32 frames (its snapshots go through b2World::Restore's own
// validation). Seed corpus: tests/golden/replays.
#include <cstddef>
#include <cstdint>
#include <span>

#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace lockbox::replay;
    ReplayFile file;
    if (!ParseReplay(std::span<const uint8_t>(data, size), file).ok()) return 0;
    (void)file.NearestKeyframe(file.frameCount);
    const std::string scene = SceneGame::SceneName(file.gameName);
    if (scene.empty() || file.frameCount > 32) return 0;
    SceneGame game(scene);
    if (!game.ok()) return 0;
    Player player(file, game.world(), game);
    (void)player.Verify();
    return 0;
}
