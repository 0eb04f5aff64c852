// b2Contact: creation rules, narrow-phase dispatch and the per-step update.
#include "lockbox/dynamics/contacts/Contact.h"

#include "dynamics/TimeStep.h"
#include "dynamics/contacts/ContactRules.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/Profile.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/fixed/detail/Sqrt.h"

namespace lockbox {

Fixed b2MixFriction(Fixed friction1, Fixed friction2) {
    // sqrt(f1 * f2): the exact raw product is a Q32.32 value whose integer square root is the
    // Q16.16 raw of the result, so one rounding suffices. Negative input is not meaningful.
    const int64_t p = int64_t{friction1.Raw()} * friction2.Raw();
    if (p <= 0) return Fixed();
    const uint64_t r = detail::IsqrtRound64(static_cast<uint64_t>(p));
    return Fixed::FromRaw(static_cast<int32>(r > static_cast<uint64_t>(Fixed::kMaxRaw) ? Fixed::kMaxRaw : r));
}

bool core_detail::ShapesCanCollide(b2Shape::Type typeA, b2Shape::Type typeB) noexcept {
    // Edges and chains are one-sided surfaces: there is no edge/edge collider.
    const bool surfaceA = typeA == b2Shape::e_edge || typeA == b2Shape::e_chain;
    const bool surfaceB = typeB == b2Shape::e_edge || typeB == b2Shape::e_chain;
    return !(surfaceA && surfaceB);
}

bool core_detail::ShapesNeedSwap(b2Shape::Type typeA, b2Shape::Type typeB) noexcept {
    // The registered (primary) orders are circle-circle, polygon-circle, polygon-polygon,
    // edge-circle, edge-polygon, chain-circle and chain-polygon: A is never "smaller" than B
    // unless A is a surface (edge or chain).
    auto rank = [](b2Shape::Type t) {
        switch (t) {
            case b2Shape::e_circle: return 0;
            case b2Shape::e_polygon: return 1;
            default: return 2;  // edge, chain
        }
    };
    return rank(typeA) < rank(typeB);
}

b2Contact::b2Contact(b2Fixture* fA, int32 indexA, b2Fixture* fB, int32 indexB, int32 id)
    : m_fixtureIdA(fA->GetId()),
      m_indexA(indexA),
      m_fixtureIdB(fB->GetId()),
      m_indexB(indexB),
      m_id(id),
      m_toiBodies(ToiBodies(*fA->GetBody(), *fB->GetBody())),
      m_fixtureA(fA),
      m_fixtureB(fB) {
    m_sensor = SensorPairNow();
    m_manifold.pointCount = 0;
    m_friction = b2MixFriction(m_fixtureA->GetFriction(), m_fixtureB->GetFriction());
    m_restitution = b2MixRestitution(m_fixtureA->GetRestitution(), m_fixtureB->GetRestitution());
    m_toi = Fixed();
}

bool b2Contact::SensorPairNow() const noexcept { return m_fixtureA->IsSensor() || m_fixtureB->IsSensor(); }

bool b2Contact::ToiBodies(const b2Body& bodyA, const b2Body& bodyB) noexcept {
    const auto collidesWithAny = [](const b2Body& b) { return b.IsBullet() || b.GetType() != b2_dynamicBody; };
    return collidesWithAny(bodyA) || collidesWithAny(bodyB);
}

void b2Contact::ResetFriction() { m_friction = b2MixFriction(m_fixtureA->GetFriction(), m_fixtureB->GetFriction()); }

void b2Contact::ResetRestitution() {
    m_restitution = b2MixRestitution(m_fixtureA->GetRestitution(), m_fixtureB->GetRestitution());
}

void b2Contact::GetWorldManifold(b2WorldManifold* worldManifold) const {
    const b2Body* bodyA = m_fixtureA->GetBody();
    const b2Body* bodyB = m_fixtureB->GetBody();
    const b2Shape* shapeA = m_fixtureA->GetShape();
    const b2Shape* shapeB = m_fixtureB->GetShape();
    worldManifold->Initialize(&m_manifold, bodyA->GetTransform(), shapeA->m_radius, bodyB->GetTransform(),
                              shapeB->m_radius);
}

void b2Contact::Evaluate(b2Manifold* manifold, const b2Transform& xfA, const b2Transform& xfB) {
    const b2Shape* shapeA = m_fixtureA->GetShape();
    const b2Shape* shapeB = m_fixtureB->GetShape();
    const b2Shape::Type typeA = shapeA->GetType();
    const b2Shape::Type typeB = shapeB->GetType();
    const bool circleB = typeB == b2Shape::e_circle;
    switch (typeA) {
        case b2Shape::e_circle:
            b2CollideCircles(manifold, static_cast<const b2CircleShape*>(shapeA), xfA,
                             static_cast<const b2CircleShape*>(shapeB), xfB);
            return;
        case b2Shape::e_polygon:
            if (circleB) {
                b2CollidePolygonAndCircle(manifold, static_cast<const b2PolygonShape*>(shapeA), xfA,
                                          static_cast<const b2CircleShape*>(shapeB), xfB);
            } else {
                b2CollidePolygons(manifold, static_cast<const b2PolygonShape*>(shapeA), xfA,
                                  static_cast<const b2PolygonShape*>(shapeB), xfB);
            }
            return;
        case b2Shape::e_edge:
            if (circleB) {
                b2CollideEdgeAndCircle(manifold, static_cast<const b2EdgeShape*>(shapeA), xfA,
                                       static_cast<const b2CircleShape*>(shapeB), xfB);
            } else {
                b2CollideEdgeAndPolygon(manifold, static_cast<const b2EdgeShape*>(shapeA), xfA,
                                        static_cast<const b2PolygonShape*>(shapeB), xfB);
            }
            return;
        case b2Shape::e_chain: {
            // A chain collides through its child edge (with ghost vertices).
            b2EdgeShape edge;
            static_cast<const b2ChainShape*>(shapeA)->GetChildEdge(&edge, m_indexA);
            if (circleB) {
                b2CollideEdgeAndCircle(manifold, &edge, xfA, static_cast<const b2CircleShape*>(shapeB), xfB);
            } else {
                b2CollideEdgeAndPolygon(manifold, &edge, xfA, static_cast<const b2PolygonShape*>(shapeB), xfB);
            }
            return;
        }
        default: manifold->pointCount = 0; return;
    }
}

void b2Contact::Update(b2ContactListener* listener, b2Profile* profile) {
    const b2Manifold oldManifold = m_manifold;

    // Re-enable this contact (PreSolve may disable it again for this step only).
    m_flags |= e_enabledFlag;

    const bool sensor = IsSensorPair();
    if (profile) ++profile->contactsUpdated;
    const bool touching = EvaluateUpdate(sensor, &m_manifold);
    if (profile && !sensor) ++profile->manifoldsEvaluated;
    FinishUpdate(listener, profile, oldManifold, sensor, touching);
}

bool b2Contact::EvaluateUpdate(bool sensor, b2Manifold* manifold) {
    const b2Transform& xfA = m_fixtureA->GetBody()->GetTransform();
    const b2Transform& xfB = m_fixtureB->GetBody()->GetTransform();
    if (sensor) {
        // Sensors don't generate manifolds.
        manifold->pointCount = 0;
        return b2TestOverlap(m_fixtureA->GetShape(), m_indexA, m_fixtureB->GetShape(), m_indexB, xfA, xfB);
    }
    Evaluate(manifold, xfA, xfB);
    return manifold->pointCount > 0;
}

void b2Contact::UpdateFrom(b2ContactListener* listener, b2Profile* profile, bool sensor, const b2Manifold& manifold,
                           bool touching) {
    const b2Manifold oldManifold = m_manifold;
    m_flags |= e_enabledFlag;
    if (profile) ++profile->contactsUpdated;
    m_manifold = manifold;
    if (profile && !sensor) ++profile->manifoldsEvaluated;
    FinishUpdate(listener, profile, oldManifold, sensor, touching);
}

bool b2Contact::UpdateUnobserved() {
    const b2Manifold oldManifold = m_manifold;
    m_flags |= e_enabledFlag;
    const bool sensor = IsSensorPair();
    const bool touching = EvaluateUpdate(sensor, &m_manifold);
    return SettleUpdate(oldManifold, sensor, touching);
}

bool b2Contact::SettleUpdate(const b2Manifold& oldManifold, bool sensor, bool touching) {
    const bool wasTouching = (m_flags & e_touchingFlag) != 0;
    if (!sensor) {
        // Match new points to old ones by feature key and carry their impulses over for warm
        // starting.
        for (int32 i = 0; i < m_manifold.pointCount; ++i) {
            b2ManifoldPoint* mp2 = m_manifold.points + i;
            mp2->normalImpulse = Wide();
            mp2->tangentImpulse = Wide();
            const uint32 key2 = mp2->id.Key();
            for (int32 j = 0; j < oldManifold.pointCount; ++j) {
                const b2ManifoldPoint* mp1 = oldManifold.points + j;
                if (mp1->id.Key() == key2) {
                    mp2->normalImpulse = mp1->normalImpulse;
                    mp2->tangentImpulse = mp1->tangentImpulse;
                    break;
                }
            }
        }
    }

    if (touching)
        m_flags |= e_touchingFlag;
    else
        m_flags &= ~e_touchingFlag;
    return !sensor && touching != wasTouching;
}

void b2Contact::FinishUpdate(b2ContactListener* listener, b2Profile* profile, const b2Manifold& oldManifold,
                             bool sensor, bool touching) {
    const bool wasTouching = (m_flags & e_touchingFlag) != 0;
    if (SettleUpdate(oldManifold, sensor, touching)) {
        m_fixtureA->GetBody()->SetAwake(true);
        m_fixtureB->GetBody()->SetAwake(true);
    }

    if (listener == nullptr) return;
    if (!wasTouching && touching) {
        listener->BeginContact(this);
        if (profile) ++profile->listenerCallbacks;
    }
    if (wasTouching && !touching) {
        listener->EndContact(this);
        if (profile) ++profile->listenerCallbacks;
    }
    if (!sensor && touching) {
        listener->PreSolve(this, &oldManifold);
        if (profile) ++profile->listenerCallbacks;
    }
}

}  // namespace lockbox
