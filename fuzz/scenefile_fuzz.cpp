// libFuzzer target for the scene-file loader: any byte string must load or be refused with an
// error, never crash, hang or allocate without bound. A file that loads is built into a world,
// saved, and loaded again: what lockbox writes must always load, to the same state hash. Seed
// corpus: the hand-written and small library scene files and the bad files of the tests.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lockbox/scenefile/SceneFile.h"
#include "lockbox/state/WorldHash.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace lockbox;
    using namespace lockbox::scenefile;
    // Small bounds keep each input fast; the limits themselves are part of what is fuzzed.
    SceneLimits limits;
    limits.maxFileBytes = 1 << 20;
    limits.maxValues = 1 << 16;
    limits.maxBodies = 256;
    limits.maxFixtures = 1024;
    limits.maxJoints = 256;
    limits.maxChainVertices = 1024;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    SceneDocument doc;
    if (!ReadScene(text, doc, limits)) return 0;
    b2World world(doc.world.gravity);
    SceneMetadata meta;
    if (!BuildScene(doc, world, &meta)) return 0;

    const std::string saved = SaveScene(world, &meta);
    SceneResult again;
    auto reloaded = LoadSceneWorld(saved, &again);
    if (!reloaded || b2WorldHash(*reloaded) != b2WorldHash(world)) __builtin_trap();
    return 0;
}
