// The scene templates instantiated for lockbox (so a scene that does not compile on lockbox
// breaks this library, not only its users), the lockbox registry and the world hash.
#include "lockbox/scenes/LockboxScenes.h"

#include <xxhash.h>

#include <vector>

namespace lockbox::scenes {

template class HelloScene<LockboxEngine>;
template class VerticalStackScene<LockboxEngine>;
template class Pyramid20Scene<LockboxEngine>;
template class LargePyramidScene<LockboxEngine>;
template class ManyPyramidsScene<LockboxEngine>;
template class RainScene<LockboxEngine>;
template class JointGridScene<LockboxEngine>;
template class TumblerScene<LockboxEngine>;
template class Chain60Scene<LockboxEngine>;
template class BulletScene<LockboxEngine>;
template class CarScene<LockboxEngine>;
template class RagdollsScene<LockboxEngine>;
template class PulleyGearScene<LockboxEngine>;
template class OneSidedPlatformScene<LockboxEngine>;
template class PendulumScene<LockboxEngine>;
template class SlopeScene<LockboxEngine>;

std::unique_ptr<LockboxScene> MakeLockboxScene(std::string_view name) { return MakeScene<LockboxEngine>(name); }

uint64_t HashWorld(const b2World& world) {
    std::vector<uint8_t> bytes;
    auto put = [&bytes](Fixed v) {
        // Little-endian bytes of the raw value, independent of the host's byte order.
        const auto u = static_cast<uint32_t>(v.Raw());
        for (int s = 0; s < 32; s += 8) bytes.push_back(static_cast<uint8_t>(u >> s));
    };
    for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        put(b->GetPosition().x);
        put(b->GetPosition().y);
        put(b->GetAngle());
        put(b->GetLinearVelocity().x);
        put(b->GetLinearVelocity().y);
        put(b->GetAngularVelocity());
    }
    return XXH3_64bits(bytes.data(), bytes.size());
}

}  // namespace lockbox::scenes
