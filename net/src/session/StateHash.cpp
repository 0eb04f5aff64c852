// The state hash fold (StateHash.h).

#include "lockbox/net/StateHash.h"

#include <vector>

#include "lockbox/dynamics/World.h"
#include "lockbox/state/WorldGame.h"

namespace lockbox::net {

uint64_t FoldUserState(uint64_t worldHash, std::span<const uint8_t> user) noexcept {
    uint64_t h = worldHash;
    if (user.empty()) return h;
    uint64_t f = 0xCBF29CE484222325ull;
    for (uint8_t b : user) f = (f ^ b) * 0x100000001B3ull;
    // Mix so that a user-state change flips about half the bits of the result.
    h ^= f + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDull;
    h ^= h >> 33;
    return h;
}

uint64_t FoldUserState(uint64_t worldHash, const WorldGame& game) {
    std::vector<uint8> user;
    game.SaveUserState(user);
    return FoldUserState(worldHash, user);
}

uint64_t FoldedStateHash(const b2World& world, const WorldGame& game) { return FoldUserState(world.Hash(), game); }

}  // namespace lockbox::net
