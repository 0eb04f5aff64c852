// b2RopeJoint solver (Box2D 2.2.1 b2RopeJoint.cpp) with Q32.32 masses and impulses.
//
// C = |pB - pA| - maxLength <= 0. The velocity solve is predictive: while slack, it lets the
// anchors approach the limit by at most C per step (Cdot + C/h >= 0).
#include "lockbox/dynamics/joints/RopeJoint.h"

#include "JointMath.h"

namespace lockbox {

using namespace jointmath;

b2RopeJoint::b2RopeJoint(const b2RopeJointDef* def) : b2Joint(def) {
    m_localAnchorA = def->localAnchorA;
    m_localAnchorB = def->localAnchorB;
    m_maxLength = def->maxLength;
}

void b2RopeJoint::InitVelocityConstraints(const b2SolverData& data) {
    [[maybe_unused]] auto [A, B, cA, aA, vA, wA, cB, aB, vB, wB] = BeginSolve(*this, data);

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    m_rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    m_rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    m_u = cB + m_rB - cA - m_rA;
    m_length = m_u.Normalize();

    const Fixed C = m_length - m_maxLength;
    m_state = C > Fixed() ? e_atUpperLimit : e_inactiveLimit;

    // Below linearSlop the direction is noise: the joint rests this step.
    if (m_length <= b2_linearSlop) {
        m_u.SetZero();
        m_mass = Wide();
        m_impulse = Wide();
        return;
    }

    const Wide crA = CrossW(m_rA, m_u);
    const Wide crB = CrossW(m_rB, m_u);
    m_mass = Invert(m_invMassA + m_invIA * (crA * crA) + m_invMassB + m_invIB * (crB * crB));

    if (data.step.warmStarting) {
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

void b2RopeJoint::SolveVelocityConstraints(const b2SolverData& data) {
    b2WideVec2 vA = data.velocities[m_indexA].v;
    Wide wA = data.velocities[m_indexA].w;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;

    const Fixed C = m_length - m_maxLength;
    Wide Cdot = DotW(m_u, PointVelocity(vB, wB, m_rB) - PointVelocity(vA, wA, m_rA));

    // Predictive constraint.
    if (C < Fixed()) Cdot += MulWide(data.step.inv_dt, C);

    Wide impulse = -(m_mass * Cdot);
    const Wide oldImpulse = m_impulse;
    m_impulse = b2Min(Wide(), m_impulse + impulse);
    impulse = m_impulse - oldImpulse;

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

bool b2RopeJoint::SolvePositionConstraints(const b2SolverData& data) {
    b2Vec2 cA = data.positions[m_indexA].c;
    Fixed aA = data.positions[m_indexA].a;
    b2Vec2 cB = data.positions[m_indexB].c;
    Fixed aB = data.positions[m_indexB].a;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    const b2Vec2 rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    const b2Vec2 rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    b2Vec2 u = cB + rB - cA - rA;

    const Fixed length = u.Normalize();
    const Fixed C = b2Clamp(length - m_maxLength, Fixed(), b2_maxLinearCorrection);

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

    return length - m_maxLength < b2_linearSlop;
}

b2Vec2 b2RopeJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_localAnchorA); }
b2Vec2 b2RopeJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2RopeJoint::GetReactionForce(Fixed inv_dt) const {
    const Wide f = m_impulse * inv_dt;
    return {MulToFixed(f, m_u.x), MulToFixed(f, m_u.y)};
}

Fixed b2RopeJoint::GetReactionTorque(Fixed) const { return Fixed(); }

}  // namespace lockbox
