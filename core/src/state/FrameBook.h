#pragma once
// A world's rollback-frame book-keeping (docs/determinism.md, "Rollback frames"). None of it
// is state: snapshots and the hash ignore it, and a restore never rolls it back.
//
// Frames copy only what steps and inputs change; the structure (bodies', fixtures' and joints'
// set-up, shapes, pool layouts) is shared through one portable image per structure epoch.
// Every structural change moves the epoch, so a frame whose epoch is the world's needs no
// structure restore. Changes confined to one body, or to one joint and its bodies, are also
// logged, so that a frame saved before a spawn can undo it by destroying what was spawned.

#include <memory>
#include <vector>

#include "lockbox/common/Settings.h"

namespace lockbox::state_detail {

/// A structural change confined to one body, or to one joint and its two bodies: the epoch
/// it made and the ids.
struct StructureChange {
    uint64 epoch = 0;
    int32 body = -1;       ///< the body, or the joint's body A
    int32 otherBody = -1;  ///< the joint's body B (-1 for a body's change)
    int32 joint = -1;      ///< the joint (-1 for a body's change)
};

/// How a world's RestoreFrame calls went.
struct FrameRestoreCounts {
    uint64 sameStructure = 0;      ///< the structure was the frame's: arrays only
    uint64 undoneCreations = 0;    ///< bodies created since the frame were destroyed, then arrays
    uint64 restoredStructure = 0;  ///< the frame's structure image was restored, then arrays
};

struct FrameCache;
/// Frees a world's frame cache (defined where FrameCache is complete).
struct FrameCacheDeleter {
    void operator()(FrameCache* cache) const noexcept;
};

/// A serial no other world of this process has (frames check it).
uint64 NextWorldSerial() noexcept;

/// One world's book-keeping for its rollback frames.
struct FrameBook {
    /// Starts the epoch again (any structural change not confined to a body or a joint, and a
    /// full Restore): frames from before it restore their structure image.
    void MarkStructureChanged() noexcept {
        m_structureEpoch = ++m_epochSource;
        m_structureLogBase = m_structureEpoch;
        m_structureLog.clear();
    }
    /// Moves the epoch and logs `change` (its epoch filled in) when the world keeps frames.
    void LogStructureChange(StructureChange change) noexcept;

    /// This world's serial: a frame belongs to the world whose serial it carries.
    uint64 m_serial = NextWorldSerial();
    /// The structure epoch: changes with every structural change, never repeats a value this
    /// world gave before (frames compare it).
    uint64 m_structureEpoch = 0;
    /// The last epoch given out (never restored, so an epoch value is never reused).
    uint64 m_epochSource = 0;
    /// The confined changes since the epoch m_structureLogBase, oldest first: the last one's
    /// epoch is m_structureEpoch (the base, when empty). Any other change starts it again.
    std::vector<StructureChange> m_structureLog;
    uint64 m_structureLogBase = 0;
    FrameRestoreCounts m_restores;
    /// The current epoch's structure image and restore scratch; made by the first SaveFrame
    /// (a world that never saves a frame keeps no log).
    mutable std::unique_ptr<FrameCache, FrameCacheDeleter> m_cache;
};

}  // namespace lockbox::state_detail
