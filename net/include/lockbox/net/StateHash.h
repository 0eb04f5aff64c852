#pragma once
/// @file
/// The state hash lockbox's sessions compare between machines (rollback desync detection,
/// lockstep hash reports, the spectator and late-join checks): the world's hash folded with
/// the game's user state (docs/rollback.md, "The state hash"). A game that executes rollback
/// requests with its own code instead of WorldGameAdapter reports this value to
/// RollbackSession::ReportHash, so it agrees with peers that use the adapter.
///
/// The fold, for world hash W (b2World::Hash, XXH3-64 of the world) and user state U
/// (Game::SaveUserState's bytes): W itself when U is empty; otherwise, with F the 64-bit
/// FNV-1a of U (offset basis 0xCBF29CE484222325, prime 0x100000001B3), every operation
/// modulo 2^64:
///
///     h = W ^ (F + 0x9E3779B97F4A7C15 + (W << 6) + (W >> 2))
///     h ^= h >> 33;  h *= 0xFF51AFD7ED558CCD;  h ^= h >> 33
///
/// so that a change of U flips about half the bits of the result.

#include <cstdint>
#include <span>

#include "lockbox/Export.h"

namespace lockbox {
class b2World;
}
namespace lockbox {
class WorldGame;
}

namespace lockbox::net {

/// Folds user state `user` (Game::SaveUserState's bytes, any length) into world hash
/// `worldHash` (b2World::Hash) as described above.
LOCKBOX_API uint64_t FoldUserState(uint64_t worldHash, std::span<const uint8_t> user) noexcept;
/// The same fold with the game's current user state (calls Game::SaveUserState).
LOCKBOX_API uint64_t FoldUserState(uint64_t worldHash, const WorldGame& game);
/// FoldUserState(world.Hash(), game): the hash of a world and a game as sessions compare it.
/// Call outside Step.
LOCKBOX_API uint64_t FoldedStateHash(const b2World& world, const WorldGame& game);

}  // namespace lockbox::net
