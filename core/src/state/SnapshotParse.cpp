// Snapshot reading: header checks, then every section into an Image, field by field in the
// order of StateWalk.h, with local checks as values arrive. Cross-references (ids, lists,
// the tree's shape) are checked afterwards in SnapshotValidate.cpp. Nothing here touches a
// world.

#include <string>

#include "JointState.h"
#include "SnapshotCheck.h"
#include "SnapshotImage.h"
#include "StateWalk.h"
#include "dynamics/Access.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::state_detail {
namespace {

/// Checks a count read from a record (as ReadCount) once the record has been consumed.
int32 CheckCount(const ImageReader& r, int32 n, size_t minBytes, const char* what) {
    Check(n >= 0, what, "is negative", n);
    if (static_cast<uint64>(n) * minBytes > r.Remaining()) [[unlikely]] {
        Fail(b2SnapshotError::e_truncated, std::string(what) + " announces " + std::to_string(n) +
                                               " records but only " + std::to_string(r.Remaining()) +
                                               " bytes are left");
    }
    return n;
}

/// A count of records that take at least minBytes each: never more than the bytes left, so
/// a hostile count cannot make us allocate.
int32 ReadCount(ImageReader& r, size_t minBytes, const char* what) {
    const int32 n = r.I32();
    Check(n >= 0, what, "is negative", n);
    if (static_cast<uint64>(n) * minBytes > r.Remaining()) {
        Fail(b2SnapshotError::e_truncated, std::string(what) + " announces " + std::to_string(n) +
                                               " records but only " + std::to_string(r.Remaining()) +
                                               " bytes are left");
    }
    return n;
}

template <class R>
b2AABB ReadAABB(R& r) {
    b2AABB box;
    box.lowerBound = r.V();
    box.upperBound = r.V();
    return box;
}

void ReadPool(ImageReader& r, PoolImage& pool, size_t minRecordBytes, const char* what) {
    pool.capacity = r.I32();
    pool.count = ReadCount(r, minRecordBytes, what);
    const int32 freeCount = ReadCount(r, 4, what);
    Check(pool.capacity >= 0 && static_cast<int64_t>(pool.count) + freeCount == pool.capacity, what,
          "capacity is not live + free", pool.capacity);
    pool.live.assign(static_cast<size_t>(pool.capacity), 1);
    pool.free.resize(static_cast<size_t>(freeCount));
    for (int32& id : pool.free) {
        id = r.I32();
        Check(id >= 0 && id < pool.capacity && pool.live[static_cast<size_t>(id)] == 1, what,
              "free list holds an invalid or repeated id", id);
        pool.live[static_cast<size_t>(id)] = 0;
    }
}

void ReadSettings(ImageReader& r, SettingsImage& s) {
    s.gravity = r.V();
    s.allowSleep = ReadBool(r, "settings.allowSleep");
    s.warmStarting = ReadBool(r, "settings.warmStarting");
    s.continuous = ReadBool(r, "settings.continuousPhysics");
    s.subStepping = ReadBool(r, "settings.subStepping");
    s.autoClear = ReadBool(r, "settings.autoClearForces");
    s.bounds = ReadAABB(r);
    Check(s.bounds.lowerBound.x <= s.bounds.upperBound.x && s.bounds.lowerBound.y <= s.bounds.upperBound.y,
          "settings.bounds", "lower bound above upper bound", s.bounds.lowerBound.x.Raw());
    s.flags = r.U32();
    Check((s.flags &
           ~static_cast<uint32>(core_detail::Engine::World::e_newFixture | core_detail::Engine::World::e_clearForces |
                                core_detail::Engine::World::e_skipPressedToi)) == 0,
          "settings.flags", "has unknown or transient bits", s.flags);
    s.invDt0 = r.F();
    s.stepComplete = ReadBool(r, "settings.stepComplete");
    s.saturations = r.U64();
    s.bodyCount = r.I32();
    s.jointCount = r.I32();
    s.contactCount = r.I32();
    Check(s.bodyCount >= 0 && s.jointCount >= 0 && s.contactCount >= 0, "settings", "negative object count",
          s.bodyCount < 0 ? s.bodyCount : (s.jointCount < 0 ? s.jointCount : s.contactCount));
}

// Smallest encodings, for the count checks: a body record is at least 150 bytes, a fixture
// 40, a contact 48, a joint 22, a tree node 8.
constexpr size_t kMinBody = 150, kMinFixture = 40, kMinContact = 48, kMinJoint = 22, kMinNode = 8;

void ReadBodies(ImageReader& r, Image& img) {
    ReadPool(r, img.bodyPool, kMinBody, "bodies.pool");
    Check(img.bodyPool.count == img.settings.bodyCount, "bodies.pool", "count differs from settings.bodyCount",
          img.bodyPool.count);
    img.bodies.resize(static_cast<size_t>(img.bodyPool.count));
    for (BodyImage& b : img.bodies) {
        // One room check per record (kBodyRecordBytes, StateWalk.h), then unchecked reads.
        ReadCursor c = r.Begin(kBodyRecordBytes);
        b.id = c.I32();
        b.type = c.U8();
        Check(b.type <= b2_dynamicBody, "body.type", "is not static, kinematic or dynamic", b.type);
        b.flags = c.U16();
        Check((b.flags & ~0xFFu) == 0, "body.flags", "has unknown bits", b.flags);
        // Transform through user data: any value (ApplyBodyState reads them from here).
        b.stateAt = static_cast<uint32>(c.Position() - img.bytes);
        c.Skip(kBodyRecordBytes - 7 - 4);  // all but the 7-byte head and the fixture count
        const int32 fixtureCount = c.I32();
        r.End(c);
        b.fixtureCount = CheckCount(r, fixtureCount, kMinFixture, "body.fixtureCount");
    }
}

/// A shape after its type and radius (read with the fixture record).
void ReadShape(ImageReader& r, Image& img, ShapeImage& s) {
    switch (s.type) {
        case b2Shape::e_circle: {
            ReadCursor c = r.Begin(8);
            s.p = c.V();
            r.End(c);
            break;
        }
        case b2Shape::e_edge: {
            ReadCursor c = r.Begin(34);
            s.v0 = c.V();
            s.v1 = c.V();
            s.v2 = c.V();
            s.v3 = c.V();
            s.has0 = ReadBool(c, "edge.hasVertex0");
            s.has3 = ReadBool(c, "edge.hasVertex3");
            r.End(c);
            break;
        }
        case b2Shape::e_polygon: {
            ReadCursor c = r.Begin(12);
            s.p = c.V();
            s.count = c.I32();
            r.End(c);
            Check(s.count >= 3 && s.count <= b2_maxPolygonVertices, "polygon.vertexCount", "is outside [3, 8]",
                  s.count);
            ReadCursor v = r.Begin(16 * static_cast<size_t>(s.count));
            for (int32 i = 0; i < s.count; ++i) {
                s.vertices[i] = v.V();
                s.normals[i] = v.V();
            }
            r.End(v);
            break;
        }
        default: {  // chain
            s.count = ReadCount(r, 8, "chain.count");
            s.chainBegin = static_cast<int32>(img.chainVertices.size());
            for (int32 i = 0; i < s.count; ++i) img.chainVertices.push_back(r.V());
            s.prev = r.V();
            s.next = r.V();
            s.hasPrev = ReadBool(r, "chain.hasPrevVertex");
            s.hasNext = ReadBool(r, "chain.hasNextVertex");
            break;
        }
    }
}

int32 ChildCount(const ShapeImage& s) {
    if (s.type == b2Shape::e_chain) return s.count > 1 ? s.count - 1 : 0;
    return 1;
}

void ReadFixtures(ImageReader& r, Image& img) {
    ReadPool(r, img.fixturePool, kMinFixture, "fixtures.pool");
    int64_t expected = 0;
    for (const BodyImage& b : img.bodies) expected += b.fixtureCount;
    Check(expected == img.fixturePool.count, "fixtures.pool", "count differs from the bodies' fixture counts",
          img.fixturePool.count);
    img.fixtures.resize(static_cast<size_t>(img.fixturePool.count));
    size_t k = 0;
    for (const BodyImage& b : img.bodies) {
        for (int32 i = 0; i < b.fixtureCount; ++i, ++k) {
            FixtureImage& f = img.fixtures[k];
            // The fixture's fields, then the shape's type and radius.
            ReadCursor c = r.Begin(kFixtureHeadBytes + 5);
            f.id = c.I32();
            f.bodyId = c.I32();
            Check(f.bodyId == b.id, "fixture.body", "is not the body it is listed under", f.bodyId);
            f.density = c.F();
            f.friction = c.F();
            f.restitution = c.F();
            f.sensor = ReadBool(c, "fixture.isSensor");
            f.filter.categoryBits = c.U16();
            f.filter.maskBits = c.U16();
            f.filter.groupIndex = static_cast<int16>(c.U16());
            f.userData = c.U64();
            ShapeImage& shape = f.shape;
            shape.type = c.U8();
            Check(shape.type < b2Shape::e_typeCount, "shape.type", "is not a shape type", shape.type);
            shape.radius = c.F();
            Check(shape.radius >= Fixed(), "shape.radius", "is negative", shape.radius.Raw());
            r.End(c);
            ReadShape(r, img, shape);
            f.childCount = ChildCount(f.shape);
            f.proxyCount = ReadCount(r, 20, "fixture.proxyCount");
            Check(f.proxyCount == 0 || f.proxyCount == f.childCount, "fixture.proxyCount",
                  "is neither 0 nor the child count", f.proxyCount);
            const bool active = (b.flags & core_detail::Engine::Bodies::kActiveFlag) != 0;
            Check((f.proxyCount != 0) == (active && f.childCount != 0), "fixture.proxyCount",
                  "does not match the body's active flag", f.proxyCount);
            f.proxyBegin = static_cast<int32>(img.proxies.size());
            for (int32 child = 0; child < f.proxyCount; ++child) {
                ReadCursor pc = r.Begin(kProxyBytes);
                ProxyImage p;
                p.aabb = ReadAABB(pc);
                p.proxyId = pc.I32();
                r.End(pc);
                img.proxies.push_back(p);
            }
        }
    }
}

void ReadContacts(ImageReader& r, Image& img) {
    ReadPool(r, img.contactPool, kMinContact, "contacts.pool");
    Check(img.contactPool.count == img.settings.contactCount, "contacts.pool",
          "count differs from settings.contactCount", img.contactPool.count);
    img.contacts.resize(static_cast<size_t>(img.contactPool.count));
    for (ContactImage& c : img.contacts) {
        // The fixed part in one room check (kContactHeadBytes, StateWalk.h), then the points.
        // Only the references are kept; the state is checked here and read again by
        // ApplyContactState (SnapshotApply.cpp), which must follow this layout.
        ReadCursor h = r.Begin(kContactHeadBytes);
        c.id = h.I32();
        c.fixtureA = h.I32();
        c.indexA = h.I32();
        c.fixtureB = h.I32();
        c.indexB = h.I32();
        c.stateAt = static_cast<uint32>(h.Position() - img.bytes);
        const uint32 flags = h.U32();
        Check((flags & ~0x3Fu) == 0, "contact.flags", "has unknown bits", flags);
        const int32 toiCount = h.I32();
        Check(toiCount >= 0, "contact.toiCount", "is negative", toiCount);
        h.Skip(12);  // toi, friction, restitution: any value
        const uint8 type = h.U8();
        Check(type <= b2Manifold::e_faceB, "manifold.type", "is not circles, faceA or faceB", type);
        const uint8 pointCount = h.U8();
        Check(pointCount <= b2_maxManifoldPoints, "manifold.pointCount", "exceeds 2", pointCount);
        h.Skip(16);  // localNormal, localPoint: any value
        r.End(h);
        // Points: local point, impulses, feature key; any value.
        ReadCursor pc = r.Begin(kContactPointBytes * pointCount);
        pc.Skip(kContactPointBytes * pointCount);
        r.End(pc);
    }
}

/// One joint record from R (a ReadCursor or the ImageReader, see ReadJoints); the state
/// fields are checked where they lie and only their offset and references are kept.
template <class R>
void ReadJoint(R& r, JointImage& j, Image& img, size_t recordAt) {
    j.id = r.I32();
    const uint8 type = r.U8();
    Check(type >= e_revoluteJoint && type <= e_ropeJoint, "joint.type", "is not a joint type", type);
    j.type = static_cast<b2JointType>(type);
    j.bodyA = r.I32();
    j.bodyB = r.I32();
    j.collideConnected = ReadBool(r, "joint.collideConnected");
    j.userData = r.U64();
    j.stateAt = static_cast<uint32>(recordAt + kJointHeadBytes);
    j.refBegin = static_cast<int32>(img.refs.size());
    JointStateCheck<R> check{r, img.refs};
    VisitJointFields(j.type, check);
    j.refCount = static_cast<int32>(img.refs.size()) - j.refBegin;
}

void ReadJoints(ImageReader& r, Image& img) {
    const int32 n = img.settings.jointCount;
    if (static_cast<uint64>(n) * kMinJoint > r.Remaining()) {
        Fail(b2SnapshotError::e_truncated,
             "joints: settings.jointCount " + std::to_string(n) + " exceeds the bytes left");
    }
    img.joints.resize(static_cast<size_t>(n));
    // A record of any type fits in this many bytes: when that many are left, the record is
    // read through one unchecked cursor; near the end of the image, field by field, so a
    // record running past it fails at the same field as ever.
    const size_t maxRecord = kJointHeadBytes + JointStateBytes().largest;
    for (JointImage& j : img.joints) {
        const size_t at = r.Position();
        if (r.Remaining() >= maxRecord) {
            ReadCursor c = r.Begin(maxRecord);
            ReadJoint(c, j, img, at);
            r.End(c);
        } else {
            ReadJoint(r, j, img, at);
        }
    }
}

/// The joint-reaction section: each joint's VisitReactionState fields, in joint-list order
/// (any values: reaction queries only scale them). Keeps their offsets for the apply.
void ReadJointReactions(ImageReader& r, Image& img) {
    const JointStateSizes& sizes = JointStateBytes();
    for (JointImage& j : img.joints) {
        const uint32 bytes = sizes.reaction[static_cast<size_t>(j.type)];
        if (bytes == 0) continue;
        ReadCursor c = r.Begin(bytes);
        j.reactionAt = static_cast<uint32>(r.Position());
        c.Skip(bytes);
        r.End(c);
    }
}

void ReadBroadPhase(ImageReader& r, Image& img) {
    TreeImage& t = img.tree;
    t.proxyCount = r.I32();
    t.root = r.I32();
    t.freeList = r.I32();
    t.nodeCount = r.I32();
    t.insertionCount = r.I32();
    const int32 capacity = ReadCount(r, kMinNode, "tree.capacity");
    Check(capacity >= 1, "tree.capacity", "is zero", capacity);
    // Every node is overwritten whole below: resize, not assign, to skip a fill of the array.
    t.nodes.resize(static_cast<size_t>(capacity));
    for (b2TreeNode& n : t.nodes) {
        ReadCursor h = r.Begin(8);  // the height, then a free link or the start of the AABB
        const int32 height = h.I32();
        Check(height >= -1, "tree.node.height", "is below -1", height);
        if (height < 0) {
            // A free slot is canonical (b2DynamicTree::FreeNode): defaults plus its link.
            n = b2TreeNode{};
            n.next = h.I32();
            r.End(h);
            continue;
        }
        r.End(h);  // the height only
        ReadCursor c = r.Begin(36);
        n.aabb = ReadAABB(c);
        n.userData = c.U64();
        n.parent = c.I32();
        n.child1 = c.I32();
        n.child2 = c.I32();
        n.next = b2_nullNode;
        n.height = height;
        r.End(c);
    }
    const int32 moves = ReadCount(r, 4, "broadphase.moveBuffer");
    t.moveBuffer.resize(static_cast<size_t>(moves));
    for (int32& id : t.moveBuffer) id = r.I32();
}

/// Reads one section header and runs its reader, checking the announced length.
template <class ReadFn>
void ReadSection(ImageReader& r, SectionTag tag, ReadFn read) {
    const char* name = kSectionNames[tag - 1];
    const uint32 found = r.U32();
    Check(found == tag, name, "section tag is wrong", found);
    const uint32 length = r.U32();
    if (length > r.Remaining()) {
        Fail(b2SnapshotError::e_truncated, std::string(name) + ": section announces " + std::to_string(length) +
                                               " bytes, " + std::to_string(r.Remaining()) + " are left");
    }
    const size_t start = r.Position();
    read();
    Check(r.Position() - start == length, name, "section length differs from its contents", length);
}

}  // namespace

b2RestoreResult ParseSnapshot(std::span<const uint8> bytes, Image& img) {
    b2RestoreResult result;
    img.Clear();
    img.bytes = bytes.data();
    try {
        const HeaderFields header = ReadHeader(bytes);
        const uint64 payload = header.payload, checksum = header.checksum;
        ImageReader r(bytes, kHeaderBytes);
        const uint64 actual = SnapshotChecksum(bytes, static_cast<size_t>(payload));
        if (actual != checksum) {
            Fail(b2SnapshotError::e_badChecksum,
                 "payload checksum " + Hex(actual) + " differs from the header's " + Hex(checksum));
        }
        ReadSection(r, e_sectionSettings, [&] { ReadSettings(r, img.settings); });
        ReadSection(r, e_sectionBodies, [&] { ReadBodies(r, img); });
        ReadSection(r, e_sectionFixtures, [&] { ReadFixtures(r, img); });
        ReadSection(r, e_sectionContacts, [&] { ReadContacts(r, img); });
        ReadSection(r, e_sectionJoints, [&] { ReadJoints(r, img); });
        ReadSection(r, e_sectionBroadPhase, [&] { ReadBroadPhase(r, img); });
        // Format 1 had no joint-reaction section: its joints keep their reaction directions.
        if (header.format >= 2) {
            ReadSection(r, e_sectionJointReactions, [&] { ReadJointReactions(r, img); });
        }
        if (r.Remaining() != 0) {
            Fail(b2SnapshotError::e_trailingBytes, std::to_string(r.Remaining()) + " bytes after the last section");
        }
        ValidateImage(img);
    } catch (const SnapshotFailure& failure) {
        result.error = failure.error;
        result.message = failure.message;
    }
    return result;
}

}  // namespace lockbox::state_detail
