#pragma once
/// Rollback frames (issue 7, docs/determinism.md "Rollback frames"): the state of a world kept
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
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/DynamicTree.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

class b2World;

namespace frame_detail {

/// What a step changes on a body (64 bytes).
struct BodyMotion {
    b2Transform xf;
    b2Vec2 c0, c;
    Fixed a0, a, alpha0;
    b2Vec2 v;
    Fixed w;
    int32 sleepSteps = 0;
    uint32 flags = 0;
};

/// A pending force (only bodies with one are listed; the others have none).
struct BodyForce {
    int32 body = 0;  ///< index in body-list order
    b2Vec2 force;
    Fixed torque;
};

/// A contact without its manifold points (which follow in b2WorldFrame's point array).
struct ContactRecord {
    int32 id = -1;
    int32 fixtureA = -1, indexA = 0, fixtureB = -1, indexB = 0;
    uint32 flags = 0;
    int32 toiCount = 0;
    Fixed toi, friction, restitution;
    uint8 manifoldType = 0;
    uint8 pointCount = 0;
    b2Vec2 localNormal, localPoint;
};

struct Settings {
    b2Vec2 gravity;
    bool allowSleep = true, warmStarting = true, continuous = true, subStepping = false, autoClear = true;
    bool stepComplete = true;
    b2AABB bounds;
    uint32 flags = 0;
    Fixed invDt0;
    uint64 saturations = 0;
};

}  // namespace frame_detail

/// A structural change confined to one body (b2World::MarkBodyStructureChanged), or to one
/// joint and its two bodies (MarkJointStructureChanged): the epoch it made and the ids.
struct b2StructureChange {
    uint64 epoch = 0;
    int32 body = -1;       ///< the body, or the joint's body A
    int32 otherBody = -1;  ///< the joint's body B (-1 for a body's change)
    int32 joint = -1;      ///< the joint (-1 for a body's change)
};

/// How a world's RestoreFrame calls went (b2World::GetFrameRestoreCounts).
struct b2FrameRestoreCounts {
    uint64 sameStructure = 0;      ///< the structure was the frame's: arrays only
    uint64 undoneCreations = 0;    ///< bodies created since the frame were destroyed, then arrays
    uint64 restoredStructure = 0;  ///< the frame's structure image was restored, then arrays
};

namespace frame_detail {

/// The structure one epoch shares among its frames: the portable image (Save's layout without
/// contacts) and the body, fixture and joint layouts, which undoing creations puts back.
struct Structure {
    std::vector<uint8> image;
    std::vector<uint8> bodyLive, fixtureLive, jointLive;  ///< a flag per slot (joints: per id)
    std::vector<int32> bodyFree, fixtureFree;             ///< free stacks, bottom first
};

}  // namespace frame_detail

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

/// A world's state at one moment, for that world's RestoreFrame. Reuse frames (a ring): a
/// save into a used frame keeps its capacity and does not allocate once sizes settle.
class LOCKBOX_API b2WorldFrame {
public:
    b2WorldFrame() = default;
    /// True before the first SaveFrame into it.
    bool IsEmpty() const noexcept { return m_serial == 0; }
    /// The frame's byte counts; the structure image is counted apart (frames share it).
    b2FrameStats Stats() const noexcept;

private:
    friend class b2World;
    friend struct FrameAccess;
    friend struct FrameUndo;

    uint64 m_serial = 0;  ///< the saving world's serial (b2World::m_serial); 0: empty
    uint64 m_epoch = 0;   ///< the saving world's structure epoch
    std::shared_ptr<const frame_detail::Structure> m_structure;  ///< that epoch's structure
    uint64 m_checkHash = 0;  ///< b2WorldHash at the save (checked builds; 0 otherwise)
    frame_detail::Settings m_settings;
    std::vector<frame_detail::BodyMotion> m_bodies;       ///< body-list order
    std::vector<frame_detail::BodyForce> m_forces;        ///< ascending body index
    std::vector<b2AABB> m_proxies;                        ///< each body's fixtures' proxies, body then fixture order
    std::vector<uint8> m_contactLive;                     ///< contact pool: a flag per slot
    std::vector<int32> m_contactFree;                     ///< contact pool: free stack, bottom first
    std::vector<frame_detail::ContactRecord> m_contacts;  ///< contact-list order
    std::vector<b2ManifoldPoint> m_points;                ///< each contact's manifold points, in order
    std::vector<uint8> m_joints;                          ///< per joint (id order): user data, VisitState, reaction
    std::vector<b2TreeNode> m_nodes;
    int32 m_treeRoot = b2_nullNode, m_treeFree = b2_nullNode, m_treeNodeCount = 0, m_treeInsertions = 0;
    int32 m_proxyCount = 0;
    std::vector<int32> m_moveBuffer;
};

}  // namespace lockbox
