#pragma once
/// @file
/// b2Fixture (Box2D 2.2.1 b2Fixture.h): binds a shape to a body with material properties,
/// collision filtering and broad-phase proxies.

#include <memory>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/Shape.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

class b2Body;
class b2BroadPhase;
class b2Fixture;

/// Contact filtering data (the manual's "Filtering").
struct b2Filter {
    /// Collision category bits (usually one bit set).
    uint16 categoryBits = 0x0001;
    /// Categories this fixture accepts collisions with.
    uint16 maskBits = 0xFFFF;
    /// Same non-zero group: always collide (positive) or never (negative); overrides the bits.
    int16 groupIndex = 0;
};

/// Definition of a fixture; the shape is cloned, so the definition can be reused.
struct b2FixtureDef {
    const b2Shape* shape = nullptr;          ///< must be set
    uint64 userData = 0;                     ///< application data (an id or handle, never a pointer)
    Fixed friction = Fixed::FromRaw(13107);  ///< Coulomb coefficient, usually [0, 1] (default 0.2)
    Fixed restitution;                       ///< elasticity, usually [0, 1]
    Fixed density;                           ///< kg/m^2
    bool isSensor = false;                   ///< a sensor reports overlaps but never responds
    b2Filter filter;                         ///< contact filtering data
};

/// One broad-phase proxy of a fixture (one per shape child). The broad phase's user data is
/// b2FixtureProxy::MakeKey(fixtureId, childIndex): ids, never addresses.
struct b2FixtureProxy {
    b2AABB aabb;                   ///< fat-free AABB of the child, m
    b2Fixture* fixture = nullptr;  ///< owner
    int32 childIndex = 0;          ///< child of the shape
    int32 proxyId = -1;            ///< broad-phase proxy id

    /// Packs a fixture id and child index into the broad phase's 64-bit user data.
    static constexpr uint64 MakeKey(int32 fixtureId, int32 childIndex) noexcept {
        return (static_cast<uint64>(static_cast<uint32>(fixtureId)) << 32) | static_cast<uint32>(childIndex);
    }
    /// The fixture id of a key.
    static constexpr int32 KeyFixture(uint64 key) noexcept { return static_cast<int32>(key >> 32); }
    /// The child index of a key.
    static constexpr int32 KeyChild(uint64 key) noexcept { return static_cast<int32>(key & 0xFFFFFFFFu); }
};

/// A shape attached to a body. Create with b2Body::CreateFixture; never construct directly.
class LOCKBOX_API b2Fixture {
public:
    /// Shape type (the child shape type for chains is e_edge at collision time).
    b2Shape::Type GetType() const noexcept { return m_shape->GetType(); }
    /// The fixture's own shape (a clone of the definition's), to read. Reading changes nothing.
    const b2Shape* GetShape() const noexcept { return m_shape.get(); }
    /// The fixture's own shape, to change (its radius, vertices, centre): tells the world that
    /// its structure changed, so a rollback frame saved before the edit restores the shape as
    /// it was. Call it for each edit (an edit through a pointer kept from before the last
    /// SaveFrame goes unseen). Keep the shape's type and child count; mass and proxies follow
    /// at ResetMassData and the next step's synchronisation, as in Box2D.
    b2Shape* EditShape() noexcept;

    /// Makes this a sensor (or not). Takes effect at the next contact update.
    void SetSensor(bool sensor) noexcept;
    /// Whether this fixture is a sensor: it detects overlaps (its contacts touch and are reported)
    /// but produces no collision response.
    bool IsSensor() const noexcept { return m_isSensor; }

    /// Replaces the filter data. Contacts of this fixture are re-filtered at the start of the
    /// next Step, and its proxies are touched so new pairs can form then.
    void SetFilterData(const b2Filter& filter);
    /// The collision filter (category and mask bits, group index).
    const b2Filter& GetFilterData() const noexcept { return m_filter; }

    /// The parent body.
    b2Body* GetBody() noexcept { return m_body; }
    /// The parent body (read-only view).
    const b2Body* GetBody() const noexcept { return m_body; }
    /// Next fixture of the parent body (newest first).
    b2Fixture* GetNext() noexcept { return m_next; }
    /// Next fixture of the parent body (read-only view).
    const b2Fixture* GetNext() const noexcept { return m_next; }

    /// Application data: an id or handle, never a pointer (part of the snapshot and the hash).
    ///@{
    uint64 GetUserData() const noexcept { return m_userData; }
    void SetUserData(uint64 data) noexcept;
    ///@}
    /// Small integer id (world-wide, stable across snapshot and restore).
    int32 GetId() const noexcept { return m_id; }

    /// Point containment test in world coordinates (m).
    bool TestPoint(const b2Vec2& p) const;
    /// Ray cast against one child of the shape.
    bool RayCast(b2RayCastOutput* output, const b2RayCastInput& input, int32 childIndex) const;
    /// Mass properties of the shape at this fixture's density.
    void GetMassData(b2MassData* massData) const;

    /// Density, kg/m^2. Call b2Body::ResetMassData afterwards to update the body.
    void SetDensity(Fixed density) noexcept;
    /// Density, kg/m^2 (>= 0); the body's mass is density times area summed over its fixtures.
    Fixed GetDensity() const noexcept { return m_density; }
    /// Friction coefficient (dimensionless, usually in [0, 1]); contacts mix it with the other
    /// fixture's as sqrt(f1 * f2).
    Fixed GetFriction() const noexcept { return m_friction; }
    /// Affects contacts created after the call only (as in 2.2.1).
    void SetFriction(Fixed friction) noexcept;
    /// Restitution, or bounciness (dimensionless, 0 inelastic to 1 elastic); contacts use the
    /// larger of the two fixtures' values.
    Fixed GetRestitution() const noexcept { return m_restitution; }
    /// Affects contacts created after the call only (as in 2.2.1).
    void SetRestitution(Fixed restitution) noexcept;

    /// The fat-free AABB of a child as of the last synchronisation (m).
    const b2AABB& GetAABB(int32 childIndex) const { return m_proxies[static_cast<size_t>(childIndex)].aabb; }
    /// Number of broad-phase proxies (0 when the body is inactive).
    int32 GetProxyCount() const noexcept { return m_proxyCount; }
    b2Fixture(const b2Fixture&) = delete;
    b2Fixture& operator=(const b2Fixture&) = delete;

private:
    friend struct core_detail::Engine;

    b2Fixture() = default;
    ~b2Fixture() = default;
    void Create(b2Body* body, const b2FixtureDef* def, int32 id);
    void CreateProxies(b2BroadPhase* broadPhase, const b2Transform& xf);
    void DestroyProxies(b2BroadPhase* broadPhase);
    void Synchronize(b2BroadPhase* broadPhase, const b2Transform& xf1, const b2Transform& xf2);
    /// One proxy's box swept from xf1 to xf2.
    void SweepProxy(b2FixtureProxy& proxy, const b2Transform& xf1, const b2Transform& xf2) const;
    /// Synchronize's first half: each proxy's box swept from xf1 to xf2; returns whether any
    /// left its fat box in the tree (which it only reads).
    bool SweepProxies(const b2BroadPhase& broadPhase, const b2Transform& xf1, const b2Transform& xf2);
    /// Its second half: moves each proxy to its swept box (displacement xf2.p - xf1.p).
    void MoveProxies(b2BroadPhase* broadPhase, const b2Vec2& displacement);

    Fixed m_density;
    b2Fixture* m_next = nullptr;
    b2Body* m_body = nullptr;
    std::unique_ptr<b2Shape> m_shape;
    Fixed m_friction;
    Fixed m_restitution;
    std::vector<b2FixtureProxy> m_proxies;
    int32 m_proxyCount = 0;
    b2Filter m_filter;
    bool m_isSensor = false;
    uint64 m_userData = 0;
    int32 m_id = -1;
};

}  // namespace lockbox
