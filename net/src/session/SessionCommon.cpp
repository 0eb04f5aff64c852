// Shared session helpers (SessionCommon.h).

#include "session/SessionCommon.h"

#include <vector>

#include "lockbox/dynamics/World.h"
#include "lockbox/replay/Game.h"

namespace lockbox::net {

void StepConfirmedFrame(b2World& world, replay::Game& game, int32_t frame, std::span<const uint8_t> inputs,
                        uint32_t tickRate, uint32_t velocityIterations, uint32_t positionIterations) {
    game.Apply(world, frame, inputs);
    // The same step as replay::Recorder: 1/tickRate seconds rounded once to Q16.16.
    world.Step(Fixed::FromRatio(1, tickRate == 0 ? 1 : tickRate), static_cast<int32>(velocityIterations),
               static_cast<int32>(positionIterations));
}

namespace {
void PutU32(std::vector<uint8_t>& out, size_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
bool GetU32(std::span<const uint8_t> in, size_t at, uint32_t& v) {
    if (in.size() < 4 || at > in.size() - 4) return false;
    v = 0;
    for (size_t i = 0; i < 4; ++i) v |= static_cast<uint32_t>(in[at + i]) << (8 * i);
    return true;
}
}  // namespace

void PackStateBlob(std::span<const uint8_t> image, std::span<const uint8_t> user, std::vector<uint8_t>& out) {
    out.clear();
    out.reserve(8 + image.size() + user.size());
    PutU32(out, image.size());
    out.insert(out.end(), image.begin(), image.end());
    PutU32(out, user.size());
    out.insert(out.end(), user.begin(), user.end());
}

bool LoadStateBlob(std::span<const uint8_t> blob, b2World& world, replay::Game& game) {
    uint32_t imageSize = 0, userSize = 0;
    if (!GetU32(blob, 0, imageSize) || imageSize > blob.size() - 4) return false;
    const size_t userAt = 4 + size_t{imageSize};
    if (!GetU32(blob, userAt, userSize) || userSize != blob.size() - userAt - 4) return false;
    if (!world.Restore(blob.subspan(4, imageSize)).ok()) return false;
    game.LoadUserState(blob.subspan(userAt + 4, userSize));
    return true;
}

}  // namespace lockbox::net
