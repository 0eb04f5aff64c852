// Snapshot reading: header checks, then every section into an Image, field by field in the
// order of StateWalk.h, with local checks as values arrive. Cross-references (ids, lists,
// the tree's shape) are checked afterwards in SnapshotValidate.cpp. Nothing here touches a
// world.

#include <cereal/archives/portable_binary.hpp>

#include <istream>
#include <string>

#include "ByteStreams.h"
#include "SnapshotCheck.h"
#include "SnapshotImage.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/state/WorldHash.h"
#include "StateWalk.h"

namespace lockbox::state_detail {
namespace {

bool ReadBool(FieldReader& r, const char* what) {
    const uint8 b = r.U8();
    Check(b <= 1, what, "is not 0 or 1", b);
    return b != 0;
}

/// A count of records that take at least minBytes each: never more than the bytes left, so
/// a hostile count cannot make us allocate.
int32 ReadCount(FieldReader& r, size_t minBytes, const char* what) {
    const int32 n = r.I32();
    Check(n >= 0, what, "is negative", n);
    if (static_cast<uint64>(n) * minBytes > r.Remaining()) {
        Fail(b2SnapshotError::e_truncated, std::string(what) + " announces " + std::to_string(n) +
                                               " records but only " + std::to_string(r.Remaining()) + " bytes are left");
    }
    return n;
}

b2AABB ReadAABB(FieldReader& r) {
    b2AABB box;
    box.lowerBound = r.V();
    box.upperBound = r.V();
    return box;
}

void ReadPool(FieldReader& r, PoolImage& pool, size_t minRecordBytes, const char* what) {
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

void ReadSettings(FieldReader& r, SettingsImage& s) {
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
    Check((s.flags & ~static_cast<uint32>(b2World::e_newFixture | b2World::e_clearForces)) == 0, "settings.flags",
          "has unknown or transient bits", s.flags);
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

void ReadBodies(FieldReader& r, Image& img) {
    ReadPool(r, img.bodyPool, kMinBody, "bodies.pool");
    Check(img.bodyPool.count == img.settings.bodyCount, "bodies.pool", "count differs from settings.bodyCount",
          img.bodyPool.count);
    img.bodies.resize(static_cast<size_t>(img.bodyPool.count));
    for (BodyImage& b : img.bodies) {
        b.id = r.I32();
        b.type = r.U8();
        Check(b.type <= b2_dynamicBody, "body.type", "is not static, kinematic or dynamic", b.type);
        b.flags = r.U16();
        Check((b.flags & ~0xFFu) == 0, "body.flags", "has unknown bits", b.flags);
        b.xf.p = r.V();
        b.xf.q.s = r.F();
        b.xf.q.c = r.F();
        b.sweep.localCenter = r.V();
        b.sweep.c0 = r.V();
        b.sweep.c = r.V();
        b.sweep.a0 = r.F();
        b.sweep.a = r.F();
        b.sweep.alpha0 = r.F();
        b.v = r.V();
        b.w = r.F();
        b.force = r.V();
        b.torque = r.F();
        b.sleepSteps = r.I32();
        b.mass = r.W();
        b.invMass = r.W();
        b.I = r.W();
        b.invI = r.W();
        b.linearDamping = r.F();
        b.angularDamping = r.F();
        b.gravityScale = r.F();
        b.minExtent = r.F();
        b.maxExtent = r.F();
        b.userData = r.U64();
        b.fixtureCount = ReadCount(r, kMinFixture, "body.fixtureCount");
    }
}

void ReadShape(FieldReader& r, Image& img, ShapeImage& s) {
    s.type = r.U8();
    Check(s.type < b2Shape::e_typeCount, "shape.type", "is not a shape type", s.type);
    s.radius = r.F();
    Check(s.radius >= Fixed(), "shape.radius", "is negative", s.radius.Raw());
    switch (s.type) {
        case b2Shape::e_circle:
            s.p = r.V();
            break;
        case b2Shape::e_edge:
            s.v0 = r.V();
            s.v1 = r.V();
            s.v2 = r.V();
            s.v3 = r.V();
            s.has0 = ReadBool(r, "edge.hasVertex0");
            s.has3 = ReadBool(r, "edge.hasVertex3");
            break;
        case b2Shape::e_polygon:
            s.p = r.V();
            s.count = r.I32();
            Check(s.count >= 3 && s.count <= b2_maxPolygonVertices, "polygon.vertexCount", "is outside [3, 8]", s.count);
            for (int32 i = 0; i < s.count; ++i) {
                s.vertices[i] = r.V();
                s.normals[i] = r.V();
            }
            break;
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

void ReadFixtures(FieldReader& r, Image& img) {
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
            f.id = r.I32();
            f.bodyId = r.I32();
            Check(f.bodyId == b.id, "fixture.body", "is not the body it is listed under", f.bodyId);
            f.density = r.F();
            f.friction = r.F();
            f.restitution = r.F();
            f.sensor = ReadBool(r, "fixture.isSensor");
            f.filter.categoryBits = r.U16();
            f.filter.maskBits = r.U16();
            f.filter.groupIndex = static_cast<int16>(r.U16());
            f.userData = r.U64();
            ReadShape(r, img, f.shape);
            f.childCount = ChildCount(f.shape);
            f.proxyCount = ReadCount(r, 20, "fixture.proxyCount");
            Check(f.proxyCount == 0 || f.proxyCount == f.childCount, "fixture.proxyCount",
                  "is neither 0 nor the child count", f.proxyCount);
            const bool active = (b.flags & b2Body::e_activeFlag) != 0;
            Check((f.proxyCount != 0) == (active && f.childCount != 0), "fixture.proxyCount",
                  "does not match the body's active flag", f.proxyCount);
            f.proxyBegin = static_cast<int32>(img.proxies.size());
            for (int32 c = 0; c < f.proxyCount; ++c) {
                ProxyImage p;
                p.aabb = ReadAABB(r);
                p.proxyId = r.I32();
                img.proxies.push_back(p);
            }
        }
    }
}

void ReadContacts(FieldReader& r, Image& img) {
    ReadPool(r, img.contactPool, kMinContact, "contacts.pool");
    Check(img.contactPool.count == img.settings.contactCount, "contacts.pool",
          "count differs from settings.contactCount", img.contactPool.count);
    img.contacts.resize(static_cast<size_t>(img.contactPool.count));
    for (ContactImage& c : img.contacts) {
        c.id = r.I32();
        c.fixtureA = r.I32();
        c.indexA = r.I32();
        c.fixtureB = r.I32();
        c.indexB = r.I32();
        c.flags = r.U32();
        Check((c.flags & ~0x3Fu) == 0, "contact.flags", "has unknown bits", c.flags);
        c.toiCount = r.I32();
        Check(c.toiCount >= 0, "contact.toiCount", "is negative", c.toiCount);
        c.toi = r.F();
        c.friction = r.F();
        c.restitution = r.F();
        b2Manifold& m = c.manifold;
        const uint8 type = r.U8();
        Check(type <= b2Manifold::e_faceB, "manifold.type", "is not circles, faceA or faceB", type);
        m.type = static_cast<b2Manifold::Type>(type);
        m.pointCount = r.U8();
        Check(m.pointCount <= b2_maxManifoldPoints, "manifold.pointCount", "exceeds 2", m.pointCount);
        m.localNormal = r.V();
        m.localPoint = r.V();
        for (int32 i = 0; i < m.pointCount; ++i) {
            b2ManifoldPoint& p = m.points[i];
            p.localPoint = r.V();
            p.normalImpulse = r.W();
            p.tangentImpulse = r.W();
            const uint32 key = r.U32();
            p.id.cf.indexA = static_cast<uint8>(key);
            p.id.cf.indexB = static_cast<uint8>(key >> 8);
            p.id.cf.typeA = static_cast<uint8>(key >> 16);
            p.id.cf.typeB = static_cast<uint8>(key >> 24);
        }
    }
}

/// Reads a joint's VisitState fields into an empty joint; references are queued.
struct JointFieldReader {
    FieldReader& r;
    Image& img;
    template <class... T>
    void operator()(T&... fields) {
        (Get(fields), ...);
    }
    void Get(Fixed& x) { x = r.F(); }
    void Get(Wide& x) { x = r.W(); }
    void Get(b2Vec2& x) { x = r.V(); }
    void Get(b2WideVec2& x) {
        x.x = r.W();
        x.y = r.W();
    }
    void Get(b2WideVec3& x) {
        x.x = r.W();
        x.y = r.W();
        x.z = r.W();
    }
    void Get(bool& x) { x = ReadBool(r, "joint flag"); }
    void Get(b2LimitState& x) {
        const uint8 v = r.U8();
        Check(v <= e_equalLimits, "joint.limitState", "is not a limit state", v);
        x = static_cast<b2LimitState>(v);
    }
    void Get(b2JointType& x) {
        const uint8 v = r.U8();
        Check(v == e_revoluteJoint || v == e_prismaticJoint, "gear.side.type", "is not revolute or prismatic", v);
        x = static_cast<b2JointType>(v);
    }
    void BodyRef(b2Body*& slot) { img.refs.push_back({false, r.I32(), &slot}); }
    void JointRef(b2Joint*& slot) { img.refs.push_back({true, r.I32(), &slot}); }
};

void ReadJoints(FieldReader& r, Image& img) {
    const int32 n = img.settings.jointCount;
    if (static_cast<uint64>(n) * kMinJoint > r.Remaining()) {
        Fail(b2SnapshotError::e_truncated, "joints: settings.jointCount " + std::to_string(n) + " exceeds the bytes left");
    }
    img.joints.resize(static_cast<size_t>(n));
    for (JointImage& j : img.joints) {
        j.id = r.I32();
        const uint8 type = r.U8();
        Check(type >= e_revoluteJoint && type <= e_ropeJoint, "joint.type", "is not a joint type", type);
        j.type = static_cast<b2JointType>(type);
        j.bodyA = r.I32();
        j.bodyB = r.I32();
        j.collideConnected = ReadBool(r, "joint.collideConnected");
        j.userData = r.U64();
        // A reused scratch joint of the right type is refilled (VisitState sets every
        // persistent field); the solver temporaries it keeps are recomputed before use.
        if (!j.state || j.state->GetType() != j.type) j.state.reset(b2Joint::CreateEmpty(j.type));
        j.refBegin = static_cast<int32>(img.refs.size());
        JointFieldReader reader{r, img};
        VisitJointState(*j.state, reader);
        j.refCount = static_cast<int32>(img.refs.size()) - j.refBegin;
    }
}

void ReadBroadPhase(FieldReader& r, Image& img) {
    TreeImage& t = img.tree;
    t.proxyCount = r.I32();
    t.root = r.I32();
    t.freeList = r.I32();
    t.nodeCount = r.I32();
    t.insertionCount = r.I32();
    const int32 capacity = ReadCount(r, kMinNode, "tree.capacity");
    Check(capacity >= 1, "tree.capacity", "is zero", capacity);
    t.nodes.assign(static_cast<size_t>(capacity), b2TreeNode{});
    for (b2TreeNode& n : t.nodes) {
        n.height = r.I32();
        Check(n.height >= -1, "tree.node.height", "is below -1", n.height);
        if (n.height < 0) {
            n.next = r.I32();
            continue;
        }
        n.aabb = ReadAABB(r);
        n.userData = r.U64();
        n.parent = r.I32();
        n.child1 = r.I32();
        n.child2 = r.I32();
    }
    const int32 moves = ReadCount(r, 4, "broadphase.moveBuffer");
    t.moveBuffer.resize(static_cast<size_t>(moves));
    for (int32& id : t.moveBuffer) id = r.I32();
}

/// Reads one section header and runs its reader, checking the announced length.
template <class ReadFn>
void ReadSection(FieldReader& r, uint32 tag, const char* name, ReadFn read) {
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
    try {
        if (bytes.size() < kHeaderBytes) {
            Fail(b2SnapshotError::e_truncated, "image of " + std::to_string(bytes.size()) +
                                                   " bytes is shorter than the " + std::to_string(kHeaderBytes) +
                                                   "-byte header");
        }
        if (bytes[0] != 1) {
            Fail(b2SnapshotError::e_badEndianFlag,
                 "first byte is " + std::to_string(bytes[0]) + ", expected 1 (little-endian portable binary)");
        }
        // The header, through Cereal's portable binary archive (little-endian).
        uint32 magic = 0, determinism = 0;
        uint16 format = 0, major = 0, minor = 0, patch = 0;
        uint64 payload = 0, checksum = 0;
        {
            HeaderSource source(bytes.first(kHeaderBytes));
            std::istream stream(&source);
            cereal::PortableBinaryInputArchive archive(stream);
            archive(magic, format, major, minor, patch, determinism, payload, checksum);
        }
        if (magic != b2_snapshotMagic) Fail(b2SnapshotError::e_badMagic, "magic " + Hex(magic) + " is not 'LBSN'");
        if (format != b2_snapshotFormatVersion) {
            Fail(b2SnapshotError::e_badFormatVersion, "format version " + std::to_string(format) + ", this build reads " +
                                                          std::to_string(b2_snapshotFormatVersion));
        }
        // The engine version (major.minor.patch) is informative: the format and determinism
        // versions decide whether this build can continue the simulation.
        if (determinism != b2_determinismVersion) {
            Fail(b2SnapshotError::e_badDeterminismVersion, "determinism version " + Hex(determinism) +
                                                               ", this build is " + Hex(b2_determinismVersion));
        }
        FieldReader r(bytes, kHeaderBytes);
        if (payload > r.Remaining()) {
            Fail(b2SnapshotError::e_truncated, "payload of " + std::to_string(payload) + " bytes announced, " +
                                                   std::to_string(r.Remaining()) + " present");
        }
        if (payload < r.Remaining()) {
            Fail(b2SnapshotError::e_trailingBytes, std::to_string(r.Remaining() - payload) + " bytes after the payload");
        }
        const uint64 actual = SnapshotChecksum(bytes, static_cast<size_t>(payload));
        if (actual != checksum) {
            Fail(b2SnapshotError::e_badChecksum,
                 "payload checksum " + Hex(actual) + " differs from the header's " + Hex(checksum));
        }
        ReadSection(r, e_sectionSettings, "settings", [&] { ReadSettings(r, img.settings); });
        ReadSection(r, e_sectionBodies, "bodies", [&] { ReadBodies(r, img); });
        ReadSection(r, e_sectionFixtures, "fixtures", [&] { ReadFixtures(r, img); });
        ReadSection(r, e_sectionContacts, "contacts", [&] { ReadContacts(r, img); });
        ReadSection(r, e_sectionJoints, "joints", [&] { ReadJoints(r, img); });
        ReadSection(r, e_sectionBroadPhase, "broadphase", [&] { ReadBroadPhase(r, img); });
        if (r.Remaining() != 0) {
            Fail(b2SnapshotError::e_trailingBytes, std::to_string(r.Remaining()) + " bytes after the last section");
        }
        ValidateImage(img);
    } catch (const TruncatedImage&) {
        result.error = b2SnapshotError::e_truncated;
        result.message = "the image ends inside a field";
    } catch (const SnapshotFailure& failure) {
        result.error = failure.error;
        result.message = failure.message;
    }
    return result;
}

}  // namespace lockbox::state_detail
