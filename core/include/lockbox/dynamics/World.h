#pragma once
/// @file
/// b2World (Box2D 2.2.1 b2World.h): owns bodies, fixtures, contacts and joints, steps the
/// simulation, and answers queries. lockbox adds the world's state (hash, snapshot, restore,
/// rollback frames), ids, world bounds, the profile and the step observer.
///
/// Storage: bodies, fixtures and contacts live in pool slots with small integer ids; the
/// pointer API is a facade over those slots (addresses never move). Lists are in creation
/// order, newest first, as in 2.2.1.
///
/// Locking: inside Step (and so inside any callback it makes) the world is locked. Create/
/// Destroy calls made then are programmer errors (lockbox/fixed/Assert.h): in debug and checked
/// builds they go to the assert handler (b2SetAssertHandler); if the handler returns, and always
/// in release builds, the call does nothing and returns nullptr.

#include <memory>
#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Draw.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/Profile.h"
#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/Assert.h"
#include "lockbox/state/Snapshot.h"
#include "lockbox/state/WorldFrame.h"

namespace lockbox {

namespace core_detail {
struct Engine;
}  // namespace core_detail

class b2TaskSystem;

/// Default world bounds: +-16000 m on both axes. Any two in-world positions differ by at
/// most 32000 m, which still fits Q16.16 (docs/numerics.md).
inline constexpr Fixed b2_defaultWorldExtent = 16000;

/// The physics world: creates and owns bodies and joints (and through them fixtures and
/// contacts), advances them with Step, answers ray casts and AABB queries, and saves, hashes and
/// restores its whole state (see the file comment).
class LOCKBOX_API b2World {
public:
    /// A world with the given gravity (m/s^2). Sleeping is allowed by default.
    explicit b2World(const b2Vec2& gravity);
    ~b2World();
    b2World(const b2World&) = delete;
    b2World& operator=(const b2World&) = delete;

    /// Listener told about fixtures and joints destroyed implicitly (with their body, or a
    /// gear with its joint); nullptr removes it.
    void SetDestructionListener(b2DestructionListener* listener) noexcept;
    /// nullptr restores the default filter (the manual's category/mask/group rule).
    void SetContactFilter(b2ContactFilter* filter) noexcept;
    /// nullptr removes the listener (no events, no callback overhead).
    void SetContactListener(b2ContactListener* listener) noexcept;
    /// Listener for bodies leaving the world bounds.
    void SetBoundaryListener(b2BoundaryListener* listener) noexcept;
    /// Debug draw target for DrawDebugData.
    void SetDebugDraw(b2Draw* debugDraw) noexcept;

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
    b2Body* GetBodyList() noexcept;
    /// Bodies, newest first (read-only view).
    const b2Body* GetBodyList() const noexcept;
    /// Joints, newest first.
    b2Joint* GetJointList() noexcept;
    /// Joints, newest first (read-only view).
    const b2Joint* GetJointList() const noexcept;
    /// Contacts, newest first; use IsTouching to find touching ones.
    b2Contact* GetContactList() noexcept;
    /// Contacts, newest first (read-only view); use IsTouching to find touching ones.
    const b2Contact* GetContactList() const noexcept;

    /// The body with a given id (b2Body::GetId); nullptr when the id is free.
    b2Body* GetBody(int32 id) noexcept;
    /// The fixture with a given id; nullptr when the id is free.
    b2Fixture* GetFixture(int32 id) noexcept;
    /// The contact with a given id; nullptr when the id is free.
    b2Contact* GetContact(int32 id) noexcept;
    /// The joint with a given id; nullptr when the id is free.
    b2Joint* GetJoint(int32 id) noexcept;

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
    /// WorldFrame.h); the structure goes in by reference to one portable image shared by the
    /// frames saved while it lasts. Call outside Step. It is const but keeps that image in the
    /// world: do not call it from two threads at once.
    void SaveFrame(b2WorldFrame& frame) const;
    /// Puts the world back to a frame this world saved: in place, as Restore, and without the
    /// image checks (the frame never left the process). When the structure changed since the
    /// frame (a body, fixture or joint created or destroyed, a fixture, shape or mass setting
    /// changed), one of two things happens first. If every change since the frame concerned
    /// only bodies and joints created since (a spawn, and the set-up of what it spawned), those
    /// joints, bodies and fixtures are destroyed. Otherwise the frame's structure image is
    /// restored, through Restore. Refuses an empty frame or another world's (e_foreignFrame)
    /// and a call inside Step (e_locked).
    b2RestoreResult RestoreFrame(const b2WorldFrame& frame);

    /// Fixed-point saturations counted during this world's Steps (0 in checked builds, which
    /// trap instead). Part of the state hash, so peers see a numeric limit being hit.
    uint64 GetSaturationCount() const noexcept;

    // ---- workers (lockbox; lockbox/dynamics/Tasks.h) ----
    /// Runs the step's parallel work on `count` threads of a built-in pool, the calling thread
    /// included (clamped to [1, 64]). 1, the default, creates no thread. Threads are created
    /// here, only when the count changes, and joined when it drops to 1 or the world dies.
    /// The results are the same bits for every count. Not state: snapshots and the hash ignore
    /// it. Refused inside Step. The pool is handed only work that pays for waking its threads:
    /// a step's islands when the step before had at least 1,024 bodies, contacts and joints in
    /// islands and none of them held more than half, and the narrow phase from 32,768 contacts.
    /// Smaller steps run on the calling thread alone, as with one worker.
    void SetWorkerCount(int32 count);
    /// Workers of the task system in use: the game's (SetTaskSystem) or the built-in pool's.
    int32 GetWorkerCount() const noexcept;
    /// Runs the step's parallel work on a game's job system instead of the built-in pool
    /// (not owned: it must outlive its use by this world); nullptr goes back to the built-in
    /// pool. The results are the same bits with any task system. Not state. Refused inside Step.
    /// A game's task system is handed every loop of the step that has two islands, or 64
    /// contacts, or more: what a loop costs on it is the game's to judge.
    void SetTaskSystem(b2TaskSystem* tasks);
    /// The game's task system, or nullptr when the built-in pool (or no worker) is in use.
    b2TaskSystem* GetTaskSystem() const noexcept;

    /// Sleeping switch; turning it off wakes every body.
    void SetAllowSleeping(bool flag);
    /// Whether bodies may fall asleep (on by default).
    bool GetAllowSleeping() const noexcept;
    /// Warm starting of the contact and joint impulses (on by default).
    void SetWarmStarting(bool flag) noexcept;
    /// Whether warm starting is on.
    bool GetWarmStarting() const noexcept;
    /// Continuous collision (time of impact; on by default).
    void SetContinuousPhysics(bool flag) noexcept;
    /// Whether continuous collision is on.
    bool GetContinuousPhysics() const noexcept;
    /// Sub-stepping of time-of-impact events (off by default).
    void SetSubStepping(bool flag) noexcept;
    /// Whether time-of-impact sub-stepping is on.
    bool GetSubStepping() const noexcept;
    /// Time of impact for slow bodies pressed into a static or kinematic body (on by default,
    /// as 2.2.1). A body squeezed closer to such a body than the time-of-impact query's target
    /// (the bottom of a loaded pile) then gets 2.2.1's immediate event and sub-step every step.
    /// Off, only bodies that moved far enough to tunnel, and bullets, are examined: piles step
    /// much faster (docs/dynamics.md), and the results are no longer 2.2.1's. Part of the
    /// world's state (hash and snapshot).
    void SetPressedContactToi(bool flag) noexcept;
    /// Whether slow bodies pressed into a static or kinematic body get time-of-impact events.
    bool GetPressedContactToi() const noexcept;
    /// Whether each Step ends by clearing forces (on by default).
    void SetAutoClearForces(bool flag) noexcept;
    /// Whether each Step ends by clearing the forces applied to bodies.
    bool GetAutoClearForces() const noexcept;
    /// Gravity, m/s^2.
    void SetGravity(const b2Vec2& gravity) noexcept;
    /// Gravity, m/s^2 (given to the constructor or SetGravity).
    b2Vec2 GetGravity() const noexcept;

    /// Bounds for body centres (m); a body whose centre leaves them is taken out of the
    /// simulation and reported to the b2BoundaryListener. Default +-16000 m.
    void SetWorldBounds(const b2AABB& bounds) noexcept;
    /// Bounds for body centres, m (default +-16000 m on each axis).
    const b2AABB& GetWorldBounds() const noexcept;

    /// Broad-phase proxies (one per child of each fixture of an active body).
    int32 GetProxyCount() const noexcept;
    /// Number of bodies in the world.
    int32 GetBodyCount() const noexcept;
    /// Number of joints in the world.
    int32 GetJointCount() const noexcept;
    /// Number of contacts, touching or not (one per overlapping pair of fixture children's AABBs).
    int32 GetContactCount() const noexcept;
    /// True inside Step.
    bool IsLocked() const noexcept;
    /// Work counters and timings of the last Step.
    const b2Profile& GetProfile() const noexcept;
    /// Headroom telemetry: when on, each Step ends by filling GetProfile().headroom (a walk of
    /// every body, contact, joint and tree node). Off by default, so a Step costs nothing extra.
    void SetHeadroomTelemetry(bool flag) noexcept;
    /// Whether headroom telemetry is on.
    bool GetHeadroomTelemetry() const noexcept;
    /// Stage timers: when on (the default, as Box2D's profile), each Step reads the clock about
    /// ten times, and a few more per island it solves, to fill GetProfile()'s *Ns fields. Off, a
    /// Step reads no clock and those fields stay zero; the work counters and every result are
    /// the same either way. Not state: snapshots and the hash ignore it.
    void SetProfileTimers(bool flag) noexcept;
    /// Whether the stage timers are on.
    bool GetProfileTimers() const noexcept;
    /// Step fenceposts (StepObserver.h): the observer hears every stage of every Step; nullptr
    /// (the default) turns them off. Not state: snapshots and the hash ignore it.
    void SetStepObserver(b2StepObserver* observer) noexcept;
    /// The step observer, or nullptr when none is set.
    b2StepObserver* GetStepObserver() const noexcept;

private:
    friend struct core_detail::Engine;
    /// Everything else: pools, lists, switches, the contact manager, solver buffers and the
    /// rollback frames' book-keeping (core/src, allocated once with the world).
    class State;
    std::unique_ptr<State> m_state;
};

}  // namespace lockbox
