// b2World's calls (World.h), each handed to the world's engine (dynamics/WorldState.h). The
// snapshot and frame calls live with the state code (state/Snapshot.cpp, state/WorldFrame.cpp).
#include <algorithm>

#include "dynamics/WorldState.h"
#include "lockbox/dynamics/World.h"

namespace lockbox {

b2World::b2World(const b2Vec2& gravity) : m_state(std::make_unique<State>(this, gravity)) {}

b2World::~b2World() = default;

void b2World::SetDestructionListener(b2DestructionListener* listener) noexcept {
    m_state->m_destructionListener = listener;
}
void b2World::SetContactFilter(b2ContactFilter* filter) noexcept { m_state->m_contactManager.m_contactFilter = filter; }
void b2World::SetContactListener(b2ContactListener* listener) noexcept {
    m_state->m_contactManager.m_contactListener = listener;
}
void b2World::SetBoundaryListener(b2BoundaryListener* listener) noexcept { m_state->m_boundaryListener = listener; }
void b2World::SetDebugDraw(b2Draw* debugDraw) noexcept { m_state->m_debugDraw = debugDraw; }

b2Body* b2World::CreateBody(const b2BodyDef* def) { return m_state->CreateBody(def); }
void b2World::DestroyBody(b2Body* body) { m_state->DestroyBody(body); }
b2Joint* b2World::CreateJoint(const b2JointDef* def) { return m_state->CreateJoint(def); }
void b2World::DestroyJoint(b2Joint* joint) { m_state->DestroyJoint(joint); }

void b2World::Step(Fixed timeStep, int32 velocityIterations, int32 positionIterations) {
    m_state->Step(timeStep, velocityIterations, positionIterations);
}
void b2World::ClearForces() { m_state->ClearForces(); }
void b2World::DrawDebugData() { m_state->DrawDebugData(); }

void b2World::QueryAABB(b2QueryCallback* callback, const b2AABB& aabb) const { m_state->QueryAABB(callback, aabb); }
void b2World::RayCast(b2RayCastCallback* callback, const b2Vec2& point1, const b2Vec2& point2) const {
    m_state->RayCast(callback, point1, point2);
}

b2Body* b2World::GetBodyList() noexcept { return m_state->m_bodyList; }
const b2Body* b2World::GetBodyList() const noexcept { return m_state->m_bodyList; }
b2Joint* b2World::GetJointList() noexcept { return m_state->m_jointList; }
const b2Joint* b2World::GetJointList() const noexcept { return m_state->m_jointList; }
b2Contact* b2World::GetContactList() noexcept { return m_state->m_contactManager.m_contactList; }
const b2Contact* b2World::GetContactList() const noexcept { return m_state->m_contactManager.m_contactList; }

b2Body* b2World::GetBody(int32 id) noexcept { return m_state->m_bodies.Get(id); }
b2Fixture* b2World::GetFixture(int32 id) noexcept { return m_state->m_fixtures.Get(id); }
b2Contact* b2World::GetContact(int32 id) noexcept { return m_state->m_contactManager.GetContact(id); }
b2Joint* b2World::GetJoint(int32 id) noexcept { return m_state->GetJoint(id); }

uint64 b2World::GetSaturationCount() const noexcept { return m_state->m_saturationCount; }

void b2World::SetWorkerCount(int32 count) {
    if (m_state->CheckLocked("b2World::SetWorkerCount called inside a Step callback (the world is locked)")) return;
    const int32 current = m_state->m_pool ? m_state->m_pool->GetWorkerCount() : 1;
    if (std::clamp(count, int32{1}, int32{64}) == current) return;
    m_state->m_pool.reset();
    if (count > 1) m_state->m_pool = std::make_unique<b2ThreadPool>(count);
}
int32 b2World::GetWorkerCount() const noexcept {
    const b2TaskSystem* tasks = m_state->Tasks();
    return tasks != nullptr ? tasks->GetWorkerCount() : 1;
}
void b2World::SetTaskSystem(b2TaskSystem* tasks) {
    if (m_state->CheckLocked("b2World::SetTaskSystem called inside a Step callback (the world is locked)")) return;
    m_state->m_userTasks = tasks;
}
b2TaskSystem* b2World::GetTaskSystem() const noexcept { return m_state->m_userTasks; }

void b2World::SetAllowSleeping(bool flag) { m_state->SetAllowSleeping(flag); }
bool b2World::GetAllowSleeping() const noexcept { return m_state->m_allowSleep; }
void b2World::SetWarmStarting(bool flag) noexcept { m_state->m_warmStarting = flag; }
bool b2World::GetWarmStarting() const noexcept { return m_state->m_warmStarting; }
void b2World::SetContinuousPhysics(bool flag) noexcept { m_state->m_continuousPhysics = flag; }
bool b2World::GetContinuousPhysics() const noexcept { return m_state->m_continuousPhysics; }
void b2World::SetPressedContactToi(bool flag) noexcept {
    if (flag)
        m_state->m_flags &= ~core_detail::Engine::World::e_skipPressedToi;
    else
        m_state->m_flags |= core_detail::Engine::World::e_skipPressedToi;
}
bool b2World::GetPressedContactToi() const noexcept {
    return (m_state->m_flags & core_detail::Engine::World::e_skipPressedToi) == 0;
}
void b2World::SetSubStepping(bool flag) noexcept { m_state->m_subStepping = flag; }
bool b2World::GetSubStepping() const noexcept { return m_state->m_subStepping; }
void b2World::SetAutoClearForces(bool flag) noexcept { m_state->m_autoClearForces = flag; }
bool b2World::GetAutoClearForces() const noexcept { return m_state->m_autoClearForces; }
void b2World::SetGravity(const b2Vec2& gravity) noexcept { m_state->m_gravity = gravity; }
b2Vec2 b2World::GetGravity() const noexcept { return m_state->m_gravity; }

void b2World::SetWorldBounds(const b2AABB& bounds) noexcept { m_state->m_bounds = bounds; }
const b2AABB& b2World::GetWorldBounds() const noexcept { return m_state->m_bounds; }

int32 b2World::GetProxyCount() const noexcept { return m_state->m_contactManager.m_broadPhase.GetProxyCount(); }
int32 b2World::GetBodyCount() const noexcept { return m_state->m_bodyCount; }
int32 b2World::GetJointCount() const noexcept { return m_state->m_jointCount; }
int32 b2World::GetContactCount() const noexcept { return m_state->m_contactManager.m_contactCount; }
bool b2World::IsLocked() const noexcept { return m_state->IsLocked(); }
const b2Profile& b2World::GetProfile() const noexcept { return m_state->m_profile; }
void b2World::SetHeadroomTelemetry(bool flag) noexcept { m_state->m_headroomTelemetry = flag; }
bool b2World::GetHeadroomTelemetry() const noexcept { return m_state->m_headroomTelemetry; }
void b2World::SetProfileTimers(bool flag) noexcept { m_state->m_profileTimers = flag; }
bool b2World::GetProfileTimers() const noexcept { return m_state->m_profileTimers; }
void b2World::SetStepObserver(b2StepObserver* observer) noexcept { m_state->m_stepObserver = observer; }
b2StepObserver* b2World::GetStepObserver() const noexcept { return m_state->m_stepObserver; }

}  // namespace lockbox
