// b2Body: construction, fixtures, mass, transforms, forces and state flags.
#include "lockbox/dynamics/Body.h"

#include "dynamics/WorldState.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joint.h"

namespace lockbox {

using core_detail::Engine;

b2Body::b2Body(const b2BodyDef* bd, b2World* world, int32 id) : m_type(bd->type), m_world(world), m_id(id) {
    if (bd->bullet) m_flags |= e_bulletFlag;
    if (bd->fixedRotation) m_flags |= e_fixedRotationFlag;
    if (bd->allowSleep) m_flags |= e_autoSleepFlag;
    if (bd->awake) m_flags |= e_awakeFlag;
    if (bd->active) m_flags |= e_activeFlag;

    m_xf.p = bd->position;
    m_xf.q.Set(bd->angle);
    m_sweep.localCenter.SetZero();
    m_sweep.c0 = m_xf.p;
    m_sweep.c = m_xf.p;
    m_sweep.a0 = bd->angle;
    m_sweep.a = bd->angle;
    m_sweep.alpha0 = 0;

    m_linearVelocity = bd->linearVelocity;
    m_angularVelocity = bd->angularVelocity;
    m_linearDamping = bd->linearDamping;
    m_angularDamping = bd->angularDamping;
    m_gravityScale = bd->gravityScale;
    m_userData = bd->userData;

    if (m_type == b2_dynamicBody) {
        m_mass = 1;
        m_invMass = 1;
    }
}

b2Fixture* b2Body::CreateFixture(const b2FixtureDef* def) {
    if (Engine::Of(*m_world).CheckLocked("b2Body::CreateFixture")) return nullptr;
    return Engine::Of(*m_world).CreateFixture(this, def);
}

b2Fixture* b2Body::CreateFixture(const b2Shape* shape, Fixed density) {
    b2FixtureDef def;
    def.shape = shape;
    def.density = density;
    return CreateFixture(&def);
}

void b2Body::DestroyFixture(b2Fixture* fixture) {
    if (Engine::Of(*m_world).CheckLocked("b2Body::DestroyFixture")) return;
    if (fixture == nullptr || fixture->GetBody() != this) return;
    Engine::Of(*m_world).DestroyFixture(fixture);
}

Wide b2Body::GetInertia() const noexcept { return m_I + m_mass * b2DotWide(m_sweep.localCenter, m_sweep.localCenter); }

void b2Body::GetMassData(b2MassData* data) const {
    data->mass = m_mass;
    data->I = GetInertia();
    data->center = m_sweep.localCenter;
}

void b2Body::ResetMassData() {
    Engine::Of(*m_world).MarkBodyStructureChanged(m_id);
    m_mass = Wide();
    m_invMass = Wide();
    m_I = Wide();
    m_invI = Wide();
    m_sweep.localCenter.SetZero();

    if (m_type == b2_staticBody || m_type == b2_kinematicBody) {
        m_sweep.c0 = m_xf.p;
        m_sweep.c = m_xf.p;
        m_positionRemainder = {};
        m_sweep.a0 = m_sweep.a;
        UpdateExtents();
        return;
    }

    // First moments accumulate in Q32.32 so the centre is divided out with one rounding.
    Wide momentX;
    Wide momentY;
    for (b2Fixture* f = m_fixtureList; f; f = f->GetNext()) {
        if (f->GetDensity() == Fixed()) continue;
        b2MassData massData;
        f->GetMassData(&massData);
        m_mass += massData.mass;
        momentX += massData.mass * massData.center.x;
        momentY += massData.mass * massData.center.y;
        m_I += massData.I;
    }

    b2Vec2 localCenter;
    if (m_mass > Wide()) {
        m_invMass = Wide(1) / m_mass;
        localCenter.Set((momentX / m_mass).ToFixed(), (momentY / m_mass).ToFixed());
    } else {
        // Force all dynamic bodies to have a positive mass (the manual's 1 kg fallback).
        m_mass = 1;
        m_invMass = 1;
    }

    if (m_I > Wide() && (m_flags & e_fixedRotationFlag) == 0) {
        // Move the inertia from the body origin to the centre of mass.
        m_I -= m_mass * b2DotWide(localCenter, localCenter);
        if (m_I > Wide()) {
            m_invI = Wide(1) / m_I;
        } else {
            m_I = Wide();
        }
    } else {
        m_I = Wide();
        m_invI = Wide();
    }

    const b2Vec2 oldCenter = m_sweep.c;
    m_sweep.localCenter = localCenter;
    m_sweep.c = b2Mul(m_xf, m_sweep.localCenter);
    m_sweep.c0 = m_sweep.c;
    m_positionRemainder = {};
    // Keep the velocity of the origin: the centre of mass moved.
    m_linearVelocity += b2Cross(m_angularVelocity, m_sweep.c - oldCenter);
    UpdateExtents();
}

void b2Body::SetMassData(const b2MassData* massData) {
    if (Engine::Of(*m_world).CheckLocked("b2Body::SetMassData")) return;
    Engine::Of(*m_world).MarkBodyStructureChanged(m_id);
    if (m_type != b2_dynamicBody) return;

    m_invMass = Wide();
    m_I = Wide();
    m_invI = Wide();

    m_mass = massData->mass;
    if (m_mass <= Wide()) m_mass = 1;
    m_invMass = Wide(1) / m_mass;

    if (massData->I > Wide() && (m_flags & e_fixedRotationFlag) == 0) {
        m_I = massData->I - m_mass * b2DotWide(massData->center, massData->center);
        if (m_I > Wide()) {
            m_invI = Wide(1) / m_I;
        } else {
            m_I = Wide();
        }
    }

    const b2Vec2 oldCenter = m_sweep.c;
    m_sweep.localCenter = massData->center;
    m_sweep.c = b2Mul(m_xf, m_sweep.localCenter);
    m_sweep.c0 = m_sweep.c;
    m_positionRemainder = {};
    m_linearVelocity += b2Cross(m_angularVelocity, m_sweep.c - oldCenter);
    UpdateExtents();
}

bool b2Body::ShouldCollide(const b2Body* other) const {
    // At least one body must be dynamic.
    if (m_type != b2_dynamicBody && other->m_type != b2_dynamicBody) return false;
    for (const b2JointEdge* jn = m_jointList; jn; jn = jn->next) {
        if (jn->other == other && !jn->joint->GetCollideConnected()) return false;
    }
    return true;
}

void b2Body::SetTransform(const b2Vec2& position, Fixed angle) {
    if (Engine::Of(*m_world).CheckLocked("b2Body::SetTransform")) return;
    m_xf.q.Set(angle);
    m_xf.p = position;
    m_sweep.c = b2Mul(m_xf, m_sweep.localCenter);
    m_sweep.a = angle;
    m_sweep.c0 = m_sweep.c;
    m_positionRemainder = {};
    m_sweep.a0 = angle;
    Engine::World& world = Engine::Of(*m_world);
    world.SynchronizeFixtures(*this, m_xf, m_xf);
    world.m_contactManager.FindNewContacts();
}

void b2Body::SynchronizeTransform() {
    m_xf.q.Set(m_sweep.a);
    m_xf.p = m_sweep.c - b2Mul(m_xf.q, m_sweep.localCenter);
}

void b2Body::Advance(Fixed alpha) {
    // Advance to the new safe time. This doesn't sync the broad phase.
    m_sweep.Advance(alpha);
    m_sweep.c = m_sweep.c0;
    m_sweep.a = m_sweep.a0;
    m_positionRemainder = {};
    SynchronizeTransform();
}

void b2Body::WrapAngle() noexcept {
    // The Q16.16 2*pi (raw 411775) is 0.17 ULP off the true value. Subtracting the same whole
    // number of these turns from a and a0 keeps a - a0 (the step's rotation) exact; the
    // transform is rebuilt from the wrapped angle at the next synchronisation, so the
    // orientation moves by at most k * 0.4e-5 rad for k removed turns (once per turn).
    constexpr int32 kPiRaw = 205887;
    constexpr int32 kTwoPiRaw = 411775;
    const int32 a = m_sweep.a.Raw();
    if (a >= -kPiRaw && a < kPiRaw) return;
    const int64_t shifted = int64_t{a} + kPiRaw;
    int64_t turns = shifted / kTwoPiRaw;
    if (shifted - turns * kTwoPiRaw < 0) --turns;  // floor division
    const Fixed d = Fixed::FromRaw(static_cast<int32>(turns * kTwoPiRaw));
    m_sweep.a -= d;
    m_sweep.a0 -= d;
}

void b2Body::SetType(b2BodyType type) {
    if (Engine::Of(*m_world).CheckLocked("b2Body::SetType")) return;
    if (m_type == type) return;
    m_type = type;
    ResetMassData();  // marks the world's structure changed
    if (m_type == b2_staticBody) {
        m_linearVelocity.SetZero();
        m_angularVelocity = Fixed();
        m_velocityRemainder = {};
        m_sweep.a0 = m_sweep.a;
        m_sweep.c0 = m_sweep.c;
        Engine::Of(*m_world).SynchronizeFixtures(*this);
    }
    SetAwake(true);
    m_force.SetZero();
    m_torque = Fixed();
    // The type rule may now accept or reject existing pairs.
    for (b2ContactEdge* ce = m_contactList; ce; ce = ce->next) ce->contact->FlagForFiltering();
    Engine::Of(*m_world).NoteToiBodiesEdit(*this);
}

// Set-up fields that rollback frames share through the structure image: each setter marks
// the world's structure changed.
void b2Body::SetLinearDamping(Fixed d) noexcept {
    Engine::Of(*m_world).MarkBodyStructureChanged(m_id);
    m_linearDamping = d;
}

void b2Body::SetAngularDamping(Fixed d) noexcept {
    Engine::Of(*m_world).MarkBodyStructureChanged(m_id);
    m_angularDamping = d;
}

void b2Body::SetGravityScale(Fixed s) noexcept {
    Engine::Of(*m_world).MarkBodyStructureChanged(m_id);
    m_gravityScale = s;
}

void b2Body::SetUserData(uint64 data) noexcept {
    Engine::Of(*m_world).MarkBodyStructureChanged(m_id);
    m_userData = data;
}

void b2Body::SetBullet(bool flag) noexcept {
    const bool edit = flag != IsBullet();
    if (flag)
        m_flags |= e_bulletFlag;
    else
        m_flags &= ~e_bulletFlag;
    if (edit) Engine::Of(*m_world).NoteToiBodiesEdit(*this);
}

void b2Body::SetSleepingAllowed(bool flag) {
    if (flag) {
        m_flags |= e_autoSleepFlag;
    } else {
        m_flags &= ~e_autoSleepFlag;
        SetAwake(true);
    }
}

void b2Body::SetAwake(bool flag) {
    if (flag) {
        if ((m_flags & e_awakeFlag) == 0) {
            m_flags |= e_awakeFlag;
            m_sleepSteps = 0;
        }
    } else {
        m_flags &= ~e_awakeFlag;
        m_sleepSteps = 0;
        m_linearVelocity.SetZero();
        m_angularVelocity = Fixed();
        m_velocityRemainder = {};
        m_force.SetZero();
        m_torque = Fixed();
    }
}

void b2Body::SetActive(bool flag) {
    if (Engine::Of(*m_world).CheckLocked("b2Body::SetActive")) return;
    if (flag == IsActive()) return;
    // Proxies are made or dropped: a structural change for rollback frames.
    Engine::World& world = Engine::Of(*m_world);
    world.MarkBodyStructureChanged(m_id);
    if (flag) {
        m_flags |= e_activeFlag;
        m_flags &= ~e_outOfBoundsFlag;
        world.CreateProxies(*this);
        // Contacts are created at the next Step.
        world.m_flags |= Engine::World::e_newFixture;
    } else {
        m_flags &= ~e_activeFlag;
        world.DestroyProxies(*this);
        b2ContactEdge* ce = m_contactList;
        while (ce) {
            b2ContactEdge* ce0 = ce;
            ce = ce->next;
            world.m_contactManager.Destroy(ce0->contact);
        }
        m_contactList = nullptr;
    }
}

void b2Body::SetFixedRotation(bool flag) {
    if (flag)
        m_flags |= e_fixedRotationFlag;
    else
        m_flags &= ~e_fixedRotationFlag;
    ResetMassData();
}

void b2Body::SetLinearVelocity(const b2Vec2& v) {
    if (m_type == b2_staticBody) return;
    if (v.LengthSquaredWide() > Wide()) SetAwake(true);
    m_linearVelocity = v;
    m_velocityRemainder.x = 0;
    m_velocityRemainder.y = 0;
}

void b2Body::SetAngularVelocity(Fixed w) {
    if (m_type == b2_staticBody) return;
    if (w != Fixed()) SetAwake(true);
    m_angularVelocity = w;
    m_velocityRemainder.w = 0;
}

void b2Body::ApplyForce(const b2Vec2& force, const b2Vec2& point) {
    if (m_type != b2_dynamicBody) return;
    if (!IsAwake()) SetAwake(true);
    Engine::Of(*m_world).m_forcesApplied = true;
    m_force += force;
    m_torque += b2Cross(point - m_sweep.c, force);
}

void b2Body::ApplyForceToCenter(const b2Vec2& force) {
    if (m_type != b2_dynamicBody) return;
    if (!IsAwake()) SetAwake(true);
    Engine::Of(*m_world).m_forcesApplied = true;
    m_force += force;
}

void b2Body::ApplyTorque(Fixed torque) {
    if (m_type != b2_dynamicBody) return;
    if (!IsAwake()) SetAwake(true);
    Engine::Of(*m_world).m_forcesApplied = true;
    m_torque += torque;
}

void b2Body::ApplyLinearImpulse(const b2Vec2& impulse, const b2Vec2& point) {
    if (m_type != b2_dynamicBody) return;
    if (!IsAwake()) SetAwake(true);
    // The velocity changes are added in Q32.32, so an impulse below the Q16.16 quantum counts.
    b2Velocity v = SolverVelocity();
    v.v.x += m_invMass * impulse.x;
    v.v.y += m_invMass * impulse.y;
    v.w += m_invI * b2CrossWide(point - m_sweep.c, impulse);
    SetSolverVelocity(v);
}

void b2Body::ApplyAngularImpulse(Fixed impulse) {
    if (m_type != b2_dynamicBody) return;
    if (!IsAwake()) SetAwake(true);
    b2Velocity v = SolverVelocity();
    v.w += m_invI * impulse;
    SetSolverVelocity(v);
}

namespace {
// Splits a Q32.32 value into its Q16.16 rounding and the remainder below it. A value beyond
// Q16.16 saturates (reported by ToFixed) and keeps no remainder.
Fixed Split(Wide value, int32& remainder) noexcept {
    const Fixed rounded = value.ToFixed();
    const int64_t rest = value.Raw() - int64_t{rounded.Raw()} * (int64_t{1} << 16);
    constexpr int64_t kHalf = int64_t{1} << 15;
    remainder = rest >= -kHalf && rest <= kHalf ? static_cast<int32>(rest) : 0;
    return rounded;
}

Wide Join(Fixed rounded, int32 remainder) noexcept { return Wide::FromRaw(Wide(rounded).Raw() + remainder); }
}  // namespace

b2Velocity b2Body::SolverVelocity() const noexcept {
    return {{Join(m_linearVelocity.x, m_velocityRemainder.x), Join(m_linearVelocity.y, m_velocityRemainder.y)},
            Join(m_angularVelocity, m_velocityRemainder.w)};
}

void b2Body::Displace(Wide dx, Wide dy, Wide da, b2Vec2& c, Fixed& a) noexcept {
    c.x += Split(dx + Wide::FromRaw(m_positionRemainder.x), m_positionRemainder.x);
    c.y += Split(dy + Wide::FromRaw(m_positionRemainder.y), m_positionRemainder.y);
    a += Split(da + Wide::FromRaw(m_positionRemainder.w), m_positionRemainder.w);
}

void b2Body::SetSolverVelocity(const b2Velocity& v) noexcept {
    m_linearVelocity.x = Split(v.v.x, m_velocityRemainder.x);
    m_linearVelocity.y = Split(v.v.y, m_velocityRemainder.y);
    m_angularVelocity = Split(v.w, m_velocityRemainder.w);
}

b2Vec2 b2Body::GetLinearVelocityFromWorldPoint(const b2Vec2& worldPoint) const {
    return m_linearVelocity + b2Cross(m_angularVelocity, worldPoint - m_sweep.c);
}

b2Vec2 b2Body::GetLinearVelocityFromLocalPoint(const b2Vec2& localPoint) const {
    return GetLinearVelocityFromWorldPoint(GetWorldPoint(localPoint));
}

}  // namespace lockbox
