#pragma once
// The canonical walk over a world's state: every field that influences future steps, in one
// fixed order with fixed widths. The state hash (WorldHash.cpp, into XXH3) and the snapshot
// (SnapshotSave.cpp, into Cereal) both run this walk, so they cannot drift apart; the
// snapshot reader (SnapshotParse.cpp) reads the same order back. docs/determinism.md lists
// the fields. Any change here changes both: bump b2_hashVersion and b2_snapshotFormatVersion.
//
// A writer W provides U8/U16/U32/U64/I32/I64/Bool/F (Fixed)/W (Wide)/V (b2Vec2).

#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joints.h"

namespace lockbox::state_detail {

/// Calls j.VisitState(v) on the concrete joint type.
template <class V>
void VisitJointState(b2Joint& j, V& v) {
    switch (j.GetType()) {
        case e_revoluteJoint: static_cast<b2RevoluteJoint&>(j).VisitState(v); break;
        case e_prismaticJoint: static_cast<b2PrismaticJoint&>(j).VisitState(v); break;
        case e_distanceJoint: static_cast<b2DistanceJoint&>(j).VisitState(v); break;
        case e_pulleyJoint: static_cast<b2PulleyJoint&>(j).VisitState(v); break;
        case e_mouseJoint: static_cast<b2MouseJoint&>(j).VisitState(v); break;
        case e_gearJoint: static_cast<b2GearJoint&>(j).VisitState(v); break;
        case e_wheelJoint: static_cast<b2WheelJoint&>(j).VisitState(v); break;
        case e_weldJoint: static_cast<b2WeldJoint&>(j).VisitState(v); break;
        case e_frictionJoint: static_cast<b2FrictionJoint&>(j).VisitState(v); break;
        case e_ropeJoint: static_cast<b2RopeJoint&>(j).VisitState(v); break;
        case e_unknownJoint: break;
    }
}

/// Adapts a writer to the joints' VisitState protocol (read-only use of the fields).
template <class W>
struct JointFieldWriter {
    W& w;
    template <class... T>
    void operator()(const T&... fields) {
        (Put(fields), ...);
    }
    void Put(Fixed x) { w.F(x); }
    void Put(Wide x) { w.W(x); }
    void Put(const b2Vec2& x) { w.V(x); }
    void Put(const b2WideVec2& x) { w.W(x.x); w.W(x.y); }
    void Put(const b2WideVec3& x) { w.W(x.x); w.W(x.y); w.W(x.z); }
    void Put(bool x) { w.Bool(x); }
    void Put(b2LimitState x) { w.U8(static_cast<uint32>(x)); }
    void Put(b2JointType x) { w.U8(static_cast<uint32>(x)); }
    void BodyRef(const b2Body* b) { w.I32(b != nullptr ? b->GetId() : b2_nullId); }
    void JointRef(const b2Joint* j) { w.I32(j != nullptr ? j->GetId() : b2_nullId); }
};

template <class W, class T>
void WritePool(W& w, const b2Pool<T>& pool) {
    w.I32(pool.GetCapacity());
    w.I32(pool.GetCount());
    const auto& free = pool.GetFreeList();
    w.I32(static_cast<int32>(free.size()));
    for (const int32 id : free) w.I32(id);
}

template <class W>
void WriteAABB(W& w, const b2AABB& box) {
    w.V(box.lowerBound);
    w.V(box.upperBound);
}

template <class W>
void WriteSettings(W& w, const b2World& world) {
    w.V(world.GetGravity());
    w.Bool(world.GetAllowSleeping());
    w.Bool(world.GetWarmStarting());
    w.Bool(world.GetContinuousPhysics());
    w.Bool(world.GetSubStepping());
    w.Bool(world.GetAutoClearForces());
    WriteAABB(w, world.GetWorldBounds());
    // e_newFixture makes the next step look for new pairs first; e_clearForces mirrors the
    // auto-clear switch. e_locked is always clear outside Step.
    w.U32(world.m_flags);
    // The previous step's inverse length scales warm starting (dtRatio) of the next one.
    w.F(world.m_inv_dt0);
    w.Bool(world.m_stepComplete);
    w.U64(world.GetSaturationCount());
    w.I32(world.GetBodyCount());
    w.I32(world.GetJointCount());
    w.I32(world.GetContactCount());
}

template <class W>
void WriteBody(W& w, const b2Body& b) {
    w.I32(b.GetId());
    w.U8(static_cast<uint32>(b.GetType()));
    w.U16(b.m_flags);
    w.V(b.m_xf.p);
    w.F(b.m_xf.q.s);
    w.F(b.m_xf.q.c);
    const b2Sweep& sw = b.m_sweep;
    w.V(sw.localCenter);
    w.V(sw.c0);
    w.V(sw.c);
    w.F(sw.a0);
    w.F(sw.a);
    w.F(sw.alpha0);
    w.V(b.m_linearVelocity);
    w.F(b.m_angularVelocity);
    w.V(b.m_force);
    w.F(b.m_torque);
    w.I32(b.m_sleepSteps);
    w.W(b.m_mass);
    w.W(b.m_invMass);
    w.W(b.m_I);
    w.W(b.m_invI);
    w.F(b.m_linearDamping);
    w.F(b.m_angularDamping);
    w.F(b.m_gravityScale);
    w.F(b.m_minExtent);
    w.F(b.m_maxExtent);
    w.U64(b.m_userData);
    w.I32(b.m_fixtureCount);
    // The body's contact and joint edge lists are not written: both are always in world-list
    // order (every create prepends to the world list and to both bodies' lists, every destroy
    // unlinks), so the contact and joint sections already fix them. Restore rebuilds them.
}

template <class W>
void WriteShape(W& w, const b2Shape& shape) {
    w.U8(static_cast<uint32>(shape.GetType()));
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

template <class W>
void WriteFixture(W& w, const b2Fixture& f) {
    w.I32(f.GetId());
    w.I32(f.GetBody()->GetId());
    w.F(f.m_density);
    w.F(f.m_friction);
    w.F(f.m_restitution);
    w.Bool(f.m_isSensor);
    w.U16(f.m_filter.categoryBits);
    w.U16(f.m_filter.maskBits);
    w.U16(static_cast<uint16>(f.m_filter.groupIndex));
    w.U64(f.m_userData);
    WriteShape(w, *f.GetShape());
    // Proxies exist only while the body is active: 0 or one per child.
    w.I32(f.m_proxyCount);
    for (int32 i = 0; i < f.m_proxyCount; ++i) {
        const b2FixtureProxy& proxy = f.m_proxies[static_cast<size_t>(i)];
        WriteAABB(w, proxy.aabb);
        w.I32(proxy.proxyId);
    }
}

template <class W>
void WriteContact(W& w, const b2Contact& c) {
    w.I32(c.GetId());
    w.I32(c.m_fixtureA->GetId());
    w.I32(c.m_indexA);
    w.I32(c.m_fixtureB->GetId());
    w.I32(c.m_indexB);
    w.U32(c.m_flags);
    w.I32(c.m_toiCount);
    w.F(c.m_toi);
    w.F(c.m_friction);
    w.F(c.m_restitution);
    const b2Manifold& m = c.m_manifold;
    w.U8(static_cast<uint32>(m.type));
    w.U8(static_cast<uint32>(m.pointCount));
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

template <class W>
void WriteJoint(W& w, const b2Joint& j) {
    w.I32(j.GetId());
    w.U8(static_cast<uint32>(j.GetType()));
    w.I32(j.m_bodyA->GetId());
    w.I32(j.m_bodyB->GetId());
    w.Bool(j.m_collideConnected);
    w.U64(j.m_userData);
    JointFieldWriter<W> visitor{w};
    // VisitState is shared with the restore path, which writes the fields; here it only reads.
    VisitJointState(const_cast<b2Joint&>(j), visitor);
}

template <class W>
void WriteBroadPhase(W& w, const b2World& world) {
    const b2BroadPhase& bp = world.GetContactManager().m_broadPhase;
    const b2DynamicTree& tree = bp.GetTree();
    w.I32(bp.GetProxyCount());
    w.I32(tree.GetRoot());
    w.I32(tree.GetFreeList());
    w.I32(tree.GetNodeCount());
    w.I32(tree.GetInsertionCount());
    const auto& nodes = tree.GetNodes();
    w.I32(static_cast<int32>(nodes.size()));
    for (const b2TreeNode& n : nodes) {
        // A free slot is canonical (FreeNode resets it): only its free-list link matters.
        w.I32(n.height);
        if (n.height < 0) {
            w.I32(n.next);
            continue;
        }
        WriteAABB(w, n.aabb);
        w.U64(n.userData);
        w.I32(n.parent);
        w.I32(n.child1);
        w.I32(n.child2);
    }
    const auto& moves = bp.GetMoveBuffer();
    w.I32(static_cast<int32>(moves.size()));
    for (const int32 id : moves) w.I32(id);
}

/// Starts loading the object after next while the current one is written: list order is
/// not memory order, and waiting for each object's cache lines dominated the walk.
template <class T>
inline void PrefetchAhead(const T* node) noexcept {
    if (node != nullptr && node->GetNext() != nullptr) {
        const char* p = reinterpret_cast<const char*>(node->GetNext());
        for (size_t line = 0; line < sizeof(T); line += 64) __builtin_prefetch(p + line);
    }
}

/// The body section: pool, then every body in body-list order.
template <class W>
void WriteBodies(W& w, const b2World& world) {
    WritePool(w, world.m_bodies);
    for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        PrefetchAhead(b->GetNext());
        WriteBody(w, *b);
    }
}

/// The fixture section: pool, then each body's fixtures (body-list order, fixture-list order).
template <class W>
void WriteFixtures(W& w, const b2World& world) {
    WritePool(w, world.m_fixtures);
    for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext())
        for (const b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) WriteFixture(w, *f);
}

/// The contact section: pool, then every contact in contact-list order.
template <class W>
void WriteContacts(W& w, const b2World& world) {
    WritePool(w, world.GetContactManager().GetPool());
    for (const b2Contact* c = world.GetContactList(); c; c = c->GetNext()) {
        PrefetchAhead(c->GetNext());
        WriteContact(w, *c);
    }
}

/// The joint section: every joint in joint-list order.
template <class W>
void WriteJoints(W& w, const b2World& world) {
    for (const b2Joint* j = world.m_jointList; j; j = j->GetNext()) WriteJoint(w, *j);
}

}  // namespace lockbox::state_detail
