// b2Fixture: shape ownership, broad-phase proxies and filtering.
#include "lockbox/dynamics/Fixture.h"

#include "dynamics/WorldState.h"
#include "lockbox/collision/BroadPhase.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox {

void b2Fixture::Create(b2Body* body, const b2FixtureDef* def, int32 id) {
    m_userData = def->userData;
    m_friction = def->friction;
    m_restitution = def->restitution;
    m_body = body;
    m_next = nullptr;
    m_filter = def->filter;
    m_isSensor = def->isSensor;
    m_shape = def->shape->Clone();
    m_id = id;
    // One proxy slot per child; they are filled only while the body is active.
    m_proxies.assign(static_cast<size_t>(m_shape->GetChildCount()), b2FixtureProxy{});
    for (b2FixtureProxy& proxy : m_proxies) {
        proxy.fixture = this;
        proxy.proxyId = b2BroadPhase::e_nullProxy;
    }
    m_proxyCount = 0;
    m_density = def->density;
}

void b2Fixture::CreateProxies(b2BroadPhase* broadPhase, const b2Transform& xf) {
    m_proxyCount = m_shape->GetChildCount();
    for (int32 i = 0; i < m_proxyCount; ++i) {
        b2FixtureProxy& proxy = m_proxies[static_cast<size_t>(i)];
        m_shape->ComputeAABB(&proxy.aabb, xf, i);
        proxy.proxyId = broadPhase->CreateProxy(proxy.aabb, b2FixtureProxy::MakeKey(m_id, i));
        proxy.fixture = this;
        proxy.childIndex = i;
    }
}

void b2Fixture::DestroyProxies(b2BroadPhase* broadPhase) {
    for (int32 i = 0; i < m_proxyCount; ++i) {
        b2FixtureProxy& proxy = m_proxies[static_cast<size_t>(i)];
        broadPhase->DestroyProxy(proxy.proxyId);
        proxy.proxyId = b2BroadPhase::e_nullProxy;
    }
    m_proxyCount = 0;
}

void b2Fixture::SweepProxy(b2FixtureProxy& proxy, const b2Transform& transform1, const b2Transform& transform2) const {
    // The swept AABB covers the child at the start and the end of the step.
    b2AABB aabb1;
    b2AABB aabb2;
    m_shape->ComputeAABB(&aabb1, transform1, proxy.childIndex);
    m_shape->ComputeAABB(&aabb2, transform2, proxy.childIndex);
    proxy.aabb.Combine(aabb1, aabb2);
}

void b2Fixture::Synchronize(b2BroadPhase* broadPhase, const b2Transform& transform1, const b2Transform& transform2) {
    const b2Vec2 displacement = transform2.p - transform1.p;
    for (int32 i = 0; i < m_proxyCount; ++i) {
        b2FixtureProxy& proxy = m_proxies[static_cast<size_t>(i)];
        SweepProxy(proxy, transform1, transform2);
        broadPhase->MoveProxy(proxy.proxyId, proxy.aabb, displacement);
    }
}

bool b2Fixture::SweepProxies(const b2BroadPhase& broadPhase, const b2Transform& transform1,
                             const b2Transform& transform2) {
    // A proxy's box depends on nothing a move changes (a move rewrites only its own proxy's fat
    // box), so boxes swept ahead and moved later give Synchronize's moves.
    bool left = false;
    for (int32 i = 0; i < m_proxyCount; ++i) {
        b2FixtureProxy& proxy = m_proxies[static_cast<size_t>(i)];
        SweepProxy(proxy, transform1, transform2);
        left = left || !broadPhase.GetFatAABB(proxy.proxyId).Contains(proxy.aabb);
    }
    return left;
}

void b2Fixture::MoveProxies(b2BroadPhase* broadPhase, const b2Vec2& displacement) {
    for (int32 i = 0; i < m_proxyCount; ++i) {
        const b2FixtureProxy& proxy = m_proxies[static_cast<size_t>(i)];
        broadPhase->MoveProxy(proxy.proxyId, proxy.aabb, displacement);
    }
}

namespace {
/// Fixture set-up is structure for rollback frames (lockbox/state/WorldFrame.h).
void MarkChanged(b2Body* body) noexcept {
    if (body != nullptr && body->GetWorld() != nullptr)
        core_detail::Engine::Of(*body->GetWorld()).MarkBodyStructureChanged(body->GetId());
}
}  // namespace

b2Shape* b2Fixture::EditShape() noexcept {
    MarkChanged(m_body);
    return m_shape.get();
}

void b2Fixture::SetSensor(bool sensor) noexcept {
    MarkChanged(m_body);
    const bool edit = sensor != m_isSensor && m_body != nullptr && m_body->GetWorld() != nullptr;
    m_isSensor = sensor;
    if (edit) core_detail::Engine::Of(*m_body->GetWorld()).NoteSensorEdit(*m_body);
}

void b2Fixture::SetUserData(uint64 data) noexcept {
    MarkChanged(m_body);
    m_userData = data;
}

void b2Fixture::SetDensity(Fixed density) noexcept {
    MarkChanged(m_body);
    m_density = density;
}

void b2Fixture::SetFriction(Fixed friction) noexcept {
    MarkChanged(m_body);
    m_friction = friction;
}

void b2Fixture::SetRestitution(Fixed restitution) noexcept {
    MarkChanged(m_body);
    m_restitution = restitution;
}

void b2Fixture::SetFilterData(const b2Filter& filter) {
    MarkChanged(m_body);
    m_filter = filter;
    if (m_body == nullptr) return;
    for (b2ContactEdge* edge = m_body->GetContactList(); edge; edge = edge->next) {
        b2Contact* contact = edge->contact;
        if (contact->GetFixtureA() == this || contact->GetFixtureB() == this) contact->FlagForFiltering();
    }
    b2World* world = m_body->GetWorld();
    if (world == nullptr) return;
    // Touching the proxies puts them in the move buffer, so pairs that the old filter
    // rejected are offered again at the next Step.
    b2BroadPhase* broadPhase = &core_detail::Engine::Of(*world).m_contactManager.m_broadPhase;
    for (int32 i = 0; i < m_proxyCount; ++i) broadPhase->TouchProxy(m_proxies[static_cast<size_t>(i)].proxyId);
}

bool b2Fixture::TestPoint(const b2Vec2& p) const { return m_shape->TestPoint(m_body->GetTransform(), p); }

bool b2Fixture::RayCast(b2RayCastOutput* output, const b2RayCastInput& input, int32 childIndex) const {
    return m_shape->RayCast(output, input, m_body->GetTransform(), childIndex);
}

void b2Fixture::GetMassData(b2MassData* massData) const { m_shape->ComputeMass(massData, m_density); }

}  // namespace lockbox
