// Shared session helpers (SessionCommon.h).

#include "session/SessionCommon.h"

#include <vector>

#include "lockbox/common/Bytes.h"
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

void PackStateBlob(std::span<const uint8_t> image, std::span<const uint8_t> user, std::vector<uint8_t>& out) {
    out.clear();
    out.reserve(8 + image.size() + user.size());
    bytes::Writer w(out);
    w.Blob(image);
    w.Blob(user);
}

bool LoadStateBlob(std::span<const uint8_t> blob, b2World& world, replay::Game& game) {
    bytes::Reader r(blob);
    const std::span<const uint8_t> image = r.Blob();
    const std::span<const uint8_t> user = r.Blob();
    if (!r.Ok() || !r.AtEnd()) return false;
    if (!world.Restore(image).ok()) return false;
    game.LoadUserState(user);
    return true;
}

}  // namespace lockbox::net
