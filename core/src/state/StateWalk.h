#pragma once
// The canonical walk over a world's state: every field that influences future steps, in one
// fixed order with fixed widths. The state hash (WorldHash.cpp, into XXH3) and the snapshot
// (Snapshot.cpp, into the image's sections) both run this walk, so they cannot drift apart; the
// snapshot reader (SnapshotParse.cpp) reads the same order back. docs/determinism.md lists
// the fields. Any change here changes both: bump b2_hashVersion and b2_snapshotFormatVersion.
// The one exception is the joint-reaction walk (WriteJointReactions): a snapshot section that
// no hash category covers (a change there bumps only the snapshot format).
//
// A writer W provides U8/U16/U32/U64/I32/I64/Bool/F (Fixed)/W (Wide)/V (b2Vec2), and for
// hot records Begin(maxBytes) -> ByteCursor (the same field calls, unchecked) and End(cursor).

#include <type_traits>

#include "ListWalk.h"
#include "dynamics/WorldState.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joints.h"

namespace lockbox::state_detail {

using StateWalk = core_detail::Engine::StateWalk;

/// Calls f(std::type_identity<T>{}) with T the concrete joint class of `type` (nothing for
/// e_unknownJoint): the one place the state code maps a joint type to its class.
template <class F>
void WithJointClass(b2JointType type, F&& f) {
    switch (type) {
        case e_revoluteJoint: f(std::type_identity<b2RevoluteJoint>{}); break;
        case e_prismaticJoint: f(std::type_identity<b2PrismaticJoint>{}); break;
        case e_distanceJoint: f(std::type_identity<b2DistanceJoint>{}); break;
        case e_pulleyJoint: f(std::type_identity<b2PulleyJoint>{}); break;
        case e_mouseJoint: f(std::type_identity<b2MouseJoint>{}); break;
        case e_gearJoint: f(std::type_identity<b2GearJoint>{}); break;
        case e_wheelJoint: f(std::type_identity<b2WheelJoint>{}); break;
        case e_weldJoint: f(std::type_identity<b2WeldJoint>{}); break;
        case e_frictionJoint: f(std::type_identity<b2FrictionJoint>{}); break;
        case e_ropeJoint: f(std::type_identity<b2RopeJoint>{}); break;
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
    void Put(const b2WideVec2& x) {
        w.W(x.x);
        w.W(x.y);
    }
    void Put(const b2WideVec3& x) {
        w.W(x.x);
        w.W(x.y);
        w.W(x.z);
    }
    void Put(bool x) { w.Bool(x); }
    void Put(b2LimitState x) { w.U8(static_cast<uint32>(x)); }
    void Put(b2JointType x) { w.U8(static_cast<uint32>(x)); }
    void BodyRef(const b2Body* b) { w.I32(b != nullptr ? b->GetId() : b2_nullId); }
    void JointRef(const b2Joint* j) { w.I32(j != nullptr ? j->GetId() : b2_nullId); }
};

/// Record sizes in bytes, for the writers' one room check per record (Begin) and the
/// reader's (SnapshotParse.cpp). Each is the sum of the field widths written below.
inline constexpr size_t kBodyRecordBytes = 175;
/// Fixture fields (35), shape type and radius (5), at most a polygon of 8 (140), proxy count
/// (4) and one proxy (20): every non-chain fixture in one record.
inline constexpr size_t kFixtureHeadBytes = 35;
inline constexpr size_t kFixtureMaxBytes = kFixtureHeadBytes + 5 + 12 + 16 * b2_maxPolygonVertices + 4 + 20;
inline constexpr size_t kProxyBytes = 20;
/// Contact fields and manifold header (58), then 28 per manifold point.
inline constexpr size_t kContactHeadBytes = 58;
inline constexpr size_t kContactPointBytes = 28;
inline constexpr size_t kContactMaxBytes = kContactHeadBytes + kContactPointBytes * b2_maxManifoldPoints;
/// A tree node: height, then either the free link (4) or AABB, user data, links (36).
inline constexpr size_t kTreeNodeMaxBytes = 40;
/// Lists of int32 go out in chunks of this many entries per room check.
inline constexpr size_t kIdChunk = 128;

/// A list of int32 ids, in chunks of kIdChunk per room check.
template <class W>
void WriteIds(W& w, const int32* ids, size_t count) {
    for (size_t at = 0; at < count; at += kIdChunk) {
        const size_t n = count - at < kIdChunk ? count - at : kIdChunk;
        auto c = w.Begin(4 * kIdChunk);
        for (size_t i = 0; i < n; ++i) c.I32(ids[at + i]);
        w.End(c);
    }
}

template <class W, class T>
void WritePool(W& w, const b2Pool<T>& pool) {
    w.I32(pool.GetCapacity());
    w.I32(pool.GetCount());
    const auto& free = pool.GetFreeList();
    w.I32(static_cast<int32>(free.size()));
    WriteIds(w, free.data(), free.size());
}

template <class W>
void WriteAABB(W& w, const b2AABB& box) {
    w.V(box.lowerBound);
    w.V(box.upperBound);
}

/// `withContacts` false writes a contact count of 0 (the rollback frames' structure image,
/// whose contact section is empty: WriteNoContacts).
template <class W>
void WriteSettings(W& w, const b2World& world, bool withContacts = true) {
    w.V(world.GetGravity());
    w.Bool(world.GetAllowSleeping());
    w.Bool(world.GetWarmStarting());
    w.Bool(world.GetContinuousPhysics());
    w.Bool(world.GetSubStepping());
    w.Bool(world.GetAutoClearForces());
    WriteAABB(w, world.GetWorldBounds());
    // e_newFixture makes the next step look for new pairs first; e_clearForces mirrors the
    // auto-clear switch. e_locked is always clear outside Step.
    const core_detail::Engine::World& in = core_detail::Engine::Of(world);
    w.U32(in.m_flags);
    // The previous step's inverse length scales warm starting (dtRatio) of the next one.
    w.F(in.m_inv_dt0);
    w.Bool(in.m_stepComplete);
    w.U64(world.GetSaturationCount());
    w.I32(world.GetBodyCount());
    w.I32(world.GetJointCount());
    w.I32(withContacts ? world.GetContactCount() : 0);
}

/// A shape's fields, all but a chain's (WriteChainShape): type, radius, then by type.
template <class C>
void WriteShapeFixed(C& c, const b2Shape& shape) {
    c.U8(static_cast<uint32>(shape.GetType()));
    c.F(shape.m_radius);
    switch (shape.GetType()) {
        case b2Shape::e_circle: c.V(static_cast<const b2CircleShape&>(shape).m_p); break;
        case b2Shape::e_edge: {
            const auto& e = static_cast<const b2EdgeShape&>(shape);
            c.V(e.m_vertex0);
            c.V(e.m_vertex1);
            c.V(e.m_vertex2);
            c.V(e.m_vertex3);
            c.Bool(e.m_hasVertex0);
            c.Bool(e.m_hasVertex3);
            break;
        }
        case b2Shape::e_polygon: {
            const auto& p = static_cast<const b2PolygonShape&>(shape);
            c.V(p.m_centroid);
            c.I32(p.m_vertexCount);
            // Only the live vertices: slots past the count are never read.
            for (int32 i = 0; i < p.m_vertexCount; ++i) {
                c.V(p.m_vertices[i]);
                c.V(p.m_normals[i]);
            }
            break;
        }
        default: break;
    }
}

/// The rest of a chain shape after its type and radius (any length: field by field).
template <class W>
void WriteChainShape(W& w, const b2ChainShape& c) {
    w.I32(c.m_count);
    for (const b2Vec2& v : c.m_vertices) w.V(v);
    w.V(c.m_prevVertex);
    w.V(c.m_nextVertex);
    w.Bool(c.m_hasPrevVertex);
    w.Bool(c.m_hasNextVertex);
}

template <class C>
void WriteProxy(C& c, const b2FixtureProxy& proxy) {
    c.V(proxy.aabb.lowerBound);
    c.V(proxy.aabb.upperBound);
    c.I32(proxy.proxyId);
}

/// A joint record's fixed head: id, type, body A, body B, collideConnected, user data.
inline constexpr size_t kJointHeadBytes = 4 + 1 + 4 + 4 + 1 + 8;
/// Room for any joint record (head and VisitState fields; the largest, a gear joint's, is
/// about 130 bytes): one room check per joint. JointStateBytes (JointState.h) checks the bound
/// against the counted sizes.
inline constexpr size_t kJointRecordMaxBytes = 256;

}  // namespace lockbox::state_detail

namespace lockbox {

/// The walk's records that read the core classes' private fields.
struct core_detail::Engine::StateWalk {
    /// Calls j.VisitState(v) on the concrete joint type.
    template <class V>
    static void VisitJointState(b2Joint& j, V& v) {
        state_detail::WithJointClass(j.GetType(),
                                     [&](auto cls) { static_cast<typename decltype(cls)::type&>(j).VisitState(v); });
    }

    /// Calls j.VisitReactionState(v) on the concrete joint type; nothing for a type whose reaction
    /// queries read only its VisitState fields (revolute, mouse, weld, friction).
    template <class V>
    static void VisitJointReaction(b2Joint& j, V& v) {
        state_detail::WithJointClass(j.GetType(), [&](auto cls) {
            using T = typename decltype(cls)::type;
            if constexpr (requires(T & t) { t.VisitReactionState(v); }) static_cast<T&>(j).VisitReactionState(v);
        });
    }

    template <class W>
    static void WriteBody(W& w, const b2Body& b) {
        auto c = w.Begin(state_detail::kBodyRecordBytes);
        c.I32(b.GetId());
        c.U8(static_cast<uint32>(b.GetType()));
        c.U16(b.m_flags);
        c.V(b.m_xf.p);
        c.F(b.m_xf.q.s);
        c.F(b.m_xf.q.c);
        const b2Sweep& sw = b.m_sweep;
        c.V(sw.localCenter);
        c.V(sw.c0);
        c.V(sw.c);
        c.F(sw.a0);
        c.F(sw.a);
        c.F(sw.alpha0);
        c.V(b.m_linearVelocity);
        c.F(b.m_angularVelocity);
        c.I32(b.m_velocityRemainder.x);
        c.I32(b.m_velocityRemainder.y);
        c.I32(b.m_velocityRemainder.w);
        c.I32(b.m_positionRemainder.x);
        c.I32(b.m_positionRemainder.y);
        c.I32(b.m_positionRemainder.w);
        c.V(b.m_force);
        c.F(b.m_torque);
        c.I32(b.m_sleepSteps);
        c.W(b.m_mass);
        c.W(b.m_invMass);
        c.W(b.m_I);
        c.W(b.m_invI);
        c.F(b.m_linearDamping);
        c.F(b.m_angularDamping);
        c.F(b.m_gravityScale);
        c.F(b.m_minExtent);
        c.F(b.m_maxExtent);
        c.U64(b.m_userData);
        c.I32(b.m_fixtureCount);
        w.End(c);
        // The body's contact and joint edge lists are not written: both are always in world-list
        // order (every create prepends to the world list and to both bodies' lists, every destroy
        // unlinks), so the contact and joint sections already fix them. Restore rebuilds them.
    }

    template <class W>
    static void WriteFixture(W& w, const b2Fixture& f) {
        const b2Shape& shape = *f.GetShape();
        auto c = w.Begin(state_detail::kFixtureMaxBytes);
        c.I32(f.GetId());
        c.I32(f.GetBody()->GetId());
        c.F(f.m_density);
        c.F(f.m_friction);
        c.F(f.m_restitution);
        c.Bool(f.m_isSensor);
        c.U16(f.m_filter.categoryBits);
        c.U16(f.m_filter.maskBits);
        c.U16(static_cast<uint16>(f.m_filter.groupIndex));
        c.U64(f.m_userData);
        state_detail::WriteShapeFixed(c, shape);
        // Proxies exist only while the body is active: 0 or one per child.
        int32 i = 0;
        if (shape.GetType() != b2Shape::e_chain) {
            // One child: its proxy (if any) fits in the same record.
            c.I32(f.m_proxyCount);
            if (f.m_proxyCount > 0) state_detail::WriteProxy(c, f.m_proxies[static_cast<size_t>(i++)]);
            w.End(c);
        } else {
            w.End(c);
            state_detail::WriteChainShape(w, static_cast<const b2ChainShape&>(shape));
            w.I32(f.m_proxyCount);
        }
        for (; i < f.m_proxyCount; ++i) {
            auto pc = w.Begin(state_detail::kProxyBytes);
            state_detail::WriteProxy(pc, f.m_proxies[static_cast<size_t>(i)]);
            w.End(pc);
        }
    }

    template <class W>
    static void WriteContact(W& w, const b2Contact& contact) {
        auto c = w.Begin(state_detail::kContactMaxBytes);
        c.I32(contact.GetId());
        c.I32(contact.m_fixtureIdA);
        c.I32(contact.m_indexA);
        c.I32(contact.m_fixtureIdB);
        c.I32(contact.m_indexB);
        c.U32(contact.m_flags);
        c.I32(contact.m_toiCount);
        c.F(contact.m_toi);
        c.F(contact.m_friction);
        c.F(contact.m_restitution);
        const b2Manifold& m = contact.m_manifold;
        c.U8(static_cast<uint32>(m.type));
        c.U8(static_cast<uint32>(m.pointCount));
        c.V(m.localNormal);
        c.V(m.localPoint);
        // Points past pointCount are stale and never matched: left out.
        for (int32 i = 0; i < m.pointCount; ++i) {
            const b2ManifoldPoint& p = m.points[i];
            c.V(p.localPoint);
            c.W(p.normalImpulse);
            c.W(p.tangentImpulse);
            c.U32(p.id.Key());
        }
        w.End(c);
    }

    template <class W>
    static void WriteJoint(W& w, const b2Joint& j) {
        auto c = w.Begin(state_detail::kJointRecordMaxBytes);
        c.I32(j.GetId());
        c.U8(static_cast<uint32>(j.GetType()));
        c.I32(j.m_bodyA->GetId());
        c.I32(j.m_bodyB->GetId());
        c.Bool(j.m_collideConnected);
        c.U64(j.m_userData);
        state_detail::JointFieldWriter<decltype(c)> visitor{c};
        // VisitState is shared with the restore path, which writes the fields; here it only reads.
        VisitJointState(const_cast<b2Joint&>(j), visitor);
        w.End(c);
    }
};

}  // namespace lockbox

namespace lockbox::state_detail {

/// The joint-reaction section (snapshot only, not hashed): for every joint in joint-list
/// order, the fields of its VisitReactionState (none for some types).
template <class W>
void WriteJointReactions(W& w, const b2World& world) {
    for (const b2Joint* j = world.GetJointList(); j; j = j->GetNext()) {
        auto c = w.Begin(kJointRecordMaxBytes);
        JointFieldWriter<decltype(c)> visitor{c};
        StateWalk::VisitJointReaction(const_cast<b2Joint&>(*j), visitor);
        w.End(c);
    }
}

template <class C>
void WriteTreeNode(C& c, const b2TreeNode& n) {
    // A free slot is canonical (FreeNode resets it): only its free-list link matters.
    c.I32(n.height);
    if (n.height < 0) {
        c.I32(n.next);
        return;
    }
    c.V(n.aabb.lowerBound);
    c.V(n.aabb.upperBound);
    c.U64(n.userData);
    c.I32(n.parent);
    c.I32(n.child1);
    c.I32(n.child2);
}

template <class W>
void WriteBroadPhase(W& w, const b2World& world) {
    const b2BroadPhase& bp = core_detail::Engine::Of(world).m_contactManager.m_broadPhase;
    const b2DynamicTree& tree = bp.GetTree();
    w.I32(bp.GetProxyCount());
    w.I32(tree.GetRoot());
    w.I32(tree.GetFreeList());
    w.I32(tree.GetNodeCount());
    w.I32(tree.GetInsertionCount());
    const auto& nodes = tree.GetNodes();
    w.I32(static_cast<int32>(nodes.size()));
    // The nodes lie in one array: 16 per room check.
    constexpr size_t kChunk = 16;
    for (size_t at = 0; at < nodes.size(); at += kChunk) {
        const size_t n = nodes.size() - at < kChunk ? nodes.size() - at : kChunk;
        auto c = w.Begin(kTreeNodeMaxBytes * kChunk);
        for (size_t i = 0; i < n; ++i) WriteTreeNode(c, nodes[at + i]);
        w.End(c);
    }
    const auto& moves = bp.GetMoveBuffer();
    w.I32(static_cast<int32>(moves.size()));
    WriteIds(w, moves.data(), moves.size());
}

/// The body section: pool, then every body in body-list order.
template <class W>
void WriteBodies(W& w, const b2World& world) {
    WritePool(w, core_detail::Engine::Of(world).m_bodies);
    WalkList(
        world.GetBodyList(), [&](const b2Body& b) { StateWalk::WriteBody(w, b); }, [](const b2Body*) {});
}

/// The fixture section: pool, then each body's fixtures (body-list order, fixture-list order).
template <class W>
void WriteFixtures(W& w, const b2World& world) {
    WritePool(w, core_detail::Engine::Of(world).m_fixtures);
    WalkList(
        world.GetBodyList(),
        [&](const b2Body& b) {
            // The next body's first fixture was requested a node ago: now its shape.
            const b2Body* next = b.GetNext();
            if (next != nullptr && next->GetFixtureList() != nullptr) {
                PrefetchBytes(next->GetFixtureList()->GetShape(), kShapePrefetchBytes);
            }
            for (const b2Fixture* f = b.GetFixtureList(); f; f = f->GetNext()) StateWalk::WriteFixture(w, *f);
        },
        [](const b2Body* b) {
            if (b->GetFixtureList() != nullptr) PrefetchObject(b->GetFixtureList());
        });
}

/// The contact section: pool, then every contact in contact-list order.
template <class W>
void WriteContacts(W& w, const b2World& world) {
    WritePool(w, core_detail::Engine::Of(world).m_contactManager.GetPool());
    // The record's fixture ids are cached in the contact: no fixture is visited.
    WalkList(
        world.GetContactList(), [&](const b2Contact& c) { StateWalk::WriteContact(w, c); }, [](const b2Contact*) {});
}

/// An empty contact section (an empty pool): a valid image of the world without its contacts.
template <class W>
void WriteNoContacts(W& w) {
    w.I32(0);  // capacity
    w.I32(0);  // count
    w.I32(0);  // free stack
}

/// The joint section: every joint in joint-list order.
template <class W>
void WriteJoints(W& w, const b2World& world) {
    for (const b2Joint* j = world.GetJointList(); j; j = j->GetNext()) StateWalk::WriteJoint(w, *j);
}

}  // namespace lockbox::state_detail
