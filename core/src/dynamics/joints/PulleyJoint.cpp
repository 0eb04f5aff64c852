// b2PulleyJoint solver (Box2D 2.2.1 b2PulleyJoint.cpp) with Q32.32 masses and impulses.
//
// C = constant - |pA - sA| - ratio * |pB - sB|; Cdot = -dot(uA, vpA) - ratio * dot(uB, vpB).
#include "lockbox/dynamics/joints/PulleyJoint.h"

#include "JointMath.h"

namespace lockbox {

using namespace jointmath;

namespace {
// A side shorter than 10 linearSlop (5 cm) has no reliable direction: Box2D zeroes it there,
// which keeps the effective mass finite when a body reaches its ground anchor.
constexpr Fixed kMinSideLength = Fixed::FromRaw(10 * 328);

// Normalises u in place when it is long enough, else zeroes it; returns the length (m).
Fixed UnitOrZero(b2Vec2& u) {
    const Fixed length = u.Length();
    if (length > kMinSideLength) {
        u.Normalize();
    } else {
        u.SetZero();
    }
    return length;
}
}  // namespace

void b2PulleyJointDef::Initialize(b2Body* bA, b2Body* bB, const b2Vec2& gA, const b2Vec2& gB, const b2Vec2& anchorA,
                                  const b2Vec2& anchorB, Fixed r) {
    bodyA = bA;
    bodyB = bB;
    groundAnchorA = gA;
    groundAnchorB = gB;
    localAnchorA = bodyA->GetLocalPoint(anchorA);
    localAnchorB = bodyB->GetLocalPoint(anchorB);
    lengthA = b2Distance(anchorA, gA);
    lengthB = b2Distance(anchorB, gB);
    ratio = r;
}

b2PulleyJoint::b2PulleyJoint(const b2PulleyJointDef* def) : b2Joint(def) {
    m_groundAnchorA = def->groundAnchorA;
    m_groundAnchorB = def->groundAnchorB;
    m_localAnchorA = def->localAnchorA;
    m_localAnchorB = def->localAnchorB;
    m_ratio = def->ratio;
    m_constant = def->lengthA + m_ratio * def->lengthB;
}

void b2PulleyJoint::InitVelocityConstraints(const b2SolverData& data) {
    [[maybe_unused]] auto [A, B, cA, aA, vA, wA, cB, aB, vB, wB] = BeginSolve(*this, data);

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    m_rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    m_rB = b2Mul(qB, m_localAnchorB - m_localCenterB);

    // Get the pulley axes.
    m_uA = cA + m_rA - m_groundAnchorA;
    m_uB = cB + m_rB - m_groundAnchorB;
    UnitOrZero(m_uA);
    UnitOrZero(m_uB);

    // Compute the effective mass.
    const Wide ruA = CrossW(m_rA, m_uA);
    const Wide ruB = CrossW(m_rB, m_uB);
    const Wide mA = m_invMassA + m_invIA * (ruA * ruA);
    const Wide mB = m_invMassB + m_invIB * (ruB * ruB);
    m_mass = Invert(mA + mB * MulWide(m_ratio, m_ratio));

    if (data.step.warmStarting) {
        m_impulse = WarmScaled(m_impulse, data.step.dtRatio);
        // Warm starting.
        const b2WideVec2 PA = -(m_impulse * m_uA);
        const b2WideVec2 PB = -((m_impulse * m_ratio) * m_uB);
        ApplyPos(vA, wA, A, m_rA, PA);
        ApplyPos(vB, wB, B, m_rB, PB);
    } else {
        m_impulse = Wide();
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

void b2PulleyJoint::SolveVelocityConstraints(const b2SolverData& data) {
    b2WideVec2 vA = data.velocities[m_indexA].v;
    Wide wA = data.velocities[m_indexA].w;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;

    const b2WideVec2 vpA = PointVelocity(vA, wA, m_rA);
    const b2WideVec2 vpB = PointVelocity(vB, wB, m_rB);

    const Wide Cdot = -DotW(m_uA, vpA) - DotW(m_uB, vpB) * m_ratio;
    const Wide impulse = -(m_mass * Cdot);
    m_impulse += impulse;

    const b2WideVec2 PA = -(impulse * m_uA);
    const b2WideVec2 PB = -((impulse * m_ratio) * m_uB);
    const BodyData A{m_indexA, m_localCenterA, m_invMassA, m_invIA};
    const BodyData B{m_indexB, m_localCenterB, m_invMassB, m_invIB};
    ApplyPos(vA, wA, A, m_rA, PA);
    ApplyPos(vB, wB, B, m_rB, PB);

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

bool b2PulleyJoint::SolvePositionConstraints(const b2SolverData& data) {
    b2Vec2 cA = data.positions[m_indexA].c;
    Fixed aA = data.positions[m_indexA].a;
    b2Vec2 cB = data.positions[m_indexB].c;
    Fixed aB = data.positions[m_indexB].a;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    const b2Vec2 rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    const b2Vec2 rB = b2Mul(qB, m_localAnchorB - m_localCenterB);

    b2Vec2 uA = cA + rA - m_groundAnchorA;
    b2Vec2 uB = cB + rB - m_groundAnchorB;
    const Fixed lengthA = UnitOrZero(uA);
    const Fixed lengthB = UnitOrZero(uB);

    const Wide ruA = CrossW(rA, uA);
    const Wide ruB = CrossW(rB, uB);
    const Wide mA = m_invMassA + m_invIA * (ruA * ruA);
    const Wide mB = m_invMassB + m_invIB * (ruB * ruB);
    const Wide mass = Invert(mA + mB * MulWide(m_ratio, m_ratio));

    const Fixed C = m_constant - lengthA - m_ratio * lengthB;
    const Fixed linearError = b2Abs(C);

    const Wide impulse = -(mass * C);
    const b2WideVec2 PA = -(impulse * uA);
    const b2WideVec2 PB = -((impulse * m_ratio) * uB);
    const BodyData A{m_indexA, m_localCenterA, m_invMassA, m_invIA};
    const BodyData B{m_indexB, m_localCenterB, m_invMassB, m_invIB};
    ApplyPos(cA, aA, A, rA, PA);
    ApplyPos(cB, aB, B, rB, PB);

    data.positions[m_indexA].c = cA;
    data.positions[m_indexA].a = aA;
    data.positions[m_indexB].c = cB;
    data.positions[m_indexB].a = aB;

    return linearError < b2_linearSlop;
}

b2Vec2 b2PulleyJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_localAnchorA); }
b2Vec2 b2PulleyJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2PulleyJoint::GetReactionForce(Fixed inv_dt) const {
    const Wide f = m_impulse * inv_dt;
    return {MulToFixed(f, m_uB.x), MulToFixed(f, m_uB.y)};
}

Fixed b2PulleyJoint::GetReactionTorque(Fixed) const { return Fixed(); }

Fixed b2PulleyJoint::GetLengthA() const { return b2Distance(m_bodyA->GetWorldPoint(m_localAnchorA), m_groundAnchorA); }
Fixed b2PulleyJoint::GetLengthB() const { return b2Distance(m_bodyB->GetWorldPoint(m_localAnchorB), m_groundAnchorB); }

}  // namespace lockbox
