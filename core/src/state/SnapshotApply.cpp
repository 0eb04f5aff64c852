// Installing a validated snapshot image into a world. Pools take the image's exact slot
// layout (objects in slots live on both sides stay where they are), every field is
// overwritten, then all lists and edges are relinked from the image's orders. No listener
// is called: a restore is not a simulation event.

#include <memory>
#include <new>
#include <vector>

#include "ByteCursor.h"
#include "JointState.h"
#include "SnapshotImage.h"
#include "StateWalk.h"
#include "dynamics/joints/JointAccess.h"

namespace lockbox {

/// The snapshot's apply pass: it writes the core classes' private fields.
struct core_detail::Engine::SnapshotApply {
    using Image = state_detail::Image;
    using BodyImage = state_detail::BodyImage;
    using ShapeImage = state_detail::ShapeImage;
    using FixtureImage = state_detail::FixtureImage;
    using ProxyImage = state_detail::ProxyImage;
    using ContactImage = state_detail::ContactImage;
    using JointImage = state_detail::JointImage;
    using JointStateSizes = state_detail::JointStateSizes;

    /// Records ahead whose world object is requested while the current one is written: image
    /// order is list order, not memory order, so each object would otherwise be a cache miss.
    static constexpr size_t kApplyPrefetch = 6;

    /// A body's state from its image record, read from the transform on (the layout of
    /// WriteBody, StateWalk.h); every value is valid.
    static void ApplyBodyState(const uint8* at, b2Body& b) {
        state_detail::ReadCursor r(at);
        b.m_xf.p = r.V();
        b.m_xf.q.s = r.F();
        b.m_xf.q.c = r.F();
        b2Sweep& sw = b.m_sweep;
        sw.localCenter = r.V();
        sw.c0 = r.V();
        sw.c = r.V();
        sw.a0 = r.F();
        sw.a = r.F();
        sw.alpha0 = r.F();
        b.m_linearVelocity = r.V();
        b.m_angularVelocity = r.F();
        b.m_velocityRemainder.x = r.I32();
        b.m_velocityRemainder.y = r.I32();
        b.m_velocityRemainder.w = r.I32();
        b.m_positionRemainder.x = r.I32();
        b.m_positionRemainder.y = r.I32();
        b.m_positionRemainder.w = r.I32();
        b.m_force = r.V();
        b.m_torque = r.F();
        b.m_sleepSteps = r.I32();
        b.m_mass = r.W();
        b.m_invMass = r.W();
        b.m_I = r.W();
        b.m_invI = r.W();
        b.m_linearDamping = r.F();
        b.m_angularDamping = r.F();
        b.m_gravityScale = r.F();
        b.m_minExtent = r.F();
        b.m_maxExtent = r.F();
        b.m_userData = r.U64();
    }

    static void ApplyBodies(const Image& img, World& world) {
        const b2BodyDef def;
        world.m_bodies.RestoreLayout(img.bodyPool.live, img.bodyPool.free,
                                     [&](void* slot, int32 id) { ::new (slot) b2Body(&def, world.m_owner, id); });
        b2Body* previous = nullptr;
        world.m_bodyList = nullptr;
        const size_t count = img.bodies.size();
        for (size_t i = 0; i < count; ++i) {
            const BodyImage& bi = img.bodies[i];
            if (i + kApplyPrefetch < count)
                state_detail::PrefetchObject(world.m_bodies.Get(img.bodies[i + kApplyPrefetch].id));
            b2Body* b = world.m_bodies.Get(bi.id);
            b->m_type = static_cast<b2BodyType>(bi.type);
            b->m_flags = bi.flags;
            b->m_islandIndex = 0;
            ApplyBodyState(img.bytes + bi.stateAt, *b);
            b->m_world = world.m_owner;
            b->m_id = bi.id;
            b->m_fixtureCount = bi.fixtureCount;
            b->m_fixtureList = nullptr;
            b->m_contactList = nullptr;
            b->m_toiContacts = 0;
            b->m_jointList = nullptr;
            // World body list in image order.
            b->m_listKey = previous != nullptr ? previous->m_listKey + 1 : 0;
            state_detail::AppendToWorldList(b, world.m_bodyList, previous);
        }
        world.m_bodyCount = static_cast<int32>(img.bodies.size());
        world.m_forcesApplied = true;  // the image's forces were not looked at
    }

    /// A shape of the image's type holding its fields; reuses `current` when the type matches.
    static void ApplyShape(const Image& img, const ShapeImage& si, std::unique_ptr<b2Shape>& current) {
        const auto type = static_cast<b2Shape::Type>(si.type);
        if (!current || current->GetType() != type) {
            switch (type) {
                case b2Shape::e_circle: current = std::make_unique<b2CircleShape>(); break;
                case b2Shape::e_edge: current = std::make_unique<b2EdgeShape>(); break;
                case b2Shape::e_polygon: current = std::make_unique<b2PolygonShape>(); break;
                default: current = std::make_unique<b2ChainShape>(); break;
            }
        }
        current->m_radius = si.radius;
        switch (type) {
            case b2Shape::e_circle: static_cast<b2CircleShape&>(*current).m_p = si.p; break;
            case b2Shape::e_edge: {
                auto& e = static_cast<b2EdgeShape&>(*current);
                e.m_vertex0 = si.v0;
                e.m_vertex1 = si.v1;
                e.m_vertex2 = si.v2;
                e.m_vertex3 = si.v3;
                e.m_hasVertex0 = si.has0;
                e.m_hasVertex3 = si.has3;
                break;
            }
            case b2Shape::e_polygon: {
                auto& p = static_cast<b2PolygonShape&>(*current);
                p.m_centroid = si.p;
                p.m_vertexCount = si.count;
                for (int32 i = 0; i < si.count; ++i) {
                    p.m_vertices[i] = si.vertices[i];
                    p.m_normals[i] = si.normals[i];
                }
                break;
            }
            default: {
                auto& c = static_cast<b2ChainShape&>(*current);
                const auto first = img.chainVertices.begin() + si.chainBegin;
                c.m_vertices.assign(first, first + si.count);
                c.m_count = si.count;
                c.m_prevVertex = si.prev;
                c.m_nextVertex = si.next;
                c.m_hasPrevVertex = si.hasPrev;
                c.m_hasNextVertex = si.hasNext;
                break;
            }
        }
    }

    static void ApplyFixtures(Image& img, World& world) {
        world.m_fixtures.RestoreLayout(img.fixturePool.live, img.fixturePool.free,
                                       [](void* slot, int32) { ::new (slot) b2Fixture(); });
        img.fixtureSlots.resize(static_cast<size_t>(img.fixturePool.capacity));
        // Fixtures come grouped by body in body-list order, each group in fixture-list order.
        size_t k = 0;
        const size_t count = img.fixtures.size();
        for (const BodyImage& bi : img.bodies) {
            b2Body* body = world.m_bodies.Get(bi.id);
            b2Fixture* previous = nullptr;
            for (int32 i = 0; i < bi.fixtureCount; ++i, ++k) {
                const FixtureImage& fi = img.fixtures[k];
                // Fixtures and their heap shapes lie apart from the image order: request the
                // fixture 2 distances ahead, and the shape of the one requested a distance ago.
                if (k + 2 * kApplyPrefetch < count) {
                    __builtin_prefetch(world.m_fixtures.Get(img.fixtures[k + 2 * kApplyPrefetch].id));
                }
                if (k + kApplyPrefetch < count) {
                    const b2Fixture* ahead = world.m_fixtures.Get(img.fixtures[k + kApplyPrefetch].id);
                    if (ahead->m_shape)
                        state_detail::PrefetchBytes(ahead->m_shape.get(), state_detail::kShapePrefetchBytes);
                }
                b2Fixture* f = world.m_fixtures.Get(fi.id);
                img.fixtureSlots[static_cast<size_t>(fi.id)] = {f, body, bi.id, fi.sensor};
                f->m_id = fi.id;
                f->m_body = body;
                f->m_density = fi.density;
                f->m_friction = fi.friction;
                f->m_restitution = fi.restitution;
                f->m_isSensor = fi.sensor;
                f->m_filter = fi.filter;
                f->m_userData = fi.userData;
                ApplyShape(img, fi.shape, f->m_shape);
                f->m_proxies.assign(static_cast<size_t>(fi.childCount), b2FixtureProxy{});
                for (int32 c = 0; c < fi.childCount; ++c) {
                    b2FixtureProxy& proxy = f->m_proxies[static_cast<size_t>(c)];
                    proxy.fixture = f;
                    proxy.childIndex = c;
                    proxy.proxyId = b2BroadPhase::e_nullProxy;
                    if (c < fi.proxyCount) {
                        const ProxyImage& pi = img.proxies[static_cast<size_t>(fi.proxyBegin + c)];
                        proxy.aabb = pi.aabb;
                        proxy.proxyId = pi.proxyId;
                    }
                }
                f->m_proxyCount = fi.proxyCount;
                f->m_next = nullptr;
                if (previous != nullptr)
                    previous->m_next = f;
                else
                    body->m_fixtureList = f;
                previous = f;
            }
        }
    }

    /// A contact's state from its image record, read from the flags field on (the layout of
    /// WriteContact; ReadContacts checked every value). Manifold points past the count are left
    /// as they are: they are never read.
    static void ApplyContactState(const uint8* at, b2Contact& c) {
        state_detail::ReadCursor r(at);
        c.m_flags = r.U32();
        c.m_toiCount = r.I32();
        c.m_toi = r.F();
        c.m_friction = r.F();
        c.m_restitution = r.F();
        b2Manifold& m = c.m_manifold;
        m.type = static_cast<b2Manifold::Type>(r.U8());
        m.pointCount = r.U8();
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

    static void ApplyContacts(Image& img, World& world) {
        b2ContactManager& cm = world.m_contactManager;
        b2Pool<b2Fixture>& fixtures = world.m_fixtures;
        // New slots are built from their image record (the constructor needs the fixtures);
        // validation left the id -> record map in contactIndex.
        const std::vector<int32>& recordOf = img.contactIndex;
        cm.RestoreContactLayout(img.contactPool.live, img.contactPool.free, [&](void* slot, int32 id) {
            const ContactImage& ci = img.contacts[static_cast<size_t>(recordOf[static_cast<size_t>(id)])];
            ::new (slot) b2Contact(fixtures.Get(ci.fixtureA), ci.indexA, fixtures.Get(ci.fixtureB), ci.indexB, id);
        });
        cm.m_contactList = nullptr;
        img.edgeTails.assign(static_cast<size_t>(img.bodyPool.capacity), nullptr);
        state_detail::ContactListTail tail{nullptr, img.edgeTails};
        const size_t count = img.contacts.size();
        for (size_t i = 0; i < count; ++i) {
            const ContactImage& ci = img.contacts[i];
            // The whole contact, graph edges included: the walks skip them, this pass writes them.
            if (i + kApplyPrefetch < count)
                state_detail::PrefetchBytes(cm.GetContact(img.contacts[i + kApplyPrefetch].id), sizeof(b2Contact));
            b2Contact* c = cm.GetContact(ci.id);
            ApplyContactState(img.bytes + ci.stateAt, *c);
            state_detail::LinkRestoredContact(
                c, ci.fixtureA, ci.indexA, ci.fixtureB, ci.indexB, img.fixtureSlots[static_cast<size_t>(ci.fixtureA)],
                img.fixtureSlots[static_cast<size_t>(ci.fixtureB)], cm.m_contactList, tail);
        }
        cm.m_contactCount = static_cast<int32>(img.contacts.size());
    }

    /// A joint's visited fields, straight from its record into the joint, then its reaction
    /// directions when the image has them; other solver temporaries are left as they are (every
    /// step recomputes them before use, and no query reads them).
    static void ReadJointState(const Image& img, const JointImage& ji, World& world) {
        b2Joint& joint = *world.m_joints[static_cast<size_t>(ji.id)];
        state_detail::JointStateReader reader{state_detail::ReadCursor(img.bytes + ji.stateAt), world};
        StateWalk::VisitJointState(joint, reader);
        if (ji.reactionAt != 0) {
            state_detail::JointStateReader reaction{state_detail::ReadCursor(img.bytes + ji.reactionAt), world};
            StateWalk::VisitJointReaction(joint, reaction);
        }
    }

    static void ApplyJoints(Image& img, World& world) {
        int32 maxId = -1;
        for (const JointImage& ji : img.joints) maxId = ji.id > maxId ? ji.id : maxId;
        // The id table keeps the world's joints until each id is visited: a joint of the image's
        // id and type is refilled where it is, any other is freed (no listener call) and made
        // afresh. The table only grows here, so a warm restore does not allocate.
        std::vector<b2Joint*>& table = world.m_joints;
        if (table.size() < static_cast<size_t>(maxId + 1)) table.resize(static_cast<size_t>(maxId + 1), nullptr);
        std::vector<uint8>& visited = img.jointVisited;
        visited.assign(table.size(), 0);
        // The last joint edge of each body so far, by body id (every body list starts empty).
        std::vector<b2JointEdge*>& tails = img.jointEdgeTails;
        tails.assign(static_cast<size_t>(img.bodyPool.capacity), nullptr);
        const JointStateSizes& sizes = state_detail::JointStateBytes();
        b2Joint* previous = nullptr;
        world.m_jointList = nullptr;
        const size_t count = img.joints.size();
        for (size_t i = 0; i < count; ++i) {
            // Joints lie anywhere in memory: request the parts written of the one a few records
            // ahead, and its bodies' list heads (the image is read in order: the hardware streams
            // it).
            if (i + kApplyPrefetch < count) {
                const JointImage& ahead = img.joints[i + kApplyPrefetch];
                state_detail::PrefetchJointFields(table[static_cast<size_t>(ahead.id)],
                                                  sizes.chunks[static_cast<size_t>(ahead.type)]);
                __builtin_prefetch(&world.m_bodies.Get(ahead.bodyA)->m_jointList);
                __builtin_prefetch(&world.m_bodies.Get(ahead.bodyB)->m_jointList);
            }
            const JointImage& ji = img.joints[i];
            b2Joint*& slot = table[static_cast<size_t>(ji.id)];
            if (slot == nullptr || slot->GetType() != ji.type) {
                if (slot != nullptr) Joints::Destroy(slot);
                slot = Joints::CreateEmpty(ji.type);
            }
            visited[static_cast<size_t>(ji.id)] = 1;
            b2Joint* j = slot;
            // Gear joints are read once every joint is in place (their references need them).
            if (ji.type != e_gearJoint) ReadJointState(img, ji, world);
            j->m_id = ji.id;
            j->m_bodyA = world.m_bodies.Get(ji.bodyA);
            j->m_bodyB = world.m_bodies.Get(ji.bodyB);
            j->m_collideConnected = ji.collideConnected;
            j->m_userData = ji.userData;
            j->m_index = 0;
            j->m_edgeA = b2JointEdge{j->m_bodyB, j, nullptr, nullptr};
            j->m_edgeB = b2JointEdge{j->m_bodyA, j, nullptr, nullptr};
            state_detail::AppendToWorldList(j, world.m_jointList, previous);
            // Each body's edges are in world-list order, B before A when both sides are on one
            // body (CreateJoint prepends A, then B; StateWalk.h): appended now, while the joint
            // is in cache (a second pass missed on every joint).
            state_detail::AppendEdge(&j->m_edgeB, j->m_bodyB->m_jointList, tails[static_cast<size_t>(ji.bodyB)]);
            state_detail::AppendEdge(&j->m_edgeA, j->m_bodyA->m_jointList, tails[static_cast<size_t>(ji.bodyA)]);
        }
        // The world's joints the image does not hold.
        for (size_t id = 0; id < table.size(); ++id) {
            if (visited[id] == 0 && table[id] != nullptr) {
                Joints::Destroy(table[id]);
                table[id] = nullptr;
            }
        }
        table.resize(static_cast<size_t>(maxId + 1));
        for (const JointImage& ji : img.joints) {
            if (ji.type == e_gearJoint) ReadJointState(img, ji, world);
        }
        world.m_jointIdHint = 0;
        world.m_jointCount = static_cast<int32>(count);
    }

    static void Apply(Image& img, b2World& publicWorld) {
        World& world = Of(publicWorld);
        ApplyBodies(img, world);
        ApplyFixtures(img, world);
        ApplyContacts(img, world);
        ApplyJoints(img, world);
        b2BroadPhase& bp = world.m_contactManager.m_broadPhase;
        bp.GetTreeForRestore().RestoreState(img.tree.nodes, img.tree.root, img.tree.freeList, img.tree.nodeCount,
                                            img.tree.insertionCount);
        bp.RestoreState(img.tree.proxyCount, img.tree.moveBuffer);
        state_detail::InstallSettings(img.settings, world);
    }
};

}  // namespace lockbox

namespace lockbox::state_detail {

void ApplySnapshot(Image& img, b2World& world) { core_detail::Engine::SnapshotApply::Apply(img, world); }

}  // namespace lockbox::state_detail
