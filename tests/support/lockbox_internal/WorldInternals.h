#pragma once
// Test-only access to a world's internals. Tests and benchmarks that measure the engine's own
// book-keeping (the rollback frames' structure epoch, their log and restore paths) include
// this header; it needs core/src on the include path, which only their CMake targets add.
// Nothing here is public API: the engine may change it at any time.

#include <cstddef>
#include <vector>

#include "dynamics/WorldState.h"
#include "lockbox/dynamics/World.h"
#include "state/FrameBook.h"
#include "state/FrameData.h"

namespace lockbox::test {

/// The world's internal state (pools, lists, switches, frame book-keeping).
inline core_detail::Engine::World& Internals(b2World& world) { return core_detail::Engine::Of(world); }
inline const core_detail::Engine::World& Internals(const b2World& world) { return core_detail::Engine::Of(world); }

/// The structure epoch of rollback frames: moves with every structural change, never repeats.
inline uint64 StructureEpoch(const b2World& world) { return Internals(world).m_frames.m_structureEpoch; }

/// Starts the structure epoch again, as a change that no frame can undo would.
inline void MarkStructureChanged(b2World& world) { Internals(world).MarkStructureChanged(); }

/// How the world's RestoreFrame calls went so far (same structure, creations undone,
/// structure image restored).
inline state_detail::FrameRestoreCounts FrameRestores(const b2World& world) {
    return Internals(world).m_frames.m_restores;
}

/// Makes the time-of-impact event search visit every contact (2.2.1's search, the reference)
/// instead of its candidates only.
inline void SetToiSearchEveryContact(b2World& world, bool every) { Internals(world).m_toiSearchEveryContact = every; }

/// Entries in the log of confined structural changes.
inline size_t StructureLogSize(const b2World& world) { return Internals(world).m_frames.m_structureLog.size(); }

}  // namespace lockbox::test
