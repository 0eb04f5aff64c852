#pragma once
// What a rollback frame holds (lockbox/state/WorldFrame.h): native arrays of what steps and
// inputs change, and a shared reference to its epoch's structure (state/FrameBook.h).

#include <memory>
#include <vector>

#include "lockbox/collision/Collision.h"
#include "lockbox/collision/DynamicTree.h"
#include "lockbox/common/Settings.h"
#include "lockbox/state/WorldFrame.h"

namespace lockbox {

namespace frame_detail {

/// What a step changes on a body (64 bytes).
struct BodyMotion {
    b2Transform xf;
    b2Vec2 c0, c;
    Fixed a0, a, alpha0;
    b2Vec2 v;
    Fixed w;
    int32 velocityRemainder[3] = {};  ///< below Q16.16 (b2Body::SubRaw)
    int32 positionRemainder[3] = {};
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

/// The structure one epoch shares among its frames: the portable image (Save's layout without
/// contacts) and the body, fixture and joint layouts, which undoing creations puts back.
struct Structure {
    std::vector<uint8> image;
    std::vector<uint8> bodyLive, fixtureLive, jointLive;  ///< a flag per slot (joints: per id)
    std::vector<int32> bodyFree, fixtureFree;             ///< free stacks, bottom first
};

}  // namespace frame_detail

/// A frame's contents. Saving into a frame reuses every array's capacity.
struct b2WorldFrame::Data {
    uint64 m_serial = 0;  ///< the saving world's serial (FrameBook::m_serial); 0: empty
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
