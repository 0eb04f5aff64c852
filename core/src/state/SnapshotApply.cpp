// Installing a validated snapshot image into a world. Pools take the image's exact slot
// layout (objects in slots live on both sides stay where they are), every field is
// overwritten, then all lists and edges are relinked from the image's orders. No listener
// is called: a restore is not a simulation event.

#include <memory>
#include <new>
#include <vector>

#include "SnapshotImage.h"
#include "StateWalk.h"

namespace lockbox::state_detail {
namespace {

/// Appends a node at the tail of a doubly linked world list (bodies, contacts, joints).
template <class T>
void AppendToWorldList(T* node, T*& head, T*& tail) {
    node->m_prev = tail;
    node->m_next = nullptr;
    if (tail != nullptr) tail->m_next = node;
    else head = node;
    tail = node;
}

void ApplyBodies(const Image& img, b2World& world) {
    const b2BodyDef def;
    world.m_bodies.RestoreLayout(img.bodyPool.live, img.bodyPool.free,
                                 [&](void* slot, int32 id) { ::new (slot) b2Body(&def, &world, id); });
    b2Body* previous = nullptr;
    world.m_bodyList = nullptr;
    for (const BodyImage& bi : img.bodies) {
        b2Body* b = world.m_bodies.Get(bi.id);
        b->m_type = static_cast<b2BodyType>(bi.type);
        b->m_flags = bi.flags;
        b->m_islandIndex = 0;
        b->m_xf = bi.xf;
        b->m_sweep = bi.sweep;
        b->m_linearVelocity = bi.v;
        b->m_angularVelocity = bi.w;
        b->m_force = bi.force;
        b->m_torque = bi.torque;
        b->m_world = &world;
        b->m_mass = bi.mass;
        b->m_invMass = bi.invMass;
        b->m_I = bi.I;
        b->m_invI = bi.invI;
        b->m_linearDamping = bi.linearDamping;
        b->m_angularDamping = bi.angularDamping;
        b->m_gravityScale = bi.gravityScale;
        b->m_sleepSteps = bi.sleepSteps;
        b->m_minExtent = bi.minExtent;
        b->m_maxExtent = bi.maxExtent;
        b->m_userData = bi.userData;
        b->m_id = bi.id;
        b->m_fixtureCount = bi.fixtureCount;
        b->m_fixtureList = nullptr;
        b->m_contactList = nullptr;
        b->m_jointList = nullptr;
        // World body list in image order.
        AppendToWorldList(b, world.m_bodyList, previous);
    }
    world.m_bodyCount = static_cast<int32>(img.bodies.size());
}

/// A shape of the image's type holding its fields; reuses `current` when the type matches.
void ApplyShape(const Image& img, const ShapeImage& si, std::unique_ptr<b2Shape>& current) {
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
        case b2Shape::e_circle:
            static_cast<b2CircleShape&>(*current).m_p = si.p;
            break;
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

void ApplyFixtures(const Image& img, b2World& world) {
    world.m_fixtures.RestoreLayout(img.fixturePool.live, img.fixturePool.free,
                                   [](void* slot, int32) { ::new (slot) b2Fixture(); });
    // Fixtures come grouped by body in body-list order, each group in fixture-list order.
    size_t k = 0;
    for (const BodyImage& bi : img.bodies) {
        b2Body* body = world.m_bodies.Get(bi.id);
        b2Fixture* previous = nullptr;
        for (int32 i = 0; i < bi.fixtureCount; ++i, ++k) {
            const FixtureImage& fi = img.fixtures[k];
            b2Fixture* f = world.m_fixtures.Get(fi.id);
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
            if (previous != nullptr) previous->m_next = f;
            else body->m_fixtureList = f;
            previous = f;
        }
    }
}

/// Links an edge (contact or joint) at the head of a body's list.
template <class Edge>
void PrependEdge(Edge* e, Edge*& head) {
    e->prev = nullptr;
    e->next = head;
    if (head != nullptr) head->prev = e;
    head = e;
}

void ApplyContacts(const Image& img, b2World& world) {
    b2ContactManager& cm = world.m_contactManager;
    b2Pool<b2Fixture>& fixtures = world.m_fixtures;
    // New slots are built from their image record (the constructor needs the fixtures).
    std::vector<int32> recordOf(static_cast<size_t>(img.contactPool.capacity), -1);
    for (size_t i = 0; i < img.contacts.size(); ++i) recordOf[static_cast<size_t>(img.contacts[i].id)] = static_cast<int32>(i);
    cm.RestoreContactLayout(img.contactPool.live, img.contactPool.free, [&](void* slot, int32 id) {
        const ContactImage& ci = img.contacts[static_cast<size_t>(recordOf[static_cast<size_t>(id)])];
        ::new (slot) b2Contact(fixtures.Get(ci.fixtureA), ci.indexA, fixtures.Get(ci.fixtureB), ci.indexB, id);
    });
    b2Contact* previous = nullptr;
    cm.m_contactList = nullptr;
    for (const ContactImage& ci : img.contacts) {
        b2Contact* c = cm.GetContact(ci.id);
        c->m_fixtureA = fixtures.Get(ci.fixtureA);
        c->m_fixtureB = fixtures.Get(ci.fixtureB);
        c->m_indexA = ci.indexA;
        c->m_indexB = ci.indexB;
        c->m_flags = ci.flags;
        c->m_toiCount = ci.toiCount;
        c->m_toi = ci.toi;
        c->m_friction = ci.friction;
        c->m_restitution = ci.restitution;
        c->m_manifold = ci.manifold;
        b2Body* bodyA = c->m_fixtureA->m_body;
        b2Body* bodyB = c->m_fixtureB->m_body;
        c->m_nodeA = b2ContactEdge{bodyB, c, nullptr, nullptr};
        c->m_nodeB = b2ContactEdge{bodyA, c, nullptr, nullptr};
        AppendToWorldList(c, cm.m_contactList, previous);
    }
    cm.m_contactCount = static_cast<int32>(img.contacts.size());
    // Each body's edges are in world-list order (StateWalk.h): prepending in reverse list
    // order rebuilds them.
    for (auto it = img.contacts.rbegin(); it != img.contacts.rend(); ++it) {
        b2Contact* c = cm.GetContact(it->id);
        PrependEdge(&c->m_nodeA, c->m_fixtureA->m_body->m_contactList);
        PrependEdge(&c->m_nodeB, c->m_fixtureB->m_body->m_contactList);
    }
}

/// Copies every field of src into dst (same concrete type); dst keeps its address.
template <class T>
void AssignAs(b2Joint& dst, const b2Joint& src) {
    static_cast<T&>(dst) = static_cast<const T&>(src);
}
void AssignJoint(b2Joint& dst, const b2Joint& src) {
    switch (src.GetType()) {
        case e_revoluteJoint: AssignAs<b2RevoluteJoint>(dst, src); break;
        case e_prismaticJoint: AssignAs<b2PrismaticJoint>(dst, src); break;
        case e_distanceJoint: AssignAs<b2DistanceJoint>(dst, src); break;
        case e_pulleyJoint: AssignAs<b2PulleyJoint>(dst, src); break;
        case e_mouseJoint: AssignAs<b2MouseJoint>(dst, src); break;
        case e_gearJoint: AssignAs<b2GearJoint>(dst, src); break;
        case e_wheelJoint: AssignAs<b2WheelJoint>(dst, src); break;
        case e_weldJoint: AssignAs<b2WeldJoint>(dst, src); break;
        case e_frictionJoint: AssignAs<b2FrictionJoint>(dst, src); break;
        case e_ropeJoint: AssignAs<b2RopeJoint>(dst, src); break;
        case e_unknownJoint: break;
    }
}

void ApplyJoints(Image& img, b2World& world) {
    // The object each image joint ends up in: the world's joint of that id when the type
    // matches (kept, same address), else the image's freshly built one.
    int32 maxId = -1;
    for (const JointImage& ji : img.joints) maxId = ji.id > maxId ? ji.id : maxId;
    std::vector<b2Joint*> target(static_cast<size_t>(maxId + 1), nullptr);
    std::vector<uint8> keep(world.m_joints.size(), 0);
    for (JointImage& ji : img.joints) {
        b2Joint* existing = world.GetJoint(ji.id);
        const bool reuse = existing != nullptr && existing->GetType() == ji.type;
        if (reuse) keep[static_cast<size_t>(ji.id)] = 1;
        target[static_cast<size_t>(ji.id)] = reuse ? existing : ji.state.get();
    }
    // Joints that do not survive are freed without listener calls.
    for (size_t id = 0; id < world.m_joints.size(); ++id) {
        if (world.m_joints[id] != nullptr && keep[id] == 0) b2Joint::Destroy(world.m_joints[id]);
    }
    // References (gear joints) point at final objects.
    for (RefImage& ref : img.refs) {
        if (ref.isJoint) *static_cast<b2Joint**>(ref.slot) = target[static_cast<size_t>(ref.id)];
        else *static_cast<b2Body**>(ref.slot) = world.m_bodies.Get(ref.id);
    }
    world.m_joints.assign(static_cast<size_t>(maxId + 1), nullptr);
    world.m_jointIdHint = 0;
    b2Joint* previous = nullptr;
    world.m_jointList = nullptr;
    for (JointImage& ji : img.joints) {
        b2Joint* j = target[static_cast<size_t>(ji.id)];
        if (j == ji.state.get()) (void)ji.state.release();  // the world owns it now
        else AssignJoint(*j, *ji.state);
        j->m_id = ji.id;
        j->m_bodyA = world.m_bodies.Get(ji.bodyA);
        j->m_bodyB = world.m_bodies.Get(ji.bodyB);
        j->m_collideConnected = ji.collideConnected;
        j->m_userData = ji.userData;
        j->m_index = 0;
        j->m_islandFlag = false;
        j->m_edgeA = b2JointEdge{j->m_bodyB, j, nullptr, nullptr};
        j->m_edgeB = b2JointEdge{j->m_bodyA, j, nullptr, nullptr};
        world.m_joints[static_cast<size_t>(ji.id)] = j;
        AppendToWorldList(j, world.m_jointList, previous);
    }
    world.m_jointCount = static_cast<int32>(img.joints.size());
    for (auto it = img.joints.rbegin(); it != img.joints.rend(); ++it) {
        b2Joint* j = world.m_joints[static_cast<size_t>(it->id)];
        PrependEdge(&j->m_edgeA, j->m_bodyA->m_jointList);
        PrependEdge(&j->m_edgeB, j->m_bodyB->m_jointList);
    }
}

void ApplySettings(const SettingsImage& s, b2World& world) {
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

}  // namespace

void ApplySnapshot(Image& img, b2World& world) {
    ApplyBodies(img, world);
    ApplyFixtures(img, world);
    ApplyContacts(img, world);
    ApplyJoints(img, world);
    b2BroadPhase& bp = world.m_contactManager.m_broadPhase;
    bp.GetTreeForRestore().RestoreState(img.tree.nodes, img.tree.root, img.tree.freeList, img.tree.nodeCount,
                                        img.tree.insertionCount);
    bp.RestoreState(img.tree.proxyCount, img.tree.moveBuffer);
    ApplySettings(img.settings, world);
}

}  // namespace lockbox::state_detail
