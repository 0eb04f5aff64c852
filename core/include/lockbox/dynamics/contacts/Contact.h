#pragma once
/// @file
/// b2Contact (Box2D 2.2.1 b2Contact.h): the manifold of two fixture children whose AABBs
/// overlap. One class serves every shape pair: Evaluate dispatches on the two shape types to the
/// b2Collide* functions (a chain collides through its child edge). Pairs without a collider
/// (edge/chain against edge/chain) create no contact.

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/Shape.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

class b2Body;
class b2Contact;
class b2Fixture;
class b2ContactListener;
struct b2Profile;

/// Friction mixing: sqrt(f1 * f2), computed as the correctly rounded square root of the exact
/// raw product (one rounding).
LOCKBOX_API Fixed b2MixFriction(Fixed friction1, Fixed friction2);
/// Restitution mixing: the larger one.
inline Fixed b2MixRestitution(Fixed r1, Fixed r2) noexcept { return r1 > r2 ? r1 : r2; }

/// A contact edge links a body to a contact and to the other body in the contact graph.
/// (next before prev: a walk of a body's list reads the first three together.)
struct b2ContactEdge {
    b2Body* other = nullptr;        ///< the other body
    b2Contact* contact = nullptr;   ///< the contact
    b2ContactEdge* next = nullptr;  ///< next edge in the body's contact list
    b2ContactEdge* prev = nullptr;  ///< previous edge in the body's contact list
};

/// A potential contact between two fixture children. Owned by the contact manager. Aligned
/// to a cache line (its first member is), so that its layout below decides which fields share one.
class LOCKBOX_API b2Contact {
public:
    /// The manifold in local coordinates (do not modify).
    b2Manifold* GetManifold() noexcept { return &m_manifold; }
    /// The manifold in local coordinates (read-only view).
    const b2Manifold* GetManifold() const noexcept { return &m_manifold; }
    /// The manifold in world coordinates.
    void GetWorldManifold(b2WorldManifold* worldManifold) const;
    /// True when the shapes touch (sensors: overlap).
    bool IsTouching() const noexcept { return (m_flags & e_touchingFlag) != 0; }
    /// Enables or disables the contact for the current step only (PreSolve use).
    void SetEnabled(bool flag) noexcept {
        if (flag)
            m_flags |= e_enabledFlag;
        else
            m_flags &= ~e_enabledFlag;
    }
    /// Whether the contact is enabled. SetEnabled(false) in a PreSolve callback disables it for the
    /// current step only: the flag is set again before the next step's update.
    bool IsEnabled() const noexcept { return (m_flags & e_enabledFlag) != 0; }
    /// Next contact in the world's list (newest first).
    b2Contact* GetNext() noexcept { return m_next; }
    /// Next contact in the world's list (read-only view).
    const b2Contact* GetNext() const noexcept { return m_next; }
    /// The fixture on side A (the manifold's normal points from A to B).
    ///@{
    b2Fixture* GetFixtureA() noexcept { return m_fixtureA; }
    const b2Fixture* GetFixtureA() const noexcept { return m_fixtureA; }
    ///@}
    /// Child index on fixture A: the edge of a chain, otherwise 0.
    int32 GetChildIndexA() const noexcept { return m_indexA; }
    /// The fixture on side B.
    ///@{
    b2Fixture* GetFixtureB() noexcept { return m_fixtureB; }
    const b2Fixture* GetFixtureB() const noexcept { return m_fixtureB; }
    ///@}
    /// Child index on fixture B: the edge of a chain, otherwise 0.
    int32 GetChildIndexB() const noexcept { return m_indexB; }
    /// Mixed friction; persists until ResetFriction.
    void SetFriction(Fixed friction) noexcept { m_friction = friction; }
    /// The friction coefficient used by this contact (dimensionless, >= 0).
    Fixed GetFriction() const noexcept { return m_friction; }
    /// Restores the friction to the mix of the two fixtures' values (b2MixFriction).
    void ResetFriction();
    /// Mixed restitution; persists until ResetRestitution.
    void SetRestitution(Fixed restitution) noexcept { m_restitution = restitution; }
    /// The restitution used by this contact (dimensionless, 0 is inelastic, 1 perfectly elastic).
    Fixed GetRestitution() const noexcept { return m_restitution; }
    /// Restores the restitution to the mix of the two fixtures' values (b2MixRestitution).
    void ResetRestitution();
    /// Small integer id (stable across snapshot and restore).
    int32 GetId() const noexcept { return m_id; }
    /// Flags the contact for re-filtering at the next Step.
    void FlagForFiltering() noexcept { m_flags |= e_filterFlag; }

    b2Contact(const b2Contact&) = delete;
    b2Contact& operator=(const b2Contact&) = delete;

private:
    friend struct core_detail::Engine;

    enum : uint32 {
        e_islandFlag = 0x0001,     ///< used when crawling the contact graph to form islands
        e_touchingFlag = 0x0002,   ///< set when the shapes are touching
        e_enabledFlag = 0x0004,    ///< this contact can be disabled by the user
        e_filterFlag = 0x0008,     ///< this contact needs filtering (filter data changed)
        e_bulletHitFlag = 0x0010,  ///< this bullet contact had a TOI event
        e_toiFlag = 0x0020         ///< m_toi is valid
    };

    b2Contact(b2Fixture* fixtureA, int32 indexA, b2Fixture* fixtureB, int32 indexB, int32 id);
    /// Rollback frames: a contact whose every field the frame then writes (no fixture is read).
    b2Contact(b2RestoreTag, int32 id) noexcept
        : m_fixtureIdA(-1),
          m_indexA(0),
          m_fixtureIdB(-1),
          m_indexB(0),
          m_id(id),
          m_fixtureA(nullptr),
          m_fixtureB(nullptr) {}
    ~b2Contact() = default;

    /// Computes the manifold for the current transforms (dispatches on the shape types).
    void Evaluate(b2Manifold* manifold, const b2Transform& xfA, const b2Transform& xfB);
    /// Updates the manifold and touching state and calls the listener (Begin/End/PreSolve).
    /// Counts narrow-phase work and listener calls into profile (may be nullptr).
    void Update(b2ContactListener* listener, b2Profile* profile);
    /// The geometry of an update, apart from it: `*manifold` must hold a copy of this contact's
    /// manifold; it becomes the new one (a sensor pair's: point count 0). Returns whether the
    /// shapes touch. Reads only the shapes and the bodies' transforms and writes only
    /// `*manifold`, so different contacts can be evaluated on different threads.
    bool EvaluateUpdate(bool sensor, b2Manifold* manifold);
    /// Update for a world with no contact listener, leaving the waking of the bodies to the
    /// caller, so that different contacts can be updated on different threads: the same
    /// manifold, impulses and flags as Update. Returns whether the bodies must be woken (a
    /// non-sensor pair began or stopped touching). Counts nothing.
    bool UpdateUnobserved();
    /// Update with its geometry already evaluated by EvaluateUpdate(sensor, &manifold) for the
    /// current transforms: the same result and listener calls as Update.
    void UpdateFrom(b2ContactListener* listener, b2Profile* profile, bool sensor, const b2Manifold& manifold,
                    bool touching);
    /// The part of an update that needs nothing outside the contact, once the new manifold is in
    /// place: impulses carried over by feature, touching flag. Returns whether the bodies must
    /// be woken.
    bool SettleUpdate(const b2Manifold& oldManifold, bool sensor, bool touching);
    /// What Update and UpdateFrom share once the new manifold is in place.
    void FinishUpdate(b2ContactListener* listener, b2Profile* profile, const b2Manifold& oldManifold, bool sensor,
                      bool touching);
    /// True when either fixture is a sensor (then the update tests overlap, with no manifold).
    bool IsSensorPair() const noexcept { return m_sensor; }
    /// m_sensor for the fixtures' current sensor flags.
    bool SensorPairNow() const noexcept;
    /// m_toiBodies for the bodies' current types and bullet flags.
    static bool ToiBodies(const b2Body& bodyA, const b2Body& bodyB) noexcept;

    // Layout, in 64-byte lines. Lines 0 and 1 hold what the state walks (hash, save) read, apart
    // from the flags. Line 2 starts with the flags, then the sensor mark and the graph edges:
    // the island search and the time-of-impact filters read a contact's flags and sensor mark
    // through an edge, so that costs one line instead of three (flags, and both fixtures), and
    // the state walks still read three. Line 3 holds the links the walks of the list read.
    alignas(64) int32 m_fixtureIdA;  ///< m_fixtureA->GetId(), kept here so the state walks need not visit the fixture
    int32 m_indexA;
    int32 m_fixtureIdB;  ///< m_fixtureB->GetId()
    int32 m_indexB;
    int32 m_id;
    int32 m_toiCount = 0;
    Fixed m_toi;  ///< cached time of impact, fraction of the step in [0, 1]
    Fixed m_friction;
    Fixed m_restitution;
    b2Manifold m_manifold;
    alignas(64) uint32 m_flags = e_enabledFlag;
    /// Either fixture is a sensor: IsSensorPair without visiting the fixtures. Set when the
    /// contact is made or restored and by b2Fixture::SetSensor; derived, never state.
    bool m_sensor = false;
    /// A body of the pair is a bullet or not dynamic: the pair passes the time-of-impact
    /// search's body filter. Set when the contact is made or restored and by b2Body::SetBullet
    /// and SetType; derived, never state.
    bool m_toiBodies = false;
    b2ContactEdge m_nodeA;
    b2ContactEdge m_nodeB;
    b2Contact* m_prev = nullptr;
    b2Contact* m_next = nullptr;
    b2Fixture* m_fixtureA;
    b2Fixture* m_fixtureB;
    /// Where the contact stands in the world's contact list: smaller is nearer the head, and
    /// no two contacts of a world share one. A contact inserted at the head takes the old
    /// head's key minus one, a restored list numbers its contacts upwards from the head, and
    /// removals leave the others' order as it was, so sorting by it gives list order without
    /// walking the list. Derived from the list, never state.
    int64_t m_listKey = 0;
};

}  // namespace lockbox
