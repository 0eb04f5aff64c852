// The canonical walk behind b2WorldHash. Field order and widths are the definition in
// docs/determinism.md ("State hash", version b2_hashVersion); change both together and bump
// the version.

#include "lockbox/state/WorldHash.h"

#include "HashWriter.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox {

using state_detail::HashWriter;

namespace {

// Category tags open each category's stream so that two categories with equal bytes still
// hash differently.
void Tag(HashWriter& w, b2HashCategory c) {
    w.U32(b2_hashVersion);
    w.U32(static_cast<uint32>(c));
}

/// Pool allocation state: capacity and free list order decide the ids of future objects.
template <class T>
void HashPool(HashWriter& w, const b2Pool<T>& pool) {
    w.I32(pool.GetCapacity());
    w.I32(pool.GetCount());
    const auto& free = pool.GetFreeList();
    w.U32(static_cast<uint32>(free.size()));
    for (const int32 id : free) w.I32(id);
}

void HashAABB(HashWriter& w, const b2AABB& box) {
    w.V(box.lowerBound);
    w.V(box.upperBound);
}

void HashSettings(HashWriter& w, const b2World& world) {
    Tag(w, b2HashCategory::e_settings);
    w.V(world.GetGravity());
    w.Bool(world.GetAllowSleeping());
    w.Bool(world.GetWarmStarting());
    w.Bool(world.GetContinuousPhysics());
    w.Bool(world.GetSubStepping());
    w.Bool(world.GetAutoClearForces());
    HashAABB(w, world.GetWorldBounds());
    // e_newFixture makes the next step look for new pairs first; e_clearForces mirrors the
    // auto-clear switch. e_locked is always clear outside Step.
    w.U32(world.m_flags);
    // The previous step's inverse length scales warm starting (dtRatio) of the next one.
    w.F(world.m_inv_dt0);
    w.Bool(world.m_stepComplete);
    w.I32(world.GetBodyCount());
    w.I32(world.GetJointCount());
    w.I32(world.GetContactCount());
}

void HashBodyFields(HashWriter& w, const b2Body& b) {
    w.I32(b.GetId());
    w.U32(static_cast<uint32>(b.GetType()));
    w.U32(b.m_flags);
    const b2Transform& xf = b.GetTransform();
    w.V(xf.p);
    w.F(xf.q.s);
    w.F(xf.q.c);
    const b2Sweep& sw = b.m_sweep;
    w.V(sw.localCenter);
    w.V(sw.c0);
    w.V(sw.c);
    w.F(sw.a0);
    w.F(sw.a);
    w.F(sw.alpha0);
    w.V(b.GetLinearVelocity());
    w.F(b.GetAngularVelocity());
    w.V(b.m_force);
    w.F(b.m_torque);
    w.I32(b.GetSleepSteps());
    w.W(b.m_mass);
    w.W(b.m_invMass);
    w.W(b.m_I);
    w.W(b.m_invI);
    w.F(b.GetLinearDamping());
    w.F(b.GetAngularDamping());
    w.F(b.GetGravityScale());
    w.F(b.m_minExtent);
    w.F(b.m_maxExtent);
    w.U64(b.GetUserData());
    w.I32(b.m_fixtureCount);
    // Edge list order decides the island walk, hence the solver order: hash it as ids.
    int32 contactEdges = 0;
    for (const b2ContactEdge* e = b.m_contactList; e; e = e->next) ++contactEdges;
    w.I32(contactEdges);
    for (const b2ContactEdge* e = b.m_contactList; e; e = e->next) w.I32(e->contact->GetId());
    int32 jointEdges = 0;
    for (const b2JointEdge* e = b.m_jointList; e; e = e->next) ++jointEdges;
    w.I32(jointEdges);
    for (const b2JointEdge* e = b.m_jointList; e; e = e->next) w.I32(e->joint->GetId());
}

void HashShape(HashWriter& w, const b2Shape& shape) {
    w.U32(static_cast<uint32>(shape.GetType()));
    w.F(shape.m_radius);
    switch (shape.GetType()) {
        case b2Shape::e_circle:
            w.V(static_cast<const b2CircleShape&>(shape).m_p);
            break;
        case b2Shape::e_edge: {
            const auto& e = static_cast<const b2EdgeShape&>(shape);
            w.V(e.m_vertex0);
            w.V(e.m_vertex1);
            w.V(e.m_vertex2);
            w.V(e.m_vertex3);
            w.Bool(e.m_hasVertex0);
            w.Bool(e.m_hasVertex3);
            break;
        }
        case b2Shape::e_polygon: {
            const auto& p = static_cast<const b2PolygonShape&>(shape);
            w.V(p.m_centroid);
            w.I32(p.m_vertexCount);
            // Only the live vertices: slots past the count are never read.
            for (int32 i = 0; i < p.m_vertexCount; ++i) {
                w.V(p.m_vertices[i]);
                w.V(p.m_normals[i]);
            }
            break;
        }
        case b2Shape::e_chain: {
            const auto& c = static_cast<const b2ChainShape&>(shape);
            w.I32(c.m_count);
            for (const b2Vec2& v : c.m_vertices) w.V(v);
            w.V(c.m_prevVertex);
            w.V(c.m_nextVertex);
            w.Bool(c.m_hasPrevVertex);
            w.Bool(c.m_hasNextVertex);
            break;
        }
        default:
            break;
    }
}

void HashFixture(HashWriter& w, const b2Fixture& f) {
    w.I32(f.GetId());
    w.I32(f.GetBody()->GetId());
    w.F(f.GetDensity());
    w.F(f.GetFriction());
    w.F(f.GetRestitution());
    w.Bool(f.IsSensor());
    const b2Filter& filter = f.GetFilterData();
    w.U16(filter.categoryBits);
    w.U16(filter.maskBits);
    w.U16(static_cast<uint16>(filter.groupIndex));
    w.U64(f.GetUserData());
    w.I32(f.GetProxyCount());
    for (int32 i = 0; i < f.GetProxyCount(); ++i) {
        const b2FixtureProxy& proxy = f.GetProxy(i);
        HashAABB(w, proxy.aabb);
        w.I32(proxy.childIndex);
        w.I32(proxy.proxyId);
    }
    HashShape(w, *f.GetShape());
}

void HashContact(HashWriter& w, const b2Contact& c) {
    w.I32(c.GetId());
    w.I32(c.GetFixtureA()->GetId());
    w.I32(c.GetChildIndexA());
    w.I32(c.GetFixtureB()->GetId());
    w.I32(c.GetChildIndexB());
    w.U32(c.m_flags);
    w.I32(c.m_toiCount);
    w.F(c.m_toi);
    w.F(c.GetFriction());
    w.F(c.GetRestitution());
    const b2Manifold& m = *c.GetManifold();
    w.U32(static_cast<uint32>(m.type));
    w.I32(m.pointCount);
    w.V(m.localNormal);
    w.V(m.localPoint);
    // Points past pointCount are stale and never matched: left out.
    for (int32 i = 0; i < m.pointCount; ++i) {
        const b2ManifoldPoint& p = m.points[i];
        w.V(p.localPoint);
        w.W(p.normalImpulse);
        w.W(p.tangentImpulse);
        w.U32(p.id.Key());
    }
}

void HashBroadPhase(HashWriter& w, const b2World& world) {
    Tag(w, b2HashCategory::e_broadphase);
    const b2BroadPhase& bp = world.GetContactManager().m_broadPhase;
    const b2DynamicTree& tree = bp.GetTree();
    w.I32(bp.GetProxyCount());
    w.I32(tree.GetRoot());
    w.I32(tree.GetFreeList());
    w.I32(tree.GetNodeCount());
    w.I32(tree.GetInsertionCount());
    const auto& nodes = tree.GetNodes();
    w.U32(static_cast<uint32>(nodes.size()));
    for (const b2TreeNode& n : nodes) {
        if (n.height < 0) {
            // A free slot: its AABB and user data are stale. Only the marker and the free-list
            // link count, since the link orders future allocations.
            w.U32(0xFFFFFFFFu);
            w.I32(n.next);
            continue;
        }
        HashAABB(w, n.aabb);
        w.U64(n.userData);
        w.I32(n.parent);
        w.I32(n.child1);
        w.I32(n.child2);
        w.I32(n.height);
    }
    const auto& moves = bp.GetMoveBuffer();
    w.U32(static_cast<uint32>(moves.size()));
    for (const int32 id : moves) w.I32(id);
}

/// Computes all category hashes; fills per-body entries when `bodies` is non-null.
void HashAll(const b2World& world, uint64 out[], std::vector<b2BodyHashEntry>* bodies) {
    {
        HashWriter w;
        HashSettings(w, world);
        out[0] = w.Digest();
    }
    {
        HashWriter w;
        Tag(w, b2HashCategory::e_bodies);
        HashPool(w, world.m_bodies);
        for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext()) HashBodyFields(w, *b);
        out[1] = w.Digest();
    }
    {
        HashWriter w;
        Tag(w, b2HashCategory::e_fixtures);
        HashPool(w, world.m_fixtures);
        for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext())
            for (const b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) HashFixture(w, *f);
        out[2] = w.Digest();
    }
    {
        HashWriter w;
        Tag(w, b2HashCategory::e_contacts);
        HashPool(w, world.GetContactManager().GetPool());
        for (const b2Contact* c = world.GetContactList(); c; c = c->GetNext()) HashContact(w, *c);
        out[3] = w.Digest();
    }
    {
        HashWriter w;
        Tag(w, b2HashCategory::e_joints);
        for (const b2Joint* j = world.m_jointList; j; j = j->GetNext()) state_detail::HashJoint(w, *j);
        out[4] = w.Digest();
    }
    {
        HashWriter w;
        HashBroadPhase(w, world);
        out[5] = w.Digest();
    }
    if (bodies != nullptr) {
        for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext())
            bodies->push_back({b->GetId(), b2BodyStateHash(*b)});
    }
}

uint64 Combine(const uint64 categories[]) {
    HashWriter w;
    w.U32(b2_hashVersion);
    for (uint32 i = 0; i < static_cast<uint32>(b2HashCategory::e_count); ++i) w.U64(categories[i]);
    return w.Digest();
}

}  // namespace

std::string_view b2HashCategoryName(b2HashCategory category) noexcept {
    switch (category) {
        case b2HashCategory::e_settings: return "settings";
        case b2HashCategory::e_bodies: return "bodies";
        case b2HashCategory::e_fixtures: return "fixtures";
        case b2HashCategory::e_contacts: return "contacts";
        case b2HashCategory::e_joints: return "joints";
        case b2HashCategory::e_broadphase: return "broadphase";
        default: return "none";
    }
}

uint64 b2BodyStateHash(const b2Body& body) {
    HashWriter w;
    w.U32(b2_hashVersion);
    HashBodyFields(w, body);
    for (const b2Fixture* f = body.GetFixtureList(); f; f = f->GetNext()) HashFixture(w, *f);
    return w.Digest();
}

uint64 b2WorldHash(const b2World& world) {
    uint64 categories[static_cast<uint32>(b2HashCategory::e_count)];
    HashAll(world, categories, nullptr);
    return Combine(categories);
}

b2WorldHashReport b2WorldHashDetailed(const b2World& world) {
    b2WorldHashReport report;
    report.bodies.reserve(static_cast<size_t>(world.GetBodyCount()));
    HashAll(world, report.categories, &report.bodies);
    report.total = Combine(report.categories);
    return report;
}

b2HashMismatch b2CompareHashReports(const b2WorldHashReport& a, const b2WorldHashReport& b) noexcept {
    b2HashMismatch result;
    for (uint32 i = 0; i < static_cast<uint32>(b2HashCategory::e_count); ++i) {
        if (a.categories[i] != b.categories[i]) {
            result.category = static_cast<b2HashCategory>(i);
            break;
        }
    }
    const size_t n = a.bodies.size() < b.bodies.size() ? a.bodies.size() : b.bodies.size();
    for (size_t i = 0; i < n; ++i) {
        if (a.bodies[i].bodyId != b.bodies[i].bodyId || a.bodies[i].hash != b.bodies[i].hash) {
            result.bodyId = a.bodies[i].bodyId;
            return result;
        }
    }
    if (a.bodies.size() != b.bodies.size()) {
        const auto& longer = a.bodies.size() > b.bodies.size() ? a.bodies : b.bodies;
        result.bodyId = longer[n].bodyId;
    }
    return result;
}

}  // namespace lockbox
