// Shared session helpers (SessionCommon.h).

#include "SessionCommon.h"

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

uint64_t FoldedStateHash(const b2World& world, const replay::Game& game) {
    return FoldUserState(world.Hash(), game);
}

uint64_t FoldUserState(uint64_t worldHash, const replay::Game& game) {
    uint64_t h = worldHash;
    std::vector<uint8> user;
    game.SaveUserState(user);
    if (user.empty()) return h;
    uint64_t f = 0xCBF29CE484222325ull;
    for (uint8 b : user) f = (f ^ b) * 0x100000001B3ull;
    // Mix so that a user-state change flips about half the bits of the result.
    h ^= f + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDull;
    h ^= h >> 33;
    return h;
}

}  // namespace lockbox::net
