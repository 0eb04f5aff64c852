#pragma once
/// @file
/// World callbacks (Box2D 2.2.1 b2WorldCallbacks.h): destruction, contact filtering, contact
/// events, queries and ray casts, plus lockbox's world-bounds listener.

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

class b2Body;
class b2Contact;
class b2Fixture;
class b2Joint;

/// Told when the world destroys a joint or fixture implicitly (by destroying its body), so the
/// application can drop its handles.
class LOCKBOX_API b2DestructionListener {
public:
    virtual ~b2DestructionListener() = default;
    /// A joint is about to be destroyed because one of its bodies is.
    virtual void SayGoodbye(b2Joint* joint) = 0;
    /// A fixture is about to be destroyed because its body is.
    virtual void SayGoodbye(b2Fixture* fixture) = 0;
};

/// Told when a body's centre of mass leaves the world bounds (b2World::SetWorldBounds). By the
/// time Violation is called the body is already out of the simulation: inactive (no proxies,
/// no contacts), with zero velocity, and IsOutOfBounds() true. Called at the end of Step, in
/// body-list order; the world is unlocked, so the handler may destroy the body or move it
/// back with SetTransform and SetActive(true).
class LOCKBOX_API b2BoundaryListener {
public:
    virtual ~b2BoundaryListener() = default;
    /// The body left the world bounds.
    virtual void Violation(b2Body* body) = 0;
};

/// Decides whether two fixtures may collide. The default implements the manual's rule: the
/// same non-zero group index collides when positive and never when negative; otherwise each
/// mask must accept the other's category.
class LOCKBOX_API b2ContactFilter {
public:
    virtual ~b2ContactFilter() = default;
    /// Return true when contact calculations should be performed between these fixtures.
    virtual bool ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB);
};

/// Impulses the solver applied to a contact, reported in PostSolve (N*s, Q32.32).
struct b2ContactImpulse {
    /// Normal impulse at each manifold point (N*s); entries past the manifold's point count are
    /// zero.
    Wide normalImpulses[b2_maxManifoldPoints];
    /// Friction impulse at each manifold point (N*s); entries past the manifold's point count are
    /// zero.
    Wide tangentImpulses[b2_maxManifoldPoints];
};

/// Contact events. Every method has an empty default; an unset listener costs nothing.
class LOCKBOX_API b2ContactListener {
public:
    virtual ~b2ContactListener() = default;
    /// Two fixtures begin to touch (sensors too).
    virtual void BeginContact(b2Contact* contact) { (void)contact; }
    /// Two fixtures cease to touch (sensors too; also when a touching contact is destroyed).
    virtual void EndContact(b2Contact* contact) { (void)contact; }
    /// After collision, before solving, for touching non-sensor contacts; may disable the
    /// contact for this step. oldManifold is the manifold of the previous step.
    virtual void PreSolve(b2Contact* contact, const b2Manifold* oldManifold) {
        (void)contact;
        (void)oldManifold;
    }
    /// After solving, with the impulses applied (touching, enabled, non-sensor contacts in
    /// islands), in island order. With one worker each island's calls come right after it is
    /// solved; with more, after every island of the step is solved (same calls, same order).
    virtual void PostSolve(b2Contact* contact, const b2ContactImpulse* impulse) {
        (void)contact;
        (void)impulse;
    }
};

/// AABB query callback.
class LOCKBOX_API b2QueryCallback {
public:
    virtual ~b2QueryCallback() = default;
    /// Called for each fixture whose fat AABB overlaps the query box. Return false to stop.
    virtual bool ReportFixture(b2Fixture* fixture) = 0;
};

/// Ray-cast callback, with the manual's fraction protocol.
class LOCKBOX_API b2RayCastCallback {
public:
    virtual ~b2RayCastCallback() = default;
    /// Called for each fixture hit: point (m), normal, and fraction along the ray. Return -1 to
    /// ignore this fixture and continue, 0 to stop, the fraction to clip the ray to this hit,
    /// or 1 to continue unclipped.
    virtual Fixed ReportFixture(b2Fixture* fixture, const b2Vec2& point, const b2Vec2& normal, Fixed fraction) = 0;
};

}  // namespace lockbox
