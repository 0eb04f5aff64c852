// b2DistanceJoint solver (Box2D 2.2.1 b2DistanceJoint.cpp) with Q32.32 masses and impulses.
//
// 1-D constraint C = |pB - pA| - L along the unit axis u; the soft version adds gamma and a
// bias velocity (Catto's soft step), see JointMath.h.
#include "lockbox/dynamics/joints/DistanceJoint.h"

#include "JointMath.h"

namespace lockbox {

using namespace jointmath;

void b2DistanceJointDef::Initialize(b2Body* b1, b2Body* b2, const b2Vec2& anchor1, const b2Vec2& anchor2) {
    bodyA = b1;
    bodyB = b2;
    localAnchorA = bodyA->GetLocalPoint(anchor1);
    localAnchorB = bodyB->GetLocalPoint(anchor2);
    length = b2Distance(anchor2, anchor1);
}

b2DistanceJoint::b2DistanceJoint(const b2DistanceJointDef* def) : b2Joint(def) {
    m_localAnchorA = def->localAnchorA;
    m_localAnchorB = def->localAnchorB;
    m_length = def->length;
    m_frequencyHz = def->frequencyHz;
    m_dampingRatio = def->dampingRatio;
}

void b2DistanceJoint::InitVelocityConstraints(const b2SolverData& data) {
    [[maybe_unused]] auto [A, B, cA, aA, vA, wA, cB, aB, vB, wB] = BeginSolve(*this, data);

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    m_rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    m_rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    m_u = cB + m_rB - cA - m_rA;

    // Below linearSlop the direction is noise: Box2D zeroes the axis there (the constraint
    // then does nothing this step).
    const Fixed length = m_u.Normalize();
    if (length <= b2_linearSlop) m_u.SetZero();

    const Wide crAu = CrossW(m_rA, m_u);
    const Wide crBu = CrossW(m_rB, m_u);
    Wide invMass = m_invMassA + m_invIA * (crAu * crAu) + m_invMassB + m_invIB * (crBu * crBu);
    m_mass = Invert(invMass);

    if (m_frequencyHz > Fixed()) {
        const Fixed C = length - m_length;
        const Soft soft = SoftCoefficients(m_mass, m_frequencyHz, m_dampingRatio, data.step.dt);
        m_gamma = soft.gamma;
        m_bias = soft.biasRate * C;
        invMass += m_gamma;
        m_mass = Invert(invMass);
    } else {
        m_gamma = Wide();
        m_bias = Wide();
    }

    if (data.step.warmStarting) {
        // Scale the impulse to support a variable time step.
        m_impulse = WarmScaled(m_impulse, data.step.dtRatio);
        const b2WideVec2 P = m_impulse * m_u;
        ApplyNeg(vA, wA, A, m_rA, P);
        ApplyPos(vB, wB, B, m_rB, P);
    } else {
        m_impulse = Wide();
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

void b2DistanceJoint::SolveVelocityConstraints(const b2SolverData& data) {
    b2WideVec2 vA = data.velocities[m_indexA].v;
    Wide wA = data.velocities[m_indexA].w;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;

    // Cdot = dot(u, v_pB - v_pA)
    const Wide Cdot = DotW(m_u, PointVelocity(vB, wB, m_rB) - PointVelocity(vA, wA, m_rA));

    const Wide impulse = -(m_mass * (Cdot + m_bias + m_gamma * m_impulse));
    m_impulse += impulse;

    const b2WideVec2 P = impulse * m_u;
    const BodyData A{m_indexA, m_localCenterA, m_invMassA, m_invIA};
    const BodyData B{m_indexB, m_localCenterB, m_invMassB, m_invIB};
    ApplyNeg(vA, wA, A, m_rA, P);
    ApplyPos(vB, wB, B, m_rB, P);

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

bool b2DistanceJoint::SolvePositionConstraints(const b2SolverData& data) {
    // A soft joint is only a spring: no position correction.
    if (m_frequencyHz > Fixed()) return true;

    b2Vec2 cA = data.positions[m_indexA].c;
    Fixed aA = data.positions[m_indexA].a;
    b2Vec2 cB = data.positions[m_indexB].c;
    Fixed aB = data.positions[m_indexB].a;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    const b2Vec2 rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    const b2Vec2 rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    b2Vec2 u = cB + rB - cA - rA;

    const Fixed length = u.Normalize();
    const Fixed C = b2Clamp(length - m_length, -b2_maxLinearCorrection, b2_maxLinearCorrection);

    const Wide impulse = -(m_mass * C);
    const b2WideVec2 P = impulse * u;
    const BodyData A{m_indexA, m_localCenterA, m_invMassA, m_invIA};
    const BodyData B{m_indexB, m_localCenterB, m_invMassB, m_invIB};
    ApplyNeg(cA, aA, A, rA, P);
    ApplyPos(cB, aB, B, rB, P);

    data.positions[m_indexA].c = cA;
    data.positions[m_indexA].a = aA;
    data.positions[m_indexB].c = cB;
    data.positions[m_indexB].a = aB;

    return b2Abs(C) < b2_linearSlop;
}

b2Vec2 b2DistanceJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_localAnchorA); }
b2Vec2 b2DistanceJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2DistanceJoint::GetReactionForce(Fixed inv_dt) const {
    const Wide f = m_impulse * inv_dt;
    return {MulToFixed(f, m_u.x), MulToFixed(f, m_u.y)};
}

Fixed b2DistanceJoint::GetReactionTorque(Fixed) const { return Fixed(); }

}  // namespace lockbox
