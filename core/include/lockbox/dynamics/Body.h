#pragma once
/// @file
/// b2Body (Box2D 2.2.1 b2Body.h): a rigid body. Create with b2World::CreateBody.
///
/// Formats: position, angle, velocities, forces are Fixed (Q16.16); mass, inertia and their
/// inverses are Wide (Q32.32) because Q16.16 under- and overflows for small and large bodies
/// (docs/numerics.md, "Formats"). User data is a uint64 (an id or handle), never a pointer.

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

class b2World;
class b2Contact;
struct b2ContactEdge;
struct b2JointEdge;

/// Body types (the manual's "Body Types").
enum b2BodyType {
    b2_staticBody = 0,  ///< zero mass, zero velocity, moved only by SetTransform
    b2_kinematicBody,   ///< zero mass, velocity set by the user, moved by the solver
    b2_dynamicBody      ///< positive mass, moved by forces and contacts
};

/// Everything needed to create a body; reusable.
struct b2BodyDef {
    b2BodyType type = b2_staticBody;  ///< body type
    b2Vec2 position;                  ///< world position of the body origin, m
    Fixed angle;                      ///< world angle, rad
    b2Vec2 linearVelocity;            ///< of the origin, m/s
    Fixed angularVelocity;            ///< rad/s
    Fixed linearDamping;              ///< 1/s, >= 0 (v *= 1 / (1 + h*c) each step)
    Fixed angularDamping;             ///< 1/s, >= 0
    bool allowSleep = true;           ///< may this body fall asleep?
    bool awake = true;                ///< initially awake?
    bool fixedRotation = false;       ///< prevents rotation (zero inverse inertia)
    bool bullet = false;              ///< continuous collision against dynamic bodies too
    bool active = true;               ///< in the simulation at start?
    uint64 userData = 0;              ///< application data
    Fixed gravityScale = 1;           ///< multiplies the world gravity for this body
};

/// A rigid body: a position and angle, velocities, mass data from its fixtures, and its fixture,
/// joint and contact lists. Created and destroyed by b2World; a user never deletes one.
class LOCKBOX_API b2Body {
public:
    /// Creates a fixture from a definition and attaches it (refused while the world is
    /// locked: returns nullptr). Updates the mass if the density is positive.
    b2Fixture* CreateFixture(const b2FixtureDef* def);
    /// Shortcut for a fixture with default material and the given density (kg/m^2).
    b2Fixture* CreateFixture(const b2Shape* shape, Fixed density);
    /// Destroys a fixture and its contacts, then resets the mass (refused while locked).
    void DestroyFixture(b2Fixture* fixture);

    /// Moves the body origin (m) and angle (rad); contacts update at the next Step (refused
    /// while locked).
    void SetTransform(const b2Vec2& position, Fixed angle);
    /// The body origin's transform.
    const b2Transform& GetTransform() const noexcept { return m_xf; }
    /// World position of the body origin, m.
    const b2Vec2& GetPosition() const noexcept { return m_xf.p; }
    /// Angle in radians, kept in [-pi, pi) by the step (whole turns are removed exactly).
    Fixed GetAngle() const noexcept { return m_sweep.a; }
    /// World position of the centre of mass, m.
    const b2Vec2& GetWorldCenter() const noexcept { return m_sweep.c; }
    /// Centre of mass in body coordinates, m.
    const b2Vec2& GetLocalCenter() const noexcept { return m_sweep.localCenter; }

    /// Sets the linear velocity of the centre of mass (m/s); wakes the body if non-zero.
    void SetLinearVelocity(const b2Vec2& v);
    /// Linear velocity of the centre of mass, m/s (rounded to Q16.16; the body also keeps the
    /// part below that quantum, which the next step continues from).
    const b2Vec2& GetLinearVelocity() const noexcept { return m_linearVelocity; }
    /// Sets the angular velocity (rad/s); wakes the body if non-zero.
    void SetAngularVelocity(Fixed omega);
    /// Angular velocity, rad/s (positive is counter-clockwise).
    Fixed GetAngularVelocity() const noexcept { return m_angularVelocity; }

    /// Applies a force (N) at a world point (m); wakes the body. Dynamic bodies only.
    void ApplyForce(const b2Vec2& force, const b2Vec2& point);
    /// Applies a force (N) at the centre of mass; wakes the body.
    void ApplyForceToCenter(const b2Vec2& force);
    /// Applies a torque (N*m); wakes the body.
    void ApplyTorque(Fixed torque);
    /// Applies an impulse (N*s) at a world point (m); wakes the body.
    void ApplyLinearImpulse(const b2Vec2& impulse, const b2Vec2& point);
    /// Applies an angular impulse (N*m*s); wakes the body.
    void ApplyAngularImpulse(Fixed impulse);

    /// Total mass, kg (Q32.32).
    Wide GetMass() const noexcept { return m_mass; }
    /// Rotational inertia about the body origin, kg*m^2 (Q32.32).
    Wide GetInertia() const noexcept;
    /// Mass data of the body: mass, centre (body frame) and inertia about the origin.
    void GetMassData(b2MassData* data) const;
    /// Overrides the mass properties (dynamic bodies only; refused while locked). A
    /// non-positive mass becomes 1 kg.
    void SetMassData(const b2MassData* data);
    /// Recomputes the mass from the fixtures. A dynamic body without mass gets 1 kg.
    void ResetMassData();

    /// Local point -> world point.
    b2Vec2 GetWorldPoint(const b2Vec2& localPoint) const { return b2Mul(m_xf, localPoint); }
    /// Local vector -> world vector.
    b2Vec2 GetWorldVector(const b2Vec2& localVector) const { return b2Mul(m_xf.q, localVector); }
    /// World point -> local point.
    b2Vec2 GetLocalPoint(const b2Vec2& worldPoint) const { return b2MulT(m_xf, worldPoint); }
    /// World vector -> local vector.
    b2Vec2 GetLocalVector(const b2Vec2& worldVector) const { return b2MulT(m_xf.q, worldVector); }
    /// Velocity of a world point attached to this body, m/s.
    b2Vec2 GetLinearVelocityFromWorldPoint(const b2Vec2& worldPoint) const;
    /// Velocity of a local point attached to this body, m/s.
    b2Vec2 GetLinearVelocityFromLocalPoint(const b2Vec2& localPoint) const;

    /// Linear damping, 1/s (>= 0; 0 is none, the manual suggests 0 to 0.1): each step scales the
    /// linear velocity by 1 / (1 + h * damping), a drag that stays stable for any value.
    ///@{
    Fixed GetLinearDamping() const noexcept { return m_linearDamping; }
    void SetLinearDamping(Fixed d) noexcept;
    ///@}
    /// Angular damping, 1/s (>= 0): each step scales the angular velocity by 1 / (1 + h * damping).
    ///@{
    Fixed GetAngularDamping() const noexcept { return m_angularDamping; }
    void SetAngularDamping(Fixed d) noexcept;
    ///@}
    /// Multiplier of the world gravity for this body (1 is normal, 0 floats, negative rises).
    ///@{
    Fixed GetGravityScale() const noexcept { return m_gravityScale; }
    void SetGravityScale(Fixed s) noexcept;
    ///@}

    /// Changes the type; resets mass, wakes, and re-filters contacts (refused while locked).
    void SetType(b2BodyType type);
    /// The body type (static, kinematic or dynamic).
    b2BodyType GetType() const noexcept { return m_type; }

    /// A bullet takes part in continuous collision against dynamic bodies too (not only static and
    /// kinematic ones), so a fast small body does not tunnel through other moving bodies; it costs
    /// time.
    ///@{
    void SetBullet(bool flag) noexcept;
    bool IsBullet() const noexcept { return (m_flags & e_bulletFlag) != 0; }
    ///@}
    /// Whether the body may fall asleep; false wakes it.
    void SetSleepingAllowed(bool flag);
    /// Whether the body may fall asleep after resting long enough.
    bool IsSleepingAllowed() const noexcept { return (m_flags & e_autoSleepFlag) != 0; }
    /// Wakes (resets the sleep counter) or puts to sleep (zeroes velocities and forces).
    void SetAwake(bool flag);
    /// Whether the body is awake; a sleeping body is not simulated until something wakes it.
    bool IsAwake() const noexcept { return (m_flags & e_awakeFlag) != 0; }
    /// Adds or removes the body from the simulation: proxies and contacts are destroyed when
    /// deactivated and recreated at the next Step when activated (refused while locked).
    void SetActive(bool flag);
    /// Whether the body takes part in the simulation (collision, solver, ray casts). An inactive
    /// body keeps its fixtures and joints but has no broad-phase proxies or contacts.
    bool IsActive() const noexcept { return (m_flags & e_activeFlag) != 0; }
    /// True after the world bounds check took this body out of the simulation (cleared when
    /// the body is activated again).
    bool IsOutOfBounds() const noexcept { return (m_flags & e_outOfBoundsFlag) != 0; }
    /// A body with fixed rotation has zero inverse inertia: forces, contacts and joints cannot turn
    /// it. Changing the flag resets the mass data.
    ///@{
    void SetFixedRotation(bool flag);
    bool IsFixedRotation() const noexcept { return (m_flags & e_fixedRotationFlag) != 0; }
    ///@}

    /// First fixture of the body's fixture list (newest first; follow b2Fixture::GetNext), or
    /// nullptr.
    ///@{
    b2Fixture* GetFixtureList() noexcept { return m_fixtureList; }
    const b2Fixture* GetFixtureList() const noexcept { return m_fixtureList; }
    ///@}
    /// First edge of the body's joint list (one b2JointEdge per attached joint), or nullptr.
    ///@{
    b2JointEdge* GetJointList() noexcept { return m_jointList; }
    const b2JointEdge* GetJointList() const noexcept { return m_jointList; }
    ///@}
    /// First edge of the body's contact list (one b2ContactEdge per contact of one of its
    /// fixtures, touching or not), or nullptr. Contacts come and go with the broad-phase during
    /// Step: do not keep pointers to them across steps.
    ///@{
    b2ContactEdge* GetContactList() noexcept { return m_contactList; }
    const b2ContactEdge* GetContactList() const noexcept { return m_contactList; }
    ///@}
    /// Next body in the world list (newest first).
    b2Body* GetNext() noexcept { return m_next; }
    /// Next body in the world list (newest first).
    const b2Body* GetNext() const noexcept { return m_next; }
    /// Application data: an id or handle, never a pointer, so it survives snapshot and restore and
    /// hashes the same on every machine. It is part of the snapshot.
    ///@{
    uint64 GetUserData() const noexcept { return m_userData; }
    void SetUserData(uint64 data) noexcept;
    ///@}
    /// The world that owns this body.
    ///@{
    b2World* GetWorld() noexcept { return m_world; }
    const b2World* GetWorld() const noexcept { return m_world; }
    ///@}
    /// Small integer id (stable across snapshot and restore).
    int32 GetId() const noexcept { return m_id; }
    /// Consecutive still steps counted toward sleep.
    int32 GetSleepSteps() const noexcept { return m_sleepSteps; }

    b2Body(const b2Body&) = delete;
    b2Body& operator=(const b2Body&) = delete;

private:
    friend struct core_detail::Engine;

    enum : uint16 {
        e_islandFlag = 0x0001,
        e_awakeFlag = 0x0002,
        e_autoSleepFlag = 0x0004,
        e_bulletFlag = 0x0008,
        e_fixedRotationFlag = 0x0010,
        e_activeFlag = 0x0020,
        e_fastFlag = 0x0040,  ///< moved far enough this step to need continuous collision
        e_outOfBoundsFlag = 0x0080,
        /// Set while the island search has scanned the body's edges; cleared when its island is
        /// done, so never seen outside the search.
        e_scannedFlag = 0x0100,
    };

    b2Body(const b2BodyDef* def, b2World* world, int32 id);
    ~b2Body() = default;

    void SynchronizeTransform();
    /// Whether this body may collide with other (type rule and joints' collideConnected).
    bool ShouldCollide(const b2Body* other) const;
    /// Moves the body to time fraction alpha of its sweep (TOI).
    void Advance(Fixed alpha);
    /// Removes whole turns from the sweep angles once a leaves [-pi, pi).
    void WrapAngle() noexcept;
    /// Recomputes m_minExtent and m_maxExtent from the fixtures.
    void UpdateExtents();
    /// True when this step's motion could tunnel: the centre moved, or a point on the body
    /// swept by the rotation moved, more than half the thinnest fixture extent.
    bool IsFastThisStep() const noexcept;
    /// A bound (m) on how far any point of the body moved along this step's sweep:
    /// |c - c0| + |a - a0| * maxExtent.
    Wide SweptDistanceBound() const noexcept;

    b2BodyType m_type;
    uint16 m_flags = 0;
    int32 m_islandIndex = 0;
    b2Transform m_xf;  ///< body origin transform
    b2Sweep m_sweep;   ///< swept motion for CCD
    /// The Q32.32 velocity the solver works on, made of the Q16.16 value and its remainder.
    b2Velocity SolverVelocity() const noexcept;
    /// Stores a Q32.32 velocity: its Q16.16 rounding and the remainder.
    void SetSolverVelocity(const b2Velocity& v) noexcept;

    /// Moves the centre and angle by a Q32.32 displacement, rounded with the position
    /// remainder carried from the previous steps (Q32.32 integration of positions).
    void Displace(Wide dx, Wide dy, Wide da, b2Vec2& c, Fixed& a) noexcept;

    /// The part of a Q32.32 quantity below its Q16.16 rounding, in raw units of 2^-32,
    /// |r| <= 2^15: a force too gentle to change the Q16.16 velocity in one step still
    /// accumulates over many, and a slow body moves at its velocity's rate, not at the rate of
    /// h v rounded to a whole Q16.16 unit per step. x and y are linear, w angular.
    struct SubRaw {
        int32 x = 0;
        int32 y = 0;
        int32 w = 0;
    };

    b2Vec2 m_linearVelocity;
    Fixed m_angularVelocity;
    SubRaw m_velocityRemainder;  ///< m/s and rad/s
    SubRaw m_positionRemainder;  ///< of m_sweep.c (m) and m_sweep.a (rad)
    b2Vec2 m_force;              ///< N
    Fixed m_torque;              ///< N*m
    b2World* m_world;
    b2Body* m_prev = nullptr;
    b2Body* m_next = nullptr;
    b2Fixture* m_fixtureList = nullptr;
    int32 m_fixtureCount = 0;
    /// How many of its contacts have b2Contact::m_toiBodies set: derived, like that mark, not
    /// state. The time-of-impact stage skips the contacts of a body without any.
    int32 m_toiContacts = 0;
    b2JointEdge* m_jointList = nullptr;
    b2ContactEdge* m_contactList = nullptr;
    Wide m_mass, m_invMass;
    Wide m_I, m_invI;  ///< about the centre of mass
    Fixed m_linearDamping;
    Fixed m_angularDamping;
    Fixed m_gravityScale;
    int32 m_sleepSteps = 0;
    Fixed m_minExtent;  ///< smallest fixture half-thickness (m), for the TOI speed test
    Fixed m_maxExtent;  ///< largest distance of a fixture point from the centre of mass (m)
    uint64 m_userData = 0;
    int32 m_id;
    /// The body's place in the world's body list: each body's key is below those after it
    /// (derived where the list is built, not state), so a few bodies gathered out of order are
    /// put back in list order by a sort without ties.
    int64_t m_listKey = 0;
};

}  // namespace lockbox
