#pragma once
/// b2World (Box2D 2.2.1 b2World.h): owns bodies, fixtures, contacts (and later joints), steps
/// the simulation, and answers queries.
///
/// Storage: bodies, fixtures and contacts live in b2Pool slots with small integer ids; the
/// pointer API is a facade over those slots (addresses never move). Lists are in creation
/// order, newest first, as in 2.2.1.
///
/// Locking: inside Step (and so inside any callback it makes) the world is locked. Create/
/// Destroy calls made then are programmer errors: in debug and checked builds they go to the
/// assert handler (b2SetAssertHandler); if the handler returns, or in release builds, the call
/// does nothing and returns nullptr.

#include <memory>
#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/ContactManager.h"
#include "lockbox/dynamics/Draw.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/Island.h"
#include "lockbox/dynamics/Pool.h"
#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/dynamics/TimeStep.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/state/Snapshot.h"
#include "lockbox/state/WorldFrame.h"

namespace lockbox {

namespace state_detail {
struct Image;
/// Frees a restore scratch image (defined where Image is complete).
struct ImageDeleter {
    void operator()(Image* image) const noexcept;
};
struct FrameCache;
/// Frees a world's frame cache (defined where FrameCache is complete).
struct FrameCacheDeleter {
    void operator()(FrameCache* cache) const noexcept;
};
/// A serial no other world of this process has (frames check it): not state.
uint64 NextWorldSerial() noexcept;
}  // namespace state_detail

/// Called for programmer errors such as modifying a locked world. expr names the check, msg
/// explains it. The default prints to stderr and aborts. If the handler returns, the call is
/// refused (nothing changes; creators return nullptr).
using b2AssertHandler = void (*)(const char* expr, const char* msg, const char* file, int line);

/// Replaces the assert handler; returns the previous one. nullptr restores the default.
LOCKBOX_API b2AssertHandler b2SetAssertHandler(b2AssertHandler handler) noexcept;

/// True in builds where b2World's programmer-error checks call the assert handler (debug or
/// LOCKBOX_CHECKED); release builds refuse the call silently.
constexpr bool b2_assertsEnabled =
#if defined(LOCKBOX_CHECKED) || !defined(NDEBUG)
    true;
#else
    false;
#endif

/// Default world bounds: +-16000 m on both axes. Any two in-world positions differ by at
/// most 32000 m, which still fits Q16.16 (ARCHITECTURE §5).
inline constexpr Fixed b2_defaultWorldExtent = 16000;

/// The physics world.
class LOCKBOX_API b2World {
public:
    /// A world with the given gravity (m/s^2). Sleeping is allowed by default.
    explicit b2World(const b2Vec2& gravity);
    ~b2World();
    b2World(const b2World&) = delete;
    b2World& operator=(const b2World&) = delete;

    void SetDestructionListener(b2DestructionListener* listener) noexcept { m_destructionListener = listener; }
    /// nullptr restores the default filter (the manual's category/mask/group rule).
    void SetContactFilter(b2ContactFilter* filter) noexcept { m_contactManager.m_contactFilter = filter; }
    /// nullptr removes the listener (no events, no callback overhead).
    void SetContactListener(b2ContactListener* listener) noexcept { m_contactManager.m_contactListener = listener; }
    /// Listener for bodies leaving the world bounds.
    void SetBoundaryListener(b2BoundaryListener* listener) noexcept { m_boundaryListener = listener; }
    /// Debug draw target for DrawDebugData.
    void SetDebugDraw(b2Draw* debugDraw) noexcept { m_debugDraw = debugDraw; }

    /// Creates a body (refused while locked: returns nullptr).
    b2Body* CreateBody(const b2BodyDef* def);
    /// Destroys a body with its fixtures, contacts and joints (refused while locked). The
    /// destruction listener hears about the fixtures and joints.
    void DestroyBody(b2Body* body);
    /// Creates a joint from a concrete definition (b2RevoluteJointDef, ...); refused while
    /// locked or for an invalid definition (returns nullptr). Does not wake the bodies.
    b2Joint* CreateJoint(const b2JointDef* def);
    /// Destroys a joint and wakes its bodies (refused while locked). Gear joints that couple
    /// it are destroyed first, and the destruction listener hears SayGoodbye for each of them.
    void DestroyJoint(b2Joint* joint);

    /// Advances the world by timeStep seconds (Q16.16; 1/60 s is raw 1092) with the given
    /// iteration counts (the manual suggests 8 and 3).
    void Step(Fixed timeStep, int32 velocityIterations, int32 positionIterations);
    /// Zeroes all forces and torques (automatic after each Step unless disabled).
    void ClearForces();
    /// Draws the world through the registered b2Draw according to its flags.
    void DrawDebugData();

    /// Reports every fixture whose fat AABB overlaps aabb.
    void QueryAABB(b2QueryCallback* callback, const b2AABB& aabb) const;
    /// Casts a ray from point1 to point2 (m) with the manual's fraction protocol.
    void RayCast(b2RayCastCallback* callback, const b2Vec2& point1, const b2Vec2& point2) const;

    /// Bodies, newest first.
    b2Body* GetBodyList() noexcept { return m_bodyList; }
    const b2Body* GetBodyList() const noexcept { return m_bodyList; }
    /// Joints, newest first (always empty until joints exist).
    b2Joint* GetJointList() noexcept { return m_jointList; }
    const b2Joint* GetJointList() const noexcept { return m_jointList; }
    /// Contacts, newest first; use IsTouching to find touching ones.
    b2Contact* GetContactList() noexcept { return m_contactManager.m_contactList; }
    const b2Contact* GetContactList() const noexcept { return m_contactManager.m_contactList; }

    /// Lookup by id (nullptr when the id is free).
    b2Body* GetBody(int32 id) noexcept { return m_bodies.Get(id); }
    b2Fixture* GetFixture(int32 id) noexcept { return m_fixtures.Get(id); }
    b2Contact* GetContact(int32 id) noexcept { return m_contactManager.GetContact(id); }

    b2Joint* GetJoint(int32 id) noexcept {
        return id >= 0 && static_cast<size_t>(id) < m_joints.size() ? m_joints[static_cast<size_t>(id)] : nullptr;
    }

    // ---- state: hash, snapshot, restore (lockbox; docs/determinism.md) ----
    /// XXH3-64 of everything that influences future steps (b2WorldHash). Call outside Step.
    uint64 Hash() const;
    /// Writes the world's state as a portable snapshot image into out (replacing its
    /// contents; out's capacity is reused, so a ring of buffers saves without allocating).
    void Save(std::vector<uint8>& out) const;
    /// The world's state as a new snapshot image.
    std::vector<uint8> Save() const;
    /// Byte counts per section of the image Save would write now.
    b2SnapshotStats SaveStats() const;
    /// Replaces the world's state with a snapshot image (made by Save, possibly in another
    /// process or on another machine). In place: bodies, fixtures, contacts and joints whose
    /// ids exist in both keep their address; the others are destroyed or created without
    /// listener calls. The whole image is validated first: on any error nothing changes.
    b2RestoreResult Restore(std::span<const uint8> image);
    /// Copies what steps and inputs change into a rollback frame of this world (lockbox/state/
    /// WorldFrame.h); the structure goes in by reference to one portable image per structure
    /// epoch (made by the first SaveFrame after a structural change). Call outside Step. It is
    /// const but keeps that image in the world: do not call it from two threads at once.
    void SaveFrame(b2WorldFrame& frame) const;
    /// Puts the world back to a frame this world saved: in place, as Restore, and without the
    /// image checks (the frame never left the process). When the structure changed since the
    /// frame (a body, fixture or joint created or destroyed, a fixture or mass setting
    /// changed), one of two things happens first. If every change since the frame concerned
    /// only bodies and joints created since (a spawn, and the set-up of what it spawned), those
    /// joints, bodies and fixtures are destroyed. Otherwise the frame's structure image is restored,
    /// through Restore. Refuses an empty frame or another world's (e_foreignFrame) and a call
    /// inside Step (e_locked).
    b2RestoreResult RestoreFrame(const b2WorldFrame& frame);
    /// How this world's RestoreFrame calls went so far (lockbox/state/WorldFrame.h).
    b2FrameRestoreCounts GetFrameRestoreCounts() const noexcept;
    /// Tells the world that its structure changed. Every API call that changes the structure
    /// calls it; call it yourself after changing a shape through a b2Shape pointer taken
    /// before the last SaveFrame (b2Fixture::GetShape() marks the change when called, so a
    /// shape edited right after GetShape() needs nothing more). A frame saved before it is
    /// restored through its structure image.
    void MarkStructureChanged() noexcept {
        m_structureEpoch = ++m_epochSource;
        m_structureLogBase = m_structureEpoch;
        m_structureLog.clear();
    }
    /// A structural change confined to one body: its creation or destruction, its fixtures
    /// and their settings, its mass, type, activity, damping, gravity scale or user data.
    /// Called by those API calls; a frame saved before the body existed undoes such changes
    /// by destroying the body (RestoreFrame).
    void MarkBodyStructureChanged(int32 bodyId) noexcept;
    /// A joint created or destroyed (with its id and bodies set): confined to the joint and
    /// its two bodies, undone the same way when all three are newer than the frame.
    void MarkJointStructureChanged(const b2Joint& joint) noexcept;
    /// The structure epoch: changes with every structural change, never repeats a value this
    /// world gave before (frames compare it).
    uint64 GetStructureEpoch() const noexcept { return m_structureEpoch; }

    /// Fixed-point saturations counted during this world's Steps (0 in checked builds, which
    /// trap instead). Part of the state hash, so peers see a numeric limit being hit.
    uint64 GetSaturationCount() const noexcept { return m_saturationCount; }

    /// Sleeping switch; turning it off wakes every body.
    void SetAllowSleeping(bool flag);
    bool GetAllowSleeping() const noexcept { return m_allowSleep; }
    void SetWarmStarting(bool flag) noexcept { m_warmStarting = flag; }
    bool GetWarmStarting() const noexcept { return m_warmStarting; }
    void SetContinuousPhysics(bool flag) noexcept { m_continuousPhysics = flag; }
    bool GetContinuousPhysics() const noexcept { return m_continuousPhysics; }
    void SetSubStepping(bool flag) noexcept { m_subStepping = flag; }
    bool GetSubStepping() const noexcept { return m_subStepping; }
    void SetAutoClearForces(bool flag) noexcept { m_autoClearForces = flag; }
    bool GetAutoClearForces() const noexcept { return m_autoClearForces; }
    /// Gravity, m/s^2.
    void SetGravity(const b2Vec2& gravity) noexcept { m_gravity = gravity; }
    b2Vec2 GetGravity() const noexcept { return m_gravity; }

    /// Bounds for body centres (m); a body whose centre leaves them is taken out of the
    /// simulation and reported to the b2BoundaryListener. Default +-16000 m.
    void SetWorldBounds(const b2AABB& bounds) noexcept { m_bounds = bounds; }
    const b2AABB& GetWorldBounds() const noexcept { return m_bounds; }

    int32 GetProxyCount() const noexcept { return m_contactManager.m_broadPhase.GetProxyCount(); }
    int32 GetBodyCount() const noexcept { return m_bodyCount; }
    int32 GetJointCount() const noexcept { return m_jointCount; }
    int32 GetContactCount() const noexcept { return m_contactManager.m_contactCount; }
    /// True inside Step.
    bool IsLocked() const noexcept { return (m_flags & e_locked) != 0; }
    /// Work counters and timings of the last Step.
    const b2Profile& GetProfile() const noexcept { return m_profile; }
    /// Headroom telemetry: when on, each Step ends by filling GetProfile().headroom (a walk of
    /// every body, contact, joint and tree node). Off by default, so a Step costs nothing extra.
    void SetHeadroomTelemetry(bool flag) noexcept { m_headroomTelemetry = flag; }
    bool GetHeadroomTelemetry() const noexcept { return m_headroomTelemetry; }
    /// The contact manager (broad phase, contacts).
    const b2ContactManager& GetContactManager() const noexcept { return m_contactManager; }
    /// Step fenceposts (StepObserver.h): the observer hears every stage of every Step; nullptr
    /// (the default) turns them off. Not state: snapshots and the hash ignore it.
    void SetStepObserver(b2StepObserver* observer) noexcept { m_stepObserver = observer; }
    b2StepObserver* GetStepObserver() const noexcept { return m_stepObserver; }

    // ---- internal (bodies and fixtures call back into the world) ----
    enum : uint32 { e_newFixture = 0x0001, e_locked = 0x0002, e_clearForces = 0x0004 };
    /// Reports a refused call on a locked world; returns true when the world is locked.
    bool CheckLocked(const char* what) const;
    b2Fixture* CreateFixtureSlot(b2Body* body, const b2FixtureDef* def);
    void DestroyFixtureSlot(b2Fixture* fixture);
    /// Frees a joint id in the id table (the joint is being destroyed).
    void ReleaseJointId(int32 id);

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
    bool m_stepComplete = true;
    b2AABB m_bounds;
    uint64 m_saturationCount = 0;  ///< saturations inside this world's Steps (state)
    /// Parsed-image scratch kept between restores, so a rollback restore reuses its buffers.
    std::unique_ptr<state_detail::Image, state_detail::ImageDeleter> m_restoreScratch;
    /// Rollback frames (not state): this world's serial, its structure epoch and the epoch
    /// source (never restored, so an epoch value is never reused), and the frames' shared
    /// structure image and restore scratch.
    uint64 m_serial = state_detail::NextWorldSerial();
    uint64 m_structureEpoch = 0;
    uint64 m_epochSource = 0;
    /// The structural changes since the epoch m_structureLogBase, oldest first, each confined
    /// to one body or one joint: the last one's epoch is m_structureEpoch (the base, when
    /// empty). Any other change starts the log again.
    std::vector<b2StructureChange> m_structureLog;
    uint64 m_structureLogBase = 0;
    b2FrameRestoreCounts m_frameRestores;
    mutable std::unique_ptr<state_detail::FrameCache, state_detail::FrameCacheDeleter> m_frameCache;
    b2Profile m_profile;
    bool m_headroomTelemetry = false;          ///< fill m_profile.headroom at the end of each Step
    b2StepObserver* m_stepObserver = nullptr;  ///< step fenceposts (not state)

private:
    /// Moves the epoch and logs `change` (its epoch filled in) when the world keeps frames.
    void LogStructureChange(b2StructureChange change) noexcept;
    void Solve(const b2TimeStep& step);
    void SolveTOI(const b2TimeStep& step);
    /// Takes bodies whose centre left the bounds out of the simulation and reports them.
    void EnforceBounds();
    bool IsOutside(const b2Body* b) const noexcept;
    void DrawShape(b2Fixture* fixture, const b2Transform& xf, const b2Color& color);

    b2Island m_island;
    std::vector<b2Body*> m_stack;
    std::vector<b2Body*> m_outOfBounds;
};

}  // namespace lockbox
