// The world's engine (Engine::World): lifetime of bodies and fixtures, the step driver,
// switches and the assert handler.
#include "lockbox/dynamics/World.h"

#include "dynamics/ProfileTimer.h"
#include "dynamics/WorldState.h"
#include "dynamics/joints/JointAccess.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox {

using core_detail::StageTimer;
using World = core_detail::Engine::World;
using Joints = core_detail::Engine::Joints;

World::World(b2World* owner, const b2Vec2& gravity)
    : m_owner(owner), m_contactManager(&m_fixtures), m_gravity(gravity) {
    m_bounds.lowerBound.Set(-b2_defaultWorldExtent, -b2_defaultWorldExtent);
    m_bounds.upperBound.Set(b2_defaultWorldExtent, b2_defaultWorldExtent);
}

World::~World() {
    // Joints are heap objects owned by the world (bodies and fixtures live in pools).
    b2Joint* j = m_jointList;
    while (j) {
        b2Joint* next = j->m_next;
        Joints::Destroy(j);
        j = next;
    }
}

void World::MarkBodyStructureChanged(int32 bodyId) noexcept {
    m_frames.LogStructureChange({0, bodyId, b2_nullId, b2_nullId});
}

void World::NoteSensorEdit(b2Body& body) noexcept {
    NoteToiFilterEdit();
    for (b2ContactEdge* ce = body.m_contactList; ce; ce = ce->next)
        ce->contact->m_sensor = ce->contact->SensorPairNow();
}

void World::NoteToiBodiesEdit(b2Body& body) noexcept {
    NoteToiFilterEdit();
    for (b2ContactEdge* ce = body.m_contactList; ce; ce = ce->next) {
        b2Contact* c = ce->contact;
        const bool marked = b2Contact::ToiBodies(body, *ce->other);
        if (marked == c->m_toiBodies) continue;
        b2ContactManager::CountToiMark(*c, -1);  // counted with the old mark, then the new
        c->m_toiBodies = marked;
        b2ContactManager::CountToiMark(*c, 1);
    }
}

void World::MarkJointStructureChanged(const b2Joint& joint) noexcept {
    m_frames.LogStructureChange({0, joint.m_bodyA->GetId(), joint.m_bodyB->GetId(), joint.GetId()});
    m_jointGraph.Invalidate();
}

bool World::CheckLocked(const char* what) const {
    if (!IsLocked()) return false;
    LOCKBOX_ASSERT(!IsLocked(), what);
    // Refused (release builds, or a handler that returned): the caller returns nullptr or does
    // nothing.
    return true;
}

b2Body* World::CreateBody(const b2BodyDef* def) {
    if (CheckLocked("b2World::CreateBody called inside a Step callback (the world is locked)")) return nullptr;
    const int32 id = m_bodies.Create(def, m_owner, b2_nullId);
    MarkBodyStructureChanged(id);
    b2Body* b = m_bodies.Get(id);
    b->m_id = id;

    // Newest first, as 2.2.1.
    b->m_listKey = m_bodyList != nullptr ? m_bodyList->m_listKey - 1 : 0;
    b->m_prev = nullptr;
    b->m_next = m_bodyList;
    if (m_bodyList) m_bodyList->m_prev = b;
    m_bodyList = b;
    ++m_bodyCount;
    return b;
}

void World::DestroyBody(b2Body* b) {
    if (CheckLocked("b2World::DestroyBody called inside a Step callback (the world is locked)")) return;
    if (b == nullptr) return;
    MarkBodyStructureChanged(b->GetId());

    // Delete the attached joints (and any gear coupling them), telling the listener. The list
    // head is re-read each time: destroying a gear may unlink other edges of this body.
    while (b->m_jointList) {
        b2Joint* j = b->m_jointList->joint;
        if (m_destructionListener) m_destructionListener->SayGoodbye(j);
        DestroyJoint(j);
    }

    // Delete the attached contacts.
    b2ContactEdge* ce = b->m_contactList;
    while (ce) {
        b2ContactEdge* ce0 = ce;
        ce = ce->next;
        m_contactManager.Destroy(ce0->contact);
    }
    b->m_contactList = nullptr;

    // Delete the attached fixtures; this destroys their broad-phase proxies.
    b2Fixture* f = b->m_fixtureList;
    while (f) {
        b2Fixture* f0 = f;
        f = f->m_next;
        if (m_destructionListener) m_destructionListener->SayGoodbye(f0);
        f0->DestroyProxies(&m_contactManager.m_broadPhase);
        m_fixtures.Destroy(f0->GetId());
        b->m_fixtureList = f;
        b->m_fixtureCount -= 1;
    }
    b->m_fixtureList = nullptr;
    b->m_fixtureCount = 0;

    // Remove from the world list.
    if (b->m_prev) b->m_prev->m_next = b->m_next;
    if (b->m_next) b->m_next->m_prev = b->m_prev;
    if (b == m_bodyList) m_bodyList = b->m_next;
    --m_bodyCount;
    m_bodies.Destroy(b->GetId());
}

b2Fixture* World::CreateFixture(b2Body* body, const b2FixtureDef* def) {
    if (def == nullptr || def->shape == nullptr) {
        LOCKBOX_ASSERT(def != nullptr && def->shape != nullptr, "b2Body::CreateFixture needs a shape");
        return nullptr;
    }
    MarkBodyStructureChanged(body->GetId());
    const int32 id = m_fixtures.Create();
    b2Fixture* fixture = m_fixtures.Get(id);
    fixture->Create(body, def, id);
    if (body->IsActive()) fixture->CreateProxies(&m_contactManager.m_broadPhase, body->m_xf);

    fixture->m_next = body->m_fixtureList;
    body->m_fixtureList = fixture;
    ++body->m_fixtureCount;

    if (fixture->m_density > Fixed()) body->ResetMassData();
    body->UpdateExtents();

    // New contacts are found at the beginning of the next Step.
    m_flags |= e_newFixture;
    return fixture;
}

void World::DestroyFixture(b2Fixture* fixture) {
    b2Body* body = fixture->m_body;
    MarkBodyStructureChanged(body->GetId());

    // Unlink from the body's singly linked list.
    b2Fixture** node = &body->m_fixtureList;
    while (*node != nullptr) {
        if (*node == fixture) {
            *node = fixture->m_next;
            break;
        }
        node = &(*node)->m_next;
    }

    // Destroy any contacts of this fixture.
    b2ContactEdge* edge = body->m_contactList;
    while (edge) {
        b2Contact* c = edge->contact;
        edge = edge->next;
        if (c->GetFixtureA() == fixture || c->GetFixtureB() == fixture) m_contactManager.Destroy(c);
    }

    if (body->IsActive()) fixture->DestroyProxies(&m_contactManager.m_broadPhase);
    m_fixtures.Destroy(fixture->GetId());
    --body->m_fixtureCount;
    body->ResetMassData();
}

void World::SynchronizeFixtures(b2Body& body, const b2Transform& xf1, const b2Transform& xf2) {
    b2BroadPhase* broadPhase = &m_contactManager.m_broadPhase;
    for (b2Fixture* f = body.m_fixtureList; f; f = f->m_next) f->Synchronize(broadPhase, xf1, xf2);
}

b2Transform World::SweepStart(const b2Body& body) noexcept {
    b2Transform xf;
    xf.q.Set(body.m_sweep.a0);
    xf.p = body.m_sweep.c0 - b2Mul(xf.q, body.m_sweep.localCenter);
    return xf;
}

void World::SynchronizeFixtures(b2Body& body) { SynchronizeFixtures(body, SweepStart(body), body.m_xf); }

void World::CreateProxies(b2Body& body) {
    for (b2Fixture* f = body.m_fixtureList; f; f = f->m_next)
        f->CreateProxies(&m_contactManager.m_broadPhase, body.m_xf);
}

void World::DestroyProxies(b2Body& body) {
    for (b2Fixture* f = body.m_fixtureList; f; f = f->m_next) f->DestroyProxies(&m_contactManager.m_broadPhase);
}

void World::SetAllowSleeping(bool flag) {
    if (flag == m_allowSleep) return;
    m_allowSleep = flag;
    if (!m_allowSleep) {
        for (b2Body* b = m_bodyList; b; b = b->m_next) b->SetAwake(true);
    }
}

void World::ClearForces() {
    if (!m_forcesApplied) {
#ifndef NDEBUG
        m_bodies.ForEachLive([](const b2Body& b) {
            LOCKBOX_ASSERT(b.m_force == b2Vec2_zero && b.m_torque == Fixed(), "a force was set unnoticed");
        });
#endif
        return;
    }
    // By slot: memory order, and the order of zeroing does not matter.
    m_bodies.ForEachLive([](b2Body& b) {
        b.m_force.SetZero();
        b.m_torque = Fixed();
    });
    m_forcesApplied = false;
}

void World::Step(Fixed dt, int32 velocityIterations, int32 positionIterations) {
    const bool timers = m_profileTimers;
    const StageTimer stepTimer(timers);
    const uint64 saturationsBefore = SaturationCount();
    m_profile = b2Profile{};
    // Counters record the work of this Step only (not of SetTransform or DestroyBody calls
    // made between steps).
    m_contactManager.m_profile = &m_profile;

    // New fixtures need their pairs before the narrow phase.
    if (m_flags & e_newFixture) {
        m_contactManager.FindNewContacts();
        m_flags &= ~e_newFixture;
    }

    m_flags |= e_locked;

    b2TimeStep step;
    step.dt = dt;
    step.velocityIterations = velocityIterations;
    step.positionIterations = positionIterations;
    // inv_dt is 1/dt in Q16.16, so dtRatio = inv_dt0 * dt is exactly 1 for a fixed step
    // (NUMERICS Table 4), unlike an exact 60 which gives 65520 raw.
    step.inv_dt = dt > Fixed() ? Fixed(1) / dt : Fixed();
    step.dtRatio = m_inv_dt0 * dt;
    step.warmStarting = m_warmStarting;
    step.timers = timers;
    if (dt > Fixed()) {
        // round(timeToSleep / dt) whole steps: 30 at 60 Hz, as float Box2D sleeps.
        const int64_t n = (2 * int64_t{b2_timeToSleep.Raw()} + dt.Raw()) / (2 * int64_t{dt.Raw()});
        step.stepsToSleep = n < 1 ? 1 : static_cast<int32>(n);
    }

    // Update contacts: this is where some contacts are destroyed.
    {
        const StageTimer timer(timers);
        m_contactManager.Collide(Tasks(), MinParallelContacts());
        m_profile.collideNs = timer.Nanos();
    }
    if (m_stepObserver != nullptr) m_stepObserver->OnStage(b2StepStage::e_collide, *m_owner);

    // Integrate velocities, solve velocity constraints, integrate positions.
    if (m_stepComplete && step.dt > Fixed()) {
        const StageTimer timer(timers);
        Solve(step);
        m_profile.solveNs = timer.Nanos();
    }

    // Handle TOI events.
    if (m_continuousPhysics && step.dt > Fixed()) {
        const StageTimer timer(timers);
        SolveTOI(step);
        m_profile.solveTOINs = timer.Nanos();
        if (m_stepObserver != nullptr) m_stepObserver->OnStage(b2StepStage::e_solveTOI, *m_owner);
    }

    if (step.dt > Fixed()) m_inv_dt0 = step.inv_dt;

    if (m_autoClearForces) ClearForces();

    // Take escaped bodies out while still locked (EndContact may fire), then report them.
    EnforceBounds();

    m_flags &= ~e_locked;

    if (m_boundaryListener != nullptr) {
        // The world is unlocked: a handler may destroy or revive the body it is given (but
        // should not destroy other reported bodies before they are reported).
        std::vector<b2Body*> escaped;
        escaped.swap(m_outOfBounds);
        for (b2Body* b : escaped) {
            m_boundaryListener->Violation(b);
            ++m_profile.listenerCallbacks;
        }
    }
    m_outOfBounds.clear();
    m_contactManager.m_profile = nullptr;
    m_saturationCount += SaturationCount() - saturationsBefore;
    if (m_headroomTelemetry) {
        // Read the step's count before the walk, so the walk itself can never add to it.
        const int64_t stepSaturations = static_cast<int64_t>(SaturationCount() - saturationsBefore);
        m_profile.headroom = b2MeasureHeadroom(*m_owner);
        m_profile.headroom.saturations = stepSaturations;
    }
    m_profile.stepNs = stepTimer.Nanos();
}

bool World::IsOutside(const b2Body* b) const noexcept {
    const b2Vec2& c = b->m_sweep.c;
    return c.x < m_bounds.lowerBound.x || c.y < m_bounds.lowerBound.y || c.x > m_bounds.upperBound.x ||
           c.y > m_bounds.upperBound.y;
}

void World::EnforceBounds() {
    if (m_outOfBounds.empty()) return;
    // The candidates were pushed in body-list order by the solver; drop duplicates and bodies
    // that came back inside within the step (TOI).
    std::vector<b2Body*> taken;
    for (b2Body* b : m_outOfBounds) {
        if (b->IsOutOfBounds() || !b->IsActive() || !IsOutside(b)) continue;
        // Out of the simulation: no proxies, no contacts, no motion. The body keeps its
        // transform so the application can inspect it or move it back.
        m_flags &= ~e_locked;
        b->SetActive(false);
        m_flags |= e_locked;
        b->m_flags |= b2Body::e_outOfBoundsFlag;
        b->SetSolverVelocity({});
        b->m_force.SetZero();
        b->m_torque = Fixed();
        b->m_sweep.c0 = b->m_sweep.c;
        b->m_sweep.a0 = b->m_sweep.a;
        ++m_profile.boundsViolations;
        taken.push_back(b);
    }
    m_outOfBounds.swap(taken);
}

}  // namespace lockbox
