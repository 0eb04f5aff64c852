#pragma once
// A world's internal state and the code behind b2World's calls. b2World (World.h) holds one
// of these and forwards to it; the rest of the engine reaches it through Engine::Of.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "Engine.h"
#include "dynamics/ContactManager.h"
#include "dynamics/Island.h"
#include "dynamics/JointGraph.h"
#include "dynamics/Pool.h"
#include "dynamics/TimeStep.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "state/FrameBook.h"

namespace lockbox {

namespace state_detail {
struct Image;
/// Frees a restore scratch image (defined where Image is complete).
struct ImageDeleter {
    void operator()(Image* image) const noexcept;
};
}  // namespace state_detail

class core_detail::Engine::World {
public:
    explicit World(b2World* owner, const b2Vec2& gravity);
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    b2Body* CreateBody(const b2BodyDef* def);
    void DestroyBody(b2Body* body);
    b2Joint* CreateJoint(const b2JointDef* def);
    void DestroyJoint(b2Joint* joint);
    void Step(Fixed timeStep, int32 velocityIterations, int32 positionIterations);
    void ClearForces();
    void DrawDebugData();
    void QueryAABB(b2QueryCallback* callback, const b2AABB& aabb) const;
    void RayCast(b2RayCastCallback* callback, const b2Vec2& point1, const b2Vec2& point2) const;
    void SetAllowSleeping(bool flag);
    b2Joint* GetJoint(int32 id) noexcept {
        return id >= 0 && static_cast<size_t>(id) < m_joints.size() ? m_joints[static_cast<size_t>(id)] : nullptr;
    }
    bool IsLocked() const noexcept { return (m_flags & e_locked) != 0; }

    // ---- what bodies, fixtures and joints call back into ----
    // e_skipPressedToi is set when SetPressedContactToi(false): clear by default, so the flags
    // word, hashed and saved, is unchanged for a world that keeps 2.2.1's behaviour.
    enum : uint32 { e_newFixture = 0x0001, e_locked = 0x0002, e_clearForces = 0x0004, e_skipPressedToi = 0x0008 };
    /// Reports a refused call on a locked world; returns true when the world is locked.
    bool CheckLocked(const char* what) const;
    b2Fixture* CreateFixture(b2Body* body, const b2FixtureDef* def);
    void DestroyFixture(b2Fixture* fixture);
    /// Frees a joint id in the id table (the joint is being destroyed).
    void ReleaseJointId(int32 id);
    /// Moves a body's proxies to cover its fixtures from transform xf1 to xf2.
    void SynchronizeFixtures(b2Body& body, const b2Transform& xf1, const b2Transform& xf2);
    /// The same over the body's step: from its sweep's start to its transform.
    void SynchronizeFixtures(b2Body& body);
    /// The body's transform at its sweep's start (c0, a0).
    static b2Transform SweepStart(const b2Body& body) noexcept;
    /// Gives a body's fixtures their proxies (the body becomes active), or takes them away.
    void CreateProxies(b2Body& body);
    void DestroyProxies(b2Body& body);

    // ---- structural changes, for rollback frames (state/FrameBook.h) ----
    /// Every change of the structure (what a frame shares through its structure image rather
    /// than copying: bodies', fixtures' and joints' set-up, shapes, pool layouts) calls one of
    /// these. A frame saved before the change is restored through its structure image, or,
    /// for a change confined to bodies and joints created since the frame, by destroying them.
    void MarkStructureChanged() noexcept {
        m_frames.MarkStructureChanged();
        m_jointGraph.Invalidate();
    }
    /// A change confined to one body: its creation or destruction, its fixtures and their
    /// settings and shapes, its mass, type, activity, damping, gravity scale or user data.
    void MarkBodyStructureChanged(int32 bodyId) noexcept;
    /// A joint created or destroyed (with its id and bodies set): confined to the joint and
    /// its two bodies.
    void MarkJointStructureChanged(const b2Joint& joint) noexcept;

    /// The public world this state belongs to (listeners and observers are given it).
    b2World* m_owner;
    uint32 m_flags = e_clearForces;
    b2ContactManager m_contactManager;
    b2Pool<b2Body> m_bodies;
    b2Pool<b2Fixture> m_fixtures;
    b2Body* m_bodyList = nullptr;
    b2Joint* m_jointList = nullptr;
    /// Joints by id (nullptr for free ids). Ids are the smallest free ones, so this table is
    /// derived from the joints' ids and is rebuilt on restore.
    std::vector<b2Joint*> m_joints;
    int32 m_jointIdHint = 0;  ///< every joint id below it is taken (a cache, not state)
    /// The joint lists as the island search reads them (derived, not state): invalidated by
    /// MarkJointStructureChanged, MarkStructureChanged (every restore) and a frame's undo.
    JointGraph m_jointGraph;
    int32 m_bodyCount = 0;
    int32 m_jointCount = 0;
    b2Vec2 m_gravity;
    bool m_allowSleep = true;
    b2DestructionListener* m_destructionListener = nullptr;
    b2BoundaryListener* m_boundaryListener = nullptr;
    b2Draw* m_debugDraw = nullptr;
    Fixed m_inv_dt0;  ///< inverse of the previous step, for dtRatio
    bool m_warmStarting = true;
    bool m_continuousPhysics = true;
    bool m_subStepping = false;
    bool m_autoClearForces = true;
    /// Whether a body may hold a force or torque: set by b2Body::ApplyForce and its kin and by
    /// a restore, cleared by ClearForces. Not state: while it is false every body's force is
    /// zero, so ClearForces has nothing to do, and a scene driven by gravity alone never walks
    /// its bodies for it.
    bool m_forcesApplied = true;
    bool m_stepComplete = true;
    b2AABB m_bounds;
    uint64 m_saturationCount = 0;  ///< saturations inside this world's Steps (state)
    /// Parsed-image scratch kept between restores, so a rollback restore reuses its buffers.
    std::unique_ptr<state_detail::Image, state_detail::ImageDeleter> m_restoreScratch;
    /// Rollback frames' book-keeping (not state): serial, structure epochs, the log of
    /// confined changes, the shared structure image and restore scratch.
    state_detail::FrameBook m_frames;
    b2Profile m_profile;
    bool m_headroomTelemetry = false;          ///< fill m_profile.headroom at the end of each Step
    bool m_profileTimers = true;               ///< time the stages into m_profile's *Ns fields
    b2StepObserver* m_stepObserver = nullptr;  ///< step fenceposts (not state)
    /// Workers (not state: the bits never depend on them). The game's task system wins over
    /// the built-in pool, which exists only for a worker count above 1.
    b2TaskSystem* m_userTasks = nullptr;
    std::unique_ptr<b2ThreadPool> m_pool;
    b2TaskSystem* Tasks() const noexcept { return m_userTasks != nullptr ? m_userTasks : m_pool.get(); }
    /// Whether the step's loops go to the built-in pool, which keeps work that cannot pay for
    /// its wake-ups on the stepping thread (a game's own task system gets every loop: what a
    /// loop costs on it is the game's to judge).
    bool OnOwnPool() const noexcept { return m_userTasks == nullptr; }
    /// Contacts from which the narrow phase runs on the workers. A game's task system is
    /// trusted from a few blocks on. On the built-in pool, without a contact listener the
    /// workers update the contacts in place and pay from a few thousand (rain's 8,000 and
    /// tumbler's 22,000 halve their stage on two cores; pyramid20's 590 do not gain). With a
    /// listener they can only evaluate ahead of the list walk, which reads every contact again:
    /// on two cores that took longer than one thread up to tumbler's size and broke even at
    /// many_pyramids' 58,000 (docs/benchmarks.md, "Workers"). The islands' rule is in
    /// WorldSolve.cpp, since it needs the last step's islands.
    int32 MinParallelContacts() const noexcept {
        if (!OnOwnPool()) return 64;
        return m_contactManager.m_contactListener == nullptr ? 2048 : 32768;
    }
    /// The fewest moved proxies (or broad-phase pairs) of a step whose tree queries (or
    /// screening) go to the workers: a game's task system gets any count of more than one
    /// block, the built-in pool (whose threads must be woken) only a count worth it.
    int32 MinParallelBroadPhase() const noexcept { return OnOwnPool() ? 1024 : 129; }
    /// The last step's islands were worth the built-in pool (WorldSolve.cpp). Not state: only
    /// the speed of a step depends on it.
    bool m_shareIslands = false;
    /// The island buffers as the last island solved one at a time left them (its contacts in
    /// solve order, with their colours); for tests.
    const b2Island& LastIsland() const noexcept { return m_island; }

    /// A step's islands solved at the same time (IslandTasks.cpp): found in the one-worker
    /// order (by the stepping thread, or by the workers: IslandSearch.cpp), then solved on the
    /// task system, then finished (PostSolve, static bodies' sleep, saturation counts) in island
    /// order. Buffers kept between steps.
    struct ParallelIslands;
    struct ParallelIslandsDeleter {
        void operator()(ParallelIslands* p) const noexcept;
    };

    /// The time-of-impact event search visits every contact of the world list, in list order,
    /// as 2.2.1 does, when this is set; otherwise only the contacts that can pass its filters
    /// (WorldToi.cpp), in the same order, with the same result. The full search is kept as
    /// the reference the tests compare the short one with.
    bool m_toiSearchEveryContact = false;

    // The time-of-impact event search's candidates (WorldToi.cpp): the contacts it could take
    // and has still to examine, in contact-list order up to `m_toiSorted`, unsorted additions
    // after it; and those examined, with a time of impact before the end of the step, queued
    // earliest first (the earlier in list order on a tie).
    std::vector<b2Contact*> m_toiCandidates;
    size_t m_toiSorted = 0;
    struct ToiQueued {
        Fixed alpha;      ///< the contact's cached time of impact when it was queued
        int64_t listKey;  ///< the contact's list key, here so that the heap's comparisons read no contact
        b2Contact* contact;
    };
    std::vector<ToiQueued> m_toiQueue;  ///< a heap
    /// What the event search makes of a contact: one it keeps (disabled, or with neither body
    /// active, for now), one a filter rejects for the rest of the step, or one whose time of
    /// impact is cached (computed now if it was not).
    enum class ToiVerdict { e_kept, e_dropped, e_cached };
    /// 2.2.1's examination of a contact in the event search: its filters, then its time of
    /// impact, which can advance a body's sweep to the other's start.
    ToiVerdict ExamineToiContact(b2Contact* c);
    /// Examines the candidates in list order and returns the contact of the next event (the
    /// earliest time of impact, the earlier in list order on a tie), or nullptr.
    b2Contact* NextToiEvent();
    /// Counts the edits that can turn a filter of the search from reject to accept while the
    /// events are solved (a listener's SetBullet or SetSensor); the search drops a candidate
    /// that a filter rejects only while this count stays put (not state).
    uint32 m_toiFilterEdits = 0;
    void NoteToiFilterEdit() noexcept { ++m_toiFilterEdits; }
    /// A fixture of `body` became or stopped being a sensor: its contacts' sensor marks
    /// (b2Contact::IsSensorPair) follow, and the time-of-impact filters are looked at again.
    void NoteSensorEdit(b2Body& body) noexcept;
    /// `body` changed type or bullet flag: its contacts' b2Contact::m_toiBodies follow, and the
    /// time-of-impact filters are looked at again.
    void NoteToiBodiesEdit(b2Body& body) noexcept;
    /// Every contact with a cached time of impact or a fast body, in list order; with
    /// `invalidate` (a new step) the cached times of impact are dropped first. Many contacts
    /// are walked by slot, on the workers when there are any, and the few kept are sorted.
    void CollectToiCandidates(bool invalidate);
    /// One contact of that walk: drops its cached time of impact when `invalidate`, and
    /// returns whether it is a candidate.
    static bool RefreshToiContact(b2Contact& c, bool invalidate) noexcept;
    /// CollectToiCandidates's walk of slots [begin, end) into that block's buffer (a
    /// b2TaskRange; `self` is the world).
    static void CollectToiSlots(int32 begin, int32 end, void* self);
    /// A candidate of the slot walk with its list key, read while the walk has the contact at
    /// hand, so that putting them in list order compares keys and reads no contact.
    struct ToiKeyed {
        int64_t listKey;
        b2Contact* contact;
    };
    std::vector<std::vector<ToiKeyed>> m_toiBlocks;  ///< CollectToiSlots's output, per block
    std::vector<ToiKeyed> m_toiKeyed;                ///< the blocks together, to sort (scratch)
    std::vector<ToiKeyed> m_toiKeyedScratch;         ///< the sort's second buffer (scratch)
    bool m_toiInvalidate = false;                    ///< CollectToiCandidates's argument, for the blocks
    void AddToiCandidate(b2Contact* c) { m_toiCandidates.push_back(c); }
    /// Candidates for the contacts FindNewContacts put before `oldHead`, the list's head before.
    void AddNewToiCandidates(const b2Contact* oldHead);
    /// Puts the additions in list order among the others, once each.
    void SortToiCandidates();

private:
    void Solve(const b2TimeStep& step);
    /// The sizes of a step's islands, for the built-in pool's choice in the next step.
    struct IslandTally {
        int32 islands = 0;
        int64_t work = 0;  ///< bodies + contacts + joints of every island
        int64_t largest = 0;
        void Add(int64_t size) noexcept {
            ++islands;
            work += size;
            largest = size > largest ? size : largest;
        }
    };
    /// The one-worker island search, in body-list order: solves each island as it is found, or
    /// records it when `parallel`; tallies the islands when `measure`.
    void SearchIslands(const b2TimeStep& step, b2TaskSystem* tasks, bool hasWorkers, bool parallel, bool measure,
                       IslandTally& tally);
    /// 2.2.1's walk of the constraint graph from `seed` that makes an island, into `sink`
    /// (IslandWalk.h).
    template <class Sink>
    static void WalkIsland(b2Body* seed, const JointGraph& joints, std::vector<b2Body*>& stack, Sink& sink);
    /// Clears the scan marks the walk left on an island's bodies (IslandWalk.h).
    static void ClearScanMarks(std::span<b2Body* const> island) noexcept;
    /// Keeps the island just found in m_island for SolveRecordedIslands.
    void RecordIsland();
    /// Keeps an island given by its lists (in its solve order) for SolveRecordedIslands.
    void RecordIsland(std::span<b2Body* const> bodies, std::span<b2Contact* const> contacts,
                      std::span<b2Joint* const> joints, std::span<b2Body* const> statics);
    /// The island search on the workers (IslandSearch.cpp): records the islands the one-worker
    /// search finds, in its order and each in its order, and tallies them. Buffers kept
    /// between steps.
    void FindIslandsOnWorkers(b2TaskSystem& tasks, IslandTally& tally);
    struct IslandSearch;
    struct IslandSearchDeleter {
        void operator()(IslandSearch* p) const noexcept;
    };
    std::unique_ptr<IslandSearch, IslandSearchDeleter> m_islandSearch;
    /// Solves the recorded islands on `tasks` and finishes them in island order.
    void SolveRecordedIslands(const b2TimeStep& step, b2TaskSystem& tasks);
    void SolveTOI(const b2TimeStep& step);
    /// Takes bodies whose centre left the bounds out of the simulation and reports them.
    void EnforceBounds();
    bool IsOutside(const b2Body* b) const noexcept;
    void DrawShape(b2Fixture* fixture, const b2Transform& xf, const b2Color& color);

    b2Island m_island;
    std::unique_ptr<ParallelIslands, ParallelIslandsDeleter> m_parallelIslands;
    /// The end of the discrete step for a body the islands moved, after its fixtures were
    /// synchronised: the fast flag and the angle's wrap.
    static void FinishMotion(b2Body& b) noexcept;
    /// With workers, blocks of body slots sweep the moved bodies' proxies and finish their
    /// motion (each writes only its bodies and their fixtures, and reads the tree); the few
    /// bodies whose proxies left their fat boxes or that left the bounds are then taken in
    /// body-list order, as the one-thread loop takes every body, for the broad phase's moves
    /// and the bounds. Same results as that loop.
    struct FinishedBody {
        b2Body* body;
        b2Vec2 displacement;  ///< of the transform over the step, for the tree's prediction
        bool moves;           ///< a proxy left its fat box
        bool outside;         ///< the centre left the world bounds
    };
    struct FinishBlock {
        std::vector<FinishedBody> kept;
        uint64 saturations = 0;  ///< counted while the block ran
    };
    void FinishBodiesOnWorkers(b2TaskSystem& tasks);
    static void FinishBodySlots(int32 begin, int32 end, void* self);  ///< a b2TaskRange; `self` is the world
    std::vector<FinishBlock> m_finishBlocks;
    std::vector<FinishedBody> m_finished;
    std::vector<b2Body*> m_stack;
    std::vector<b2Body*> m_islandStatics;  ///< the static bodies of the island just found, in island order
    std::vector<b2Body*> m_outOfBounds;
};

/// The block a b2World holds (World.h declares it without the engine's definition).
class b2World::State final : public core_detail::Engine::World {
public:
    using core_detail::Engine::World::World;
};

inline core_detail::Engine::World& core_detail::Engine::Of(b2World& world) noexcept { return *world.m_state; }
inline const core_detail::Engine::World& core_detail::Engine::Of(const b2World& world) noexcept {
    return *world.m_state;
}

}  // namespace lockbox
