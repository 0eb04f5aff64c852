#pragma once
// Internal to the snapshot: a parsed and fully validated image, held apart from the world so
// that Restore can refuse a bad image before it touches anything (SnapshotParse.cpp reads
// and checks it, SnapshotApply.cpp installs it).

#include <span>
#include <vector>

#include "RestoreLinks.h"
#include "SnapshotFormat.h"
#include "dynamics/WorldState.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/DynamicTree.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/state/Snapshot.h"

namespace lockbox::state_detail {

/// The checksum of an image: XXH3-64 of the payload, seeded with XXH3-64 of the header bytes
/// before the checksum field (flag, magic, versions, payload size).
uint64 SnapshotChecksum(std::span<const uint8> image, size_t payloadBytes) noexcept;

struct PoolImage {
    int32 capacity = 0;
    int32 count = 0;
    std::vector<int32> free;  ///< free-slot stack, bottom first
    std::vector<uint8> live;  ///< derived: 1 for every id not on the free stack
};

struct SettingsImage {
    b2Vec2 gravity;
    bool allowSleep = true, warmStarting = true, continuous = true, subStepping = false, autoClear = true;
    b2AABB bounds;
    uint32 flags = 0;
    Fixed invDt0;
    bool stepComplete = true;
    uint64 saturations = 0;
    int32 bodyCount = 0, jointCount = 0, contactCount = 0;
};

/// Writes the world switches and step carry-over from a SettingsImage or from a rollback
/// frame's settings (frame_detail::Settings): both name these fields alike.
template <class S>
void InstallSettings(const S& s, core_detail::Engine::World& world) {
    world.m_gravity = s.gravity;
    world.m_allowSleep = s.allowSleep;
    world.m_warmStarting = s.warmStarting;
    world.m_continuousPhysics = s.continuous;
    world.m_subStepping = s.subStepping;
    world.m_autoClearForces = s.autoClear;
    world.m_bounds = s.bounds;
    world.m_flags = s.flags;
    world.m_inv_dt0 = s.invDt0;
    world.m_stepComplete = s.stepComplete;
    world.m_saturationCount = s.saturations;
}

/// A body's checked header; the rest of its record (transform through user data) is read
/// again from the image bytes when applied (ApplyBodyState), as for contacts.
struct BodyImage {
    int32 id = -1;
    uint8 type = 0;
    uint16 flags = 0;
    int32 fixtureCount = 0;
    uint32 stateAt = 0;  ///< offset in Image::bytes of the record's transform
};

struct ShapeImage {
    uint8 type = 0;
    Fixed radius;
    b2Vec2 p;               ///< circle centre or polygon centroid
    b2Vec2 v0, v1, v2, v3;  ///< edge
    bool has0 = false, has3 = false;
    int32 count = 0;  ///< polygon or chain vertex count
    b2Vec2 vertices[b2_maxPolygonVertices];
    b2Vec2 normals[b2_maxPolygonVertices];
    int32 chainBegin = 0;  ///< range start in Image::chainVertices (count entries)
    b2Vec2 prev, next;     ///< chain ghosts
    bool hasPrev = false, hasNext = false;
};

struct ProxyImage {
    b2AABB aabb;
    int32 proxyId = -1;
};

struct FixtureImage {
    int32 id = -1;
    int32 bodyId = -1;
    Fixed density, friction, restitution;
    bool sensor = false;
    b2Filter filter;
    uint64 userData = 0;
    ShapeImage shape;
    int32 childCount = 0;  ///< derived from the shape
    int32 proxyCount = 0;
    int32 proxyBegin = 0;  ///< range in Image::proxies
};

/// A contact's references; the rest of its record (flags through manifold points) is checked
/// at parse and read again from the image bytes when applied (ApplyContactState): a copy of
/// every field here doubled the bytes a restore moves through the cache.
struct ContactImage {
    int32 id = -1;
    int32 fixtureA = -1, indexA = 0, fixtureB = -1, indexB = 0;
    uint32 stateAt = 0;  ///< offset in Image::bytes of the record's flags field
};

/// A joint's checked head and references; its state fields (VisitState) are checked at
/// parse and read again from the image bytes straight into the world's joint when applied
/// (JointState.h), as for bodies and contacts.
struct JointImage {
    int32 id = -1;
    b2JointType type = e_unknownJoint;
    int32 bodyA = -1, bodyB = -1;
    bool collideConnected = false;
    uint64 userData = 0;
    uint32 stateAt = 0;                ///< offset in Image::bytes of the record's first VisitState field
    uint32 reactionAt = 0;             ///< offset of its VisitReactionState fields; 0: none in the image
    int32 refBegin = 0, refCount = 0;  ///< body/joint references in Image::refs
};

/// A reference read by a joint's VisitState (gear joints), for the cross-reference checks;
/// the apply resolves it again from the record.
struct RefImage {
    bool isJoint = false;
    int32 id = -1;
};

struct TreeImage {
    int32 proxyCount = 0, root = -1, freeList = -1, nodeCount = 0, insertionCount = 0;
    std::vector<b2TreeNode> nodes;
    std::vector<int32> moveBuffer;
};

struct Image {
    /// The image bytes being restored: valid from ParseSnapshot to the end of ApplySnapshot
    /// (both run inside one b2World::Restore).
    const uint8* bytes = nullptr;
    SettingsImage settings;
    PoolImage bodyPool, fixturePool, contactPool;
    std::vector<BodyImage> bodies;       ///< body-list order
    std::vector<FixtureImage> fixtures;  ///< grouped by body, body-list order
    std::vector<b2Vec2> chainVertices;
    std::vector<ProxyImage> proxies;
    std::vector<ContactImage> contacts;  ///< contact-list order
    std::vector<JointImage> joints;      ///< joint-list order
    std::vector<RefImage> refs;
    TreeImage tree;

    // Validation scratch (id -> record position, or -1), reused between restores.
    std::vector<int32> bodyIndex, fixtureIndex, contactIndex, jointIndex;
    /// What the contact checks need of each fixture, by fixture id: 12 bytes instead of a
    /// FixtureImage (~300) per lookup, so 2 lookups per contact stay in L1.
    struct FixtureFacts {
        int32 bodyId = -1;
        int32 childCount = 0;
        int32 shapeType = 0;
    };
    std::vector<FixtureFacts> fixtureFacts;
    /// Restore scratch: the last contact edge of each body while the lists are rebuilt.
    std::vector<b2ContactEdge*> edgeTails;
    /// Restore scratch, by fixture id: the world's fixture and its body once the fixtures are
    /// installed, so the contacts find both without a pool lookup or a fixture visit.
    std::vector<FixtureSlot> fixtureSlots;
    /// Restore scratch: which joint ids the image has visited, and the last joint edge of
    /// each body while the lists are rebuilt.
    std::vector<uint8> jointVisited;
    std::vector<b2JointEdge*> jointEdgeTails;

    /// Empties the lists before a parse; capacity is kept.
    void Clear() {
        chainVertices.clear();
        proxies.clear();
        refs.clear();
    }
};

/// b2World::Save's image, or with `withContacts` false the same image without the contacts
/// (an empty contact section and a contact count of 0; the rollback frames' structure image,
/// whose frames carry the contacts).
void SaveImage(const b2World& world, std::vector<uint8>& out, bool withContacts);

/// Reads and validates a whole image. On error the result names the problem and `image` is
/// unspecified; the world is never involved.
b2RestoreResult ParseSnapshot(std::span<const uint8> bytes, Image& image);

/// Installs a validated image into the world (SnapshotApply.cpp).
void ApplySnapshot(Image& image, b2World& world);

}  // namespace lockbox::state_detail
