#pragma once
/// @file
/// Rollback frames (docs/determinism.md, "Rollback frames"): the state of a world kept
/// in memory by that same world, for rollback rings. b2World::SaveFrame copies only what a step
/// or an input can change without a structural call (body motion, forces, proxy boxes,
/// contacts, joint state, the broad-phase tree, the step carry-over) into native arrays; the
/// structure (bodies' and fixtures' set-up, shapes, pool layouts, joints' links) is shared
/// through one portable image per structure epoch. RestoreFrame writes the arrays back in
/// place, and first restores the shared image when the world's structure changed since the
/// frame was saved. Either way, stepping afterwards gives exactly the bits the saved world gave.
///
/// A frame is not a portable snapshot: it holds native integers and belongs to the world that
/// saved it (another world refuses it). Save/Restore remain the format for files, peers and
/// late joins. Sizes: 64 bytes per body, 16 per body with a pending force, 16 per proxy, 64 per
/// contact plus 32 per manifold point, the tree's nodes, and the joints' state fields.

#include <memory>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

namespace core_detail {
struct Engine;
}  // namespace core_detail

/// Byte counts of one frame (b2WorldFrame::Stats).
struct b2FrameStats {
    uint32 bodyBytes = 0;        ///< body motion (64 per body)
    uint32 forceBytes = 0;       ///< pending forces (16 per body that has one)
    uint32 proxyBytes = 0;       ///< proxy boxes (16 per proxy)
    uint32 contactBytes = 0;     ///< contacts, manifold points and the contact pool's layout
    uint32 jointBytes = 0;       ///< joints' state fields
    uint32 broadPhaseBytes = 0;  ///< tree nodes and move buffer
    uint32 frameBytes = 0;       ///< all of the above plus the fixed part: this frame's own memory
    uint32 structureBytes = 0;   ///< the structure image and pool layouts (shared with other frames)
};

/// A world's state at one moment, for that world's RestoreFrame. Reuse frames (a ring): the
/// first save into a frame allocates its storage, and later saves into it reuse that storage,
/// so a ring of frames saves without allocating once sizes settle. Copies are deep.
class LOCKBOX_API b2WorldFrame {
public:
    b2WorldFrame() noexcept;
    ~b2WorldFrame();
    /// Deep copy: the copy owns its own storage and restores the same state.
    ///@{
    b2WorldFrame(const b2WorldFrame& other);
    b2WorldFrame& operator=(const b2WorldFrame& other);
    ///@}
    /// Move: takes the other frame's storage and leaves it empty (as a default-constructed frame).
    ///@{
    b2WorldFrame(b2WorldFrame&& other) noexcept;
    b2WorldFrame& operator=(b2WorldFrame&& other) noexcept;
    ///@}

    /// True before the first SaveFrame into it.
    bool IsEmpty() const noexcept;
    /// The frame's byte counts; the structure image is counted apart (frames share it).
    b2FrameStats Stats() const noexcept;

private:
    friend struct core_detail::Engine;
    /// The frame's arrays and its reference to the shared structure (core/src).
    struct Data;
    std::unique_ptr<Data> m_data;
};

}  // namespace lockbox
