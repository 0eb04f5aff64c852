// b2World::SaveFrame and RestoreFrame (lockbox/state/WorldFrame.h): a rollback frame holds what
// steps and inputs change, in native arrays, and shares the rest, the structure, through one
// portable image per structure epoch. Under an unchanged epoch every structural field of the
// world equals the frame's, so a restore writes the arrays back and relinks the contacts; when
// the epoch differs, the structure image goes in first through b2World::Restore.
//
// The split mirrors the full restore (SnapshotApply.cpp): what it writes from the body,
// contact, joint and broad-phase sections is either here or set-up that only a structural
// call changes, and every structural call marks the epoch (FrameBook.h).
// Checked builds prove it on every restore: the world hash after RestoreFrame must equal the
// hash taken at SaveFrame.

#include "lockbox/state/WorldFrame.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>

#include "ByteCursor.h"
#include "ByteStreams.h"
#include "FrameBook.h"
#include "FrameData.h"
#include "JointState.h"
#include "ListWalk.h"
#include "RestoreLinks.h"
#include "SnapshotImage.h"
#include "StateWalk.h"
#include "dynamics/WorldState.h"
#include "dynamics/joints/JointAccess.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox {

namespace state_detail {

using frame_detail::Structure;

/// Buffers of structure images no frame holds any more, kept for the next image: a fresh
/// buffer of a large world's size costs its page faults, several times the Save itself.
struct StructurePool {
    std::vector<std::unique_ptr<Structure>> spare;
};
constexpr size_t kSpareStructures = 2;

/// Per world: the structure image of the current epoch, and restore scratch.
struct FrameCache {
    std::shared_ptr<StructurePool> pool = std::make_shared<StructurePool>();
    std::shared_ptr<const Structure> structure;
    uint64 structureEpoch = 0;
    /// By fixture id, for the contacts: valid for `slotsEpoch` only.
    std::vector<FixtureSlot> slots;  ///< empty: to be built
    uint64 slotsEpoch = 0;
    std::vector<b2ContactEdge*> edgeTails;  ///< last contact edge of each body (by id)
};

void FrameCacheDeleter::operator()(FrameCache* cache) const noexcept { delete cache; }

uint64 NextWorldSerial() noexcept {
    static std::atomic<uint64> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

void FrameBook::LogStructureChange(StructureChange change) noexcept {
    // Only frames read the log: a world that never saved one starts it again each time.
    if (!m_cache) {
        MarkStructureChanged();
        return;
    }
    m_structureEpoch = ++m_epochSource;
    // Bounded: when full, the older half goes, and frames from before it restore their
    // structure image instead.
    constexpr size_t kLogCapacity = 4096;
    if (m_structureLog.size() == kLogCapacity) {
        constexpr size_t kDrop = kLogCapacity / 2;
        m_structureLogBase = m_structureLog[kDrop - 1].epoch;
        m_structureLog.erase(m_structureLog.begin(), m_structureLog.begin() + static_cast<std::ptrdiff_t>(kDrop));
    }
    change.epoch = m_structureEpoch;
    m_structureLog.push_back(change);
}

}  // namespace state_detail

using namespace state_detail;
using namespace frame_detail;
using core_detail::Engine;

b2WorldFrame::b2WorldFrame() noexcept = default;
b2WorldFrame::~b2WorldFrame() = default;
b2WorldFrame::b2WorldFrame(b2WorldFrame&& other) noexcept = default;
b2WorldFrame& b2WorldFrame::operator=(b2WorldFrame&& other) noexcept = default;

b2WorldFrame::b2WorldFrame(const b2WorldFrame& other)
    : m_data(other.m_data ? std::make_unique<Data>(*other.m_data) : nullptr) {}

b2WorldFrame& b2WorldFrame::operator=(const b2WorldFrame& other) {
    if (this == &other) return *this;
    if (!other.m_data) {
        m_data.reset();
    } else if (m_data) {
        *m_data = *other.m_data;  // keeps this frame's capacity
    } else {
        m_data = std::make_unique<Data>(*other.m_data);
    }
    return *this;
}

bool b2WorldFrame::IsEmpty() const noexcept { return !m_data || m_data->m_serial == 0; }

b2FrameStats b2WorldFrame::Stats() const noexcept {
    b2FrameStats s;
    if (!m_data) {
        s.frameBytes = static_cast<uint32>(sizeof(b2WorldFrame));
        return s;
    }
    const Data& f = *m_data;
    auto bytes = [](const auto& v) { return static_cast<uint32>(v.size() * sizeof(v[0])); };
    s.bodyBytes = bytes(f.m_bodies);
    s.forceBytes = bytes(f.m_forces);
    s.proxyBytes = bytes(f.m_proxies);
    s.contactBytes = bytes(f.m_contacts) + bytes(f.m_points) + bytes(f.m_contactLive) + bytes(f.m_contactFree);
    s.jointBytes = bytes(f.m_joints);
    s.broadPhaseBytes = bytes(f.m_nodes) + bytes(f.m_moveBuffer);
    s.frameBytes = static_cast<uint32>(sizeof(b2WorldFrame) + sizeof(Data)) + s.bodyBytes + s.forceBytes +
                   s.proxyBytes + s.contactBytes + s.jointBytes + s.broadPhaseBytes;
    if (f.m_structure) {
        const Structure& st = *f.m_structure;
        s.structureBytes = bytes(st.image) + bytes(st.bodyLive) + bytes(st.fixtureLive) + bytes(st.jointLive) +
                           bytes(st.bodyFree) + bytes(st.fixtureFree);
    }
    return s;
}

namespace {

void SaveSettings(const Engine::World& world, Settings& s) {
    s.gravity = world.m_gravity;
    s.allowSleep = world.m_allowSleep;
    s.warmStarting = world.m_warmStarting;
    s.continuous = world.m_continuousPhysics;
    s.subStepping = world.m_subStepping;
    s.autoClear = world.m_autoClearForces;
    s.stepComplete = world.m_stepComplete;
    s.bounds = world.m_bounds;
    s.flags = world.m_flags;
    s.invDt0 = world.m_inv_dt0;
    s.saturations = world.m_saturationCount;
}

/// Joints lie anywhere in memory and their list gives one address at a time. Frames walk them
/// by id instead (the table is the same under one structure epoch): the joint kJointAhead ids
/// on gets its first line requested, and the one half as far its state fields (their chunks
/// depend on its type, read from that first line).
constexpr size_t kJointAhead = 8;

void PrefetchJointsAhead(const std::vector<b2Joint*>& table, size_t id) {
    const JointStateSizes& sizes = JointStateBytes();
    if (id + kJointAhead < table.size() && table[id + kJointAhead] != nullptr) {
        __builtin_prefetch(table[id + kJointAhead]);
    }
    if (id + kJointAhead / 2 < table.size()) {
        const b2Joint* near = table[id + kJointAhead / 2];
        if (near != nullptr) PrefetchJointFields(near, sizes.chunks[static_cast<size_t>(near->GetType())]);
    }
}

}  // namespace

/// Rollback frames: their arrays, filled from the world and written back, the undoing of
/// creations, and the two calls b2World forwards.
struct core_detail::Engine::Frames {
    using Data = b2WorldFrame::Data;

    static void Save(const World& world, Data& f) {
        SaveSettings(world, f.m_settings);

        // Bodies, their pending forces and their proxies' boxes, in one walk of the body list.
        f.m_bodies.resize(static_cast<size_t>(world.m_bodyCount));
        f.m_forces.clear();
        f.m_proxies.clear();
        size_t i = 0;
        for (const b2Body* b = world.m_bodyList; b != nullptr; b = b->m_next, ++i) {
            if (b->m_next != nullptr) PrefetchObject(b->m_next);
            BodyMotion& m = f.m_bodies[i];
            m.xf = b->m_xf;
            m.c0 = b->m_sweep.c0;
            m.c = b->m_sweep.c;
            m.a0 = b->m_sweep.a0;
            m.a = b->m_sweep.a;
            m.alpha0 = b->m_sweep.alpha0;
            m.v = b->m_linearVelocity;
            m.w = b->m_angularVelocity;
            m.velocityRemainder[0] = b->m_velocityRemainder.x;
            m.velocityRemainder[1] = b->m_velocityRemainder.y;
            m.velocityRemainder[2] = b->m_velocityRemainder.w;
            m.positionRemainder[0] = b->m_positionRemainder.x;
            m.positionRemainder[1] = b->m_positionRemainder.y;
            m.positionRemainder[2] = b->m_positionRemainder.w;
            m.sleepSteps = b->m_sleepSteps;
            m.flags = b->m_flags;
            if (b->m_force.x != Fixed() || b->m_force.y != Fixed() || b->m_torque != Fixed()) {
                f.m_forces.push_back({static_cast<int32>(i), b->m_force, b->m_torque});
            }
            for (const b2Fixture* fx = b->m_fixtureList; fx != nullptr; fx = fx->m_next) {
                for (int32 k = 0; k < fx->m_proxyCount; ++k)
                    f.m_proxies.push_back(fx->m_proxies[static_cast<size_t>(k)].aabb);
            }
            if (b->m_next != nullptr && b->m_next->m_fixtureList != nullptr) PrefetchObject(b->m_next->m_fixtureList);
        }

        // Contacts: the pool's layout, then each contact in list order.
        const b2ContactManager& cm = world.m_contactManager;
        f.m_contactLive = cm.GetPool().GetLiveFlags();
        f.m_contactFree = cm.GetPool().GetFreeList();
        f.m_contacts.resize(static_cast<size_t>(cm.m_contactCount));
        f.m_points.clear();
        i = 0;
        for (const b2Contact* c = cm.m_contactList; c != nullptr; c = c->m_next, ++i) {
            if (c->m_next != nullptr) PrefetchObject(c->m_next);
            ContactRecord& r = f.m_contacts[i];
            r.id = c->m_id;
            r.fixtureA = c->m_fixtureIdA;
            r.indexA = c->m_indexA;
            r.fixtureB = c->m_fixtureIdB;
            r.indexB = c->m_indexB;
            r.flags = c->m_flags;
            r.toiCount = c->m_toiCount;
            r.toi = c->m_toi;
            r.friction = c->m_friction;
            r.restitution = c->m_restitution;
            const b2Manifold& m = c->m_manifold;
            r.manifoldType = static_cast<uint8>(m.type);
            r.pointCount = static_cast<uint8>(m.pointCount);
            r.localNormal = m.localNormal;
            r.localPoint = m.localPoint;
            for (int32 p = 0; p < m.pointCount; ++p) f.m_points.push_back(m.points[p]);
        }

        // Joints, by id: user data, then the fields the full snapshot writes (VisitState,
        // reaction).
        {
            FieldWriter w(f.m_joints, 0);
            const std::vector<b2Joint*>& table = world.m_joints;
            for (size_t id = 0; id < table.size(); ++id) {
                PrefetchJointsAhead(table, id);
                const b2Joint* j = table[id];
                if (j == nullptr) continue;
                auto c = w.Begin(8 + 2 * kJointRecordMaxBytes);
                c.U64(j->m_userData);
                JointFieldWriter<decltype(c)> visitor{c};
                StateWalk::VisitJointState(const_cast<b2Joint&>(*j), visitor);
                StateWalk::VisitJointReaction(const_cast<b2Joint&>(*j), visitor);
                w.End(c);
            }
            w.Finish();
        }

        // Broad-phase: tree, proxy count and move buffer.
        const b2BroadPhase& bp = cm.m_broadPhase;
        const b2DynamicTree& tree = bp.GetTree();
        f.m_nodes = tree.GetNodes();
        f.m_treeRoot = tree.GetRoot();
        f.m_treeFree = tree.GetFreeList();
        f.m_treeNodeCount = tree.GetNodeCount();
        f.m_treeInsertions = tree.GetInsertionCount();
        f.m_proxyCount = bp.GetProxyCount();
        f.m_moveBuffer = bp.GetMoveBuffer();
    }

    /// Writes the frame's arrays into a world whose structure is the frame's (same epoch).
    static void Apply(const Data& f, World& world, FrameCache& cache) {
        InstallSettings(f.m_settings, world);

        // Bodies, forces and proxy boxes; every contact list is rebuilt below.
        size_t i = 0, force = 0, proxy = 0;
        for (b2Body* b = world.m_bodyList; b != nullptr; b = b->m_next, ++i) {
            if (b->m_next != nullptr) PrefetchObject(b->m_next);
            const BodyMotion& m = f.m_bodies[i];
            b->m_xf = m.xf;
            b->m_sweep.c0 = m.c0;
            b->m_sweep.c = m.c;
            b->m_sweep.a0 = m.a0;
            b->m_sweep.a = m.a;
            b->m_sweep.alpha0 = m.alpha0;
            b->m_linearVelocity = m.v;
            b->m_angularVelocity = m.w;
            b->m_velocityRemainder = {m.velocityRemainder[0], m.velocityRemainder[1], m.velocityRemainder[2]};
            b->m_positionRemainder = {m.positionRemainder[0], m.positionRemainder[1], m.positionRemainder[2]};
            b->m_sleepSteps = m.sleepSteps;
            b->m_flags = static_cast<uint16>(m.flags);
            b->m_islandIndex = 0;
            b->m_contactList = nullptr;
            b->m_toiContacts = 0;
            if (force < f.m_forces.size() && f.m_forces[force].body == static_cast<int32>(i)) {
                b->m_force = f.m_forces[force].force;
                b->m_torque = f.m_forces[force].torque;
                ++force;
            } else {
                b->m_force.SetZero();
                b->m_torque = Fixed();
            }
            for (b2Fixture* fx = b->m_fixtureList; fx != nullptr; fx = fx->m_next) {
                for (int32 k = 0; k < fx->m_proxyCount; ++k)
                    fx->m_proxies[static_cast<size_t>(k)].aabb = f.m_proxies[proxy++];
            }
            if (b->m_next != nullptr && b->m_next->m_fixtureList != nullptr) PrefetchObject(b->m_next->m_fixtureList);
        }
        world.m_forcesApplied = !f.m_forces.empty();

        // The fixtures by id, once per structure epoch (their addresses hold while it lasts).
        if (cache.slots.empty() || cache.slotsEpoch != world.m_frames.m_structureEpoch) {
            cache.slots.assign(static_cast<size_t>(world.m_fixtures.GetCapacity()), FixtureSlot{});
            for (b2Body* b = world.m_bodyList; b != nullptr; b = b->m_next) {
                for (b2Fixture* fx = b->m_fixtureList; fx != nullptr; fx = fx->m_next) {
                    cache.slots[static_cast<size_t>(fx->m_id)] = {fx, b, b->m_id, fx->IsSensor()};
                }
            }
            cache.slotsEpoch = world.m_frames.m_structureEpoch;
        }

        // Contacts: the pool's layout (a slot live only in the frame gets a blank contact), then
        // every contact's fields, list links and edges in list order.
        b2ContactManager& cm = world.m_contactManager;
        const size_t count = f.m_contacts.size();
        cm.RestoreContactLayout(f.m_contactLive, f.m_contactFree,
                                [](void* slot, int32 id) { ::new (slot) b2Contact(b2RestoreTag{}, id); });
        cache.edgeTails.assign(static_cast<size_t>(world.m_bodies.GetCapacity()), nullptr);
        ContactListTail tail{nullptr, cache.edgeTails};
        cm.m_contactList = nullptr;
        size_t point = 0;
        for (size_t k = 0; k < count; ++k) {
            if (k + 6 < count) PrefetchBytes(cm.GetContact(f.m_contacts[k + 6].id), sizeof(b2Contact));
            const ContactRecord& r = f.m_contacts[k];
            b2Contact* c = cm.GetContact(r.id);
            c->m_flags = r.flags;
            c->m_toiCount = r.toiCount;
            c->m_toi = r.toi;
            c->m_friction = r.friction;
            c->m_restitution = r.restitution;
            b2Manifold& m = c->m_manifold;
            m.type = static_cast<b2Manifold::Type>(r.manifoldType);
            m.pointCount = r.pointCount;
            m.localNormal = r.localNormal;
            m.localPoint = r.localPoint;
            for (int32 p = 0; p < m.pointCount; ++p) m.points[p] = f.m_points[point++];
            LinkRestoredContact(c, r.fixtureA, r.indexA, r.fixtureB, r.indexB,
                                cache.slots[static_cast<size_t>(r.fixtureA)],
                                cache.slots[static_cast<size_t>(r.fixtureB)], cm.m_contactList, tail);
        }
        cm.m_contactCount = static_cast<int32>(count);

        // Joints: the same id table (same epoch); user data, VisitState and reaction fields.
        ReadCursor r(f.m_joints.data());
        const std::vector<b2Joint*>& table = world.m_joints;
        for (size_t id = 0; id < table.size(); ++id) {
            PrefetchJointsAhead(table, id);
            b2Joint* j = table[id];
            if (j == nullptr) continue;
            j->m_userData = r.U64();
            JointStateReader reader{r, world};
            StateWalk::VisitJointState(*j, reader);
            StateWalk::VisitJointReaction(*j, reader);
            r = reader.r;
        }

        b2BroadPhase& bp = cm.m_broadPhase;
        bp.GetTreeForRestore().RestoreState(f.m_nodes, f.m_treeRoot, f.m_treeFree, f.m_treeNodeCount,
                                            f.m_treeInsertions);
        bp.RestoreState(f.m_proxyCount, f.m_moveBuffer);
    }

    struct Undo;
    static void SaveFrame(const World& world, b2WorldFrame& frame);
    static b2RestoreResult RestoreFrame(World& world, const b2WorldFrame& frame);
};

namespace {

/// The world's structure in a buffer from the pool (or a new one), shared: when the last
/// frame holding it lets go, the buffer goes back to the pool if the world's cache still
/// exists.
std::shared_ptr<const Structure> SaveStructure(const Engine::World& world, FrameCache& cache) {
    std::unique_ptr<Structure> buffer;
    if (!cache.pool->spare.empty()) {
        buffer = std::move(cache.pool->spare.back());
        cache.pool->spare.pop_back();
    } else {
        buffer = std::make_unique<Structure>();
    }
    // Without the contacts: every frame carries them, and a restore across a structural change
    // would otherwise install them twice.
    SaveImage(*world.m_owner, buffer->image, /*withContacts=*/false);
    buffer->bodyLive = world.m_bodies.GetLiveFlags();
    buffer->bodyFree = world.m_bodies.GetFreeList();
    buffer->fixtureLive = world.m_fixtures.GetLiveFlags();
    buffer->fixtureFree = world.m_fixtures.GetFreeList();
    buffer->jointLive.resize(world.m_joints.size());
    for (size_t id = 0; id < world.m_joints.size(); ++id) buffer->jointLive[id] = world.m_joints[id] != nullptr ? 1 : 0;
    std::weak_ptr<StructurePool> pool = cache.pool;
    return std::shared_ptr<const Structure>(buffer.release(), [pool](const Structure* structure) {
        std::unique_ptr<Structure> owned(const_cast<Structure*>(structure));
        if (const std::shared_ptr<StructurePool> p = pool.lock(); p && p->spare.size() < kSpareStructures) {
            p->spare.push_back(std::move(owned));
        }
    });
}

/// True when slot `id` of a layout was free (or did not exist yet) in that layout's epoch.
bool IsNewSince(const std::vector<uint8>& live, int32 id) noexcept {
    return id >= 0 && (static_cast<size_t>(id) >= live.size() || live[static_cast<size_t>(id)] == 0);
}

/// True when everything `change` concerned is newer than `s`'s epoch.
bool ConcernsOnlyNew(const Structure& s, const StructureChange& change) noexcept {
    if (!IsNewSince(s.bodyLive, change.body)) return false;
    if (change.joint < 0) return true;
    return IsNewSince(s.bodyLive, change.otherBody) && IsNewSince(s.jointLive, change.joint);
}

/// True when every slot live in `live` is still live (isLive(id)).
template <class IsLive>
bool KeepsEverySlot(const std::vector<uint8>& live, IsLive isLive) noexcept {
    for (size_t id = 0; id < live.size(); ++id) {
        if (live[id] != 0 && !isLive(id)) return false;
    }
    return true;
}

constexpr size_t kCannotUndo = static_cast<size_t>(-1);

}  // namespace

/// Undoing creations: when every structural change since a frame's epoch was confined to bodies
/// and joints created since (the world's log says so), the frame's structure is the world's
/// without them, so destroying them (and putting the pools' free stacks back) makes it the
/// frame's. Everything else such a change touched (contacts, proxies in the tree, the move
/// buffer, the world's flags, older bodies' motion) the frame's arrays overwrite.
struct core_detail::Engine::Frames::Undo {
    /// How many bodies and joints at the heads of the world's lists are new (creation
    /// prepends, so the new ones come first).
    struct Heads {
        size_t bodies = 0, joints = 0;
    };

    /// Takes the first n nodes off a world list (drop(node) for each, before moving on).
    template <class T, class Drop>
    static void DropFromHead(T*& head, size_t n, Drop drop) {
        for (size_t k = 0; k < n; ++k) {
            T* next = head->m_next;
            drop(head);
            head = next;
        }
        if (head != nullptr) head->m_prev = nullptr;
    }

    /// How many of the log's entries precede the frame's epoch (the log keeps those), or
    /// kCannotUndo.
    static size_t Check(const World& world, const Data& frame, Heads& heads) {
        const std::vector<StructureChange>& log = world.m_frames.m_structureLog;
        size_t start = kCannotUndo;
        if (frame.m_epoch == world.m_frames.m_structureLogBase) {
            start = 0;
        } else {
            for (size_t k = log.size(); k-- > 0;) {
                if (log[k].epoch == frame.m_epoch) {
                    start = k + 1;
                    break;
                }
            }
        }
        if (start == kCannotUndo) return kCannotUndo;
        const Structure& s = *frame.m_structure;
        for (size_t k = start; k < log.size(); ++k) {
            if (!ConcernsOnlyNew(s, log[k])) return kCannotUndo;
        }
        // The log implies what follows; checking it keeps a wrong log from corrupting the world.
        // Every body, fixture and joint of the frame is still there, and creations prepend, so
        // the new ones are the lists' heads and the rest are the frame's lists.
        const bool kept =
            KeepsEverySlot(s.bodyLive, [&](size_t id) { return world.m_bodies.IsLive(static_cast<int32>(id)); }) &&
            KeepsEverySlot(s.fixtureLive, [&](size_t id) { return world.m_fixtures.IsLive(static_cast<int32>(id)); }) &&
            KeepsEverySlot(s.jointLive,
                           [&](size_t id) { return id < world.m_joints.size() && world.m_joints[id] != nullptr; });
        if (!kept) return kCannotUndo;
        const size_t frameJoints = static_cast<size_t>(std::count(s.jointLive.begin(), s.jointLive.end(), uint8{1}));
        heads = Heads{};
        for (const b2Joint* j = world.m_jointList; j != nullptr && IsNewSince(s.jointLive, j->m_id); j = j->m_next) {
            // A new joint holds only new bodies (else its bodies' joint lists would change).
            if (!IsNewSince(s.bodyLive, j->m_bodyA->m_id) || !IsNewSince(s.bodyLive, j->m_bodyB->m_id)) {
                return kCannotUndo;
            }
            ++heads.joints;
        }
        if (static_cast<size_t>(world.m_jointCount) - heads.joints != frameJoints) return kCannotUndo;
        for (const b2Body* b = world.m_bodyList; b != nullptr && IsNewSince(s.bodyLive, b->m_id); b = b->m_next) {
            ++heads.bodies;
        }
        if (static_cast<size_t>(world.m_bodyCount) - heads.bodies != frame.m_bodies.size()) return kCannotUndo;
        return start;
    }

    /// Destroys the new joints, then the new bodies with their fixtures, and gives the body
    /// and fixture pools the frame's layout (Check said yes).
    static void Apply(World& world, const Structure& s, const Heads& heads) {
        // Joints: only new bodies' joint lists hold them, and those bodies go next.
        DropFromHead(world.m_jointList, heads.joints, [&](b2Joint* joint) {
            world.ReleaseJointId(joint->m_id);
            Joints::Destroy(joint);
        });
        world.m_jointCount -= static_cast<int32>(heads.joints);
        if (heads.joints > 0) world.m_jointGraph.Invalidate();
        // Bodies: the pools below destroy them and their fixtures.
        DropFromHead(world.m_bodyList, heads.bodies, [](b2Body*) {});
        // Check found every slot of the frame live, so no slot is made here (unreachable).
        auto none = [](void*, int32) { std::abort(); };
        world.m_fixtures.RestoreLayout(s.fixtureLive, s.fixtureFree, none);
        world.m_bodies.RestoreLayout(s.bodyLive, s.bodyFree, none);
        world.m_bodyCount = world.m_bodies.GetCount();
    }
};

void core_detail::Engine::Frames::SaveFrame(const World& world, b2WorldFrame& frame) {
    FrameBook& book = const_cast<FrameBook&>(world.m_frames);
    if (!book.m_cache) book.m_cache.reset(new FrameCache());
    FrameCache& cache = *book.m_cache;
    if (!cache.structure || cache.structureEpoch != book.m_structureEpoch) {
        cache.structure = SaveStructure(world, cache);
        cache.structureEpoch = book.m_structureEpoch;
    }
    if (!frame.m_data) frame.m_data = std::make_unique<Data>();
    Data& f = *frame.m_data;
    f.m_serial = book.m_serial;
    f.m_epoch = book.m_structureEpoch;
    f.m_structure = cache.structure;
    Save(world, f);
#ifdef LOCKBOX_CHECKED
    f.m_checkHash = b2WorldHash(*world.m_owner);
#endif
}

b2RestoreResult core_detail::Engine::Frames::RestoreFrame(World& world, const b2WorldFrame& frame) {
    if (world.IsLocked()) {
        world.CheckLocked("b2World::RestoreFrame called inside a Step callback (the world is locked)");
        return {b2SnapshotError::e_locked, "the world is locked (inside Step)"};
    }
    if (frame.IsEmpty()) return {b2SnapshotError::e_foreignFrame, "the frame is empty (never saved into)"};
    const Data& f = *frame.m_data;
    FrameBook& book = world.m_frames;
    if (f.m_serial != book.m_serial) return {b2SnapshotError::e_foreignFrame, "the frame was saved by another world"};
    if (!book.m_cache) book.m_cache.reset(new FrameCache());
    FrameCache& cache = *book.m_cache;
    Undo::Heads heads;
    if (f.m_epoch == book.m_structureEpoch) {
        ++book.m_restores.sameStructure;
    } else if (const size_t kept = Undo::Check(world, f, heads); kept != kCannotUndo) {
        Undo::Apply(world, *f.m_structure, heads);
        // The fixtures the frame has kept their addresses: a fixture table of the epoch undone
        // still serves (the entries of the destroyed ones are never looked up).
        if (cache.slotsEpoch == book.m_structureEpoch && cache.slots.size() >= f.m_structure->fixtureLive.size()) {
            cache.slotsEpoch = f.m_epoch;
        }
        book.m_structureLog.resize(kept);
        ++book.m_restores.undoneCreations;
    } else {
        // The structure changed otherwise since the frame: its epoch's image first (it only
        // ever holds this world's own Save, so the checks pass; a failure is reported, the
        // world intact).
        b2RestoreResult result = world.m_owner->Restore(f.m_structure->image);
        if (!result.ok()) return result;
        book.m_structureLogBase = f.m_epoch;
        book.m_structureLog.clear();
        cache.slots.clear();  // fixtures may sit at other addresses than in that epoch
        ++book.m_restores.restoredStructure;
    }
    // The world's structure is now the frame's epoch's (unchanged on the first path).
    book.m_structureEpoch = f.m_epoch;
    cache.structure = f.m_structure;
    cache.structureEpoch = f.m_epoch;
    Apply(f, world, cache);
#ifdef LOCKBOX_CHECKED
    LOCKBOX_ASSERT(b2WorldHash(*world.m_owner) == f.m_checkHash,
                   "RestoreFrame did not give the saved state: a structural change did not mark the world's "
                   "structure changed (a shape edited other than through b2Fixture::EditShape?)");
#endif
    return {};
}

void b2World::SaveFrame(b2WorldFrame& frame) const { Engine::Frames::SaveFrame(Engine::Of(*this), frame); }

b2RestoreResult b2World::RestoreFrame(const b2WorldFrame& frame) {
    return Engine::Frames::RestoreFrame(Engine::Of(*this), frame);
}

}  // namespace lockbox
