// b2WheelJoint solver (Box2D 2.2.1 b2WheelJoint.cpp) with Q32.32 masses, impulses and spring.
//
// Point-to-line: Cdot = dot(ay, vB - vA) + sBy wB - sAy wA. Spring along ax (soft, see
// JointMath.h). Motor: Cdot = wB - wA.
#include "lockbox/dynamics/joints/WheelJoint.h"

#include "JointMath.h"

namespace lockbox {

using namespace jointmath;

void b2WheelJointDef::Initialize(b2Body* bA, b2Body* bB, const b2Vec2& anchor, const b2Vec2& axis) {
    bodyA = bA;
    bodyB = bB;
    localAnchorA = bodyA->GetLocalPoint(anchor);
    localAnchorB = bodyB->GetLocalPoint(anchor);
    localAxisA = bodyA->GetLocalVector(axis);
}

b2WheelJoint::b2WheelJoint(const b2WheelJointDef* def) : b2Joint(def) {
    m_localAnchorA = def->localAnchorA;
    m_localAnchorB = def->localAnchorB;
    m_localXAxisA = def->localAxisA;
    m_localXAxisA.Normalize();
    m_localYAxisA = b2Cross(Fixed(1), m_localXAxisA);
    m_maxMotorTorque = def->maxMotorTorque;
    m_motorSpeed = def->motorSpeed;
    m_enableMotor = def->enableMotor;
    m_frequencyHz = def->frequencyHz;
    m_dampingRatio = def->dampingRatio;
}

void b2WheelJoint::InitVelocityConstraints(const b2SolverData& data) {
    [[maybe_unused]] auto [A, B, cA, aA, vA, wA, cB, aB, vB, wB] = BeginSolve(*this, data);
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    const b2Vec2 rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    const b2Vec2 rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    const b2Vec2 d = cB + rB - cA - rA;

    // Point to line constraint.
    m_ay = b2Mul(qA, m_localYAxisA);
    m_sAy = b2Cross(d + rA, m_ay);
    m_sBy = b2Cross(rB, m_ay);
    m_mass = Invert(mA + mB + iA * MulWide(m_sAy, m_sAy) + iB * MulWide(m_sBy, m_sBy));

    // Spring constraint.
    m_ax = b2Mul(qA, m_localXAxisA);
    m_sAx = b2Cross(d + rA, m_ax);
    m_sBx = b2Cross(rB, m_ax);
    m_springMass = Wide();
    m_bias = Wide();
    m_gamma = Wide();
    if (m_frequencyHz > Fixed()) {
        const Wide invMass = mA + mB + iA * MulWide(m_sAx, m_sAx) + iB * MulWide(m_sBx, m_sBx);
        if (invMass > Wide()) {
            const Fixed C = b2Dot(d, m_ax);
            const Soft soft = SoftCoefficients(Invert(invMass), m_frequencyHz, m_dampingRatio, data.step.dt);
            m_gamma = soft.gamma;
            m_bias = soft.biasRate * C;
            m_springMass = Invert(invMass + m_gamma);
        }
    } else {
        m_springImpulse = Wide();
    }

    // Rotational motor.
    if (m_enableMotor) {
        m_motorMass = Invert(iA + iB);
    } else {
        m_motorMass = Wide();
        m_motorImpulse = Wide();
    }

    if (data.step.warmStarting) {
        const Fixed r = data.step.dtRatio;
        m_impulse = WarmScaled(m_impulse, r);
        m_springImpulse = WarmScaled(m_springImpulse, r);
        m_motorImpulse = WarmScaled(m_motorImpulse, r);
        const b2WideVec2 P = m_impulse * m_ay + m_springImpulse * m_ax;
        const Wide LA = m_impulse * m_sAy + m_springImpulse * m_sAx + m_motorImpulse;
        const Wide LB = m_impulse * m_sBy + m_springImpulse * m_sBx + m_motorImpulse;
        ApplyLineImpulse(vA, wA, vB, wB, mA, mB, iA, iB, P, LA, LB);
    } else {
        m_impulse = Wide();
        m_springImpulse = Wide();
        m_motorImpulse = Wide();
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

void b2WheelJoint::SolveVelocityConstraints(const b2SolverData& data) {
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;
    b2WideVec2 vA = data.velocities[m_indexA].v;
    Wide wA = data.velocities[m_indexA].w;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;

    // Solve the spring constraint.
    {
        const Wide Cdot = DotW(m_ax, vB - vA) + wB * m_sBx - wA * m_sAx;
        const Wide impulse = -(m_springMass * (Cdot + m_bias + m_gamma * m_springImpulse));
        m_springImpulse += impulse;
        ApplyLineImpulse(vA, wA, vB, wB, mA, mB, iA, iB, impulse * m_ax, impulse * m_sAx, impulse * m_sBx);
    }

    // Solve the rotational motor constraint.
    {
        const Wide Cdot = wB - wA - Wide(m_motorSpeed);
        Wide impulse = -(m_motorMass * Cdot);
        const Wide oldImpulse = m_motorImpulse;
        const Wide maxImpulse = MulWide(data.step.dt, m_maxMotorTorque);
        m_motorImpulse = b2Clamp(m_motorImpulse + impulse, -maxImpulse, maxImpulse);
        impulse = m_motorImpulse - oldImpulse;
        wA -= iA * impulse;
        wB += iB * impulse;
    }

    // Solve the point to line constraint.
    {
        const Wide Cdot = DotW(m_ay, vB - vA) + wB * m_sBy - wA * m_sAy;
        const Wide impulse = -(m_mass * Cdot);
        m_impulse += impulse;
        ApplyLineImpulse(vA, wA, vB, wB, mA, mB, iA, iB, impulse * m_ay, impulse * m_sAy, impulse * m_sBy);
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

bool b2WheelJoint::SolvePositionConstraints(const b2SolverData& data) {
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;
    b2Vec2 cA = data.positions[m_indexA].c;
    Fixed aA = data.positions[m_indexA].a;
    b2Vec2 cB = data.positions[m_indexB].c;
    Fixed aB = data.positions[m_indexB].a;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    const b2Vec2 rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    const b2Vec2 rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    const b2Vec2 d = (cB - cA) + rB - rA;

    const b2Vec2 ay = b2Mul(qA, m_localYAxisA);
    const Fixed sAy = b2Cross(d + rA, ay);
    const Fixed sBy = b2Cross(rB, ay);
    const Fixed C = b2Dot(d, ay);
    const Wide k = mA + mB + iA * MulWide(sAy, sAy) + iB * MulWide(sBy, sBy);
    const Wide impulse = k != Wide() ? -(Wide(C) / k) : Wide();

    ApplyLineImpulse(cA, aA, cB, aB, mA, mB, iA, iB, impulse * ay, impulse * sAy, impulse * sBy);

    data.positions[m_indexA].c = cA;
    data.positions[m_indexA].a = aA;
    data.positions[m_indexB].c = cB;
    data.positions[m_indexB].a = aB;

    return b2Abs(C) <= b2_linearSlop;
}

b2Vec2 b2WheelJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_localAnchorA); }
b2Vec2 b2WheelJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2WheelJoint::GetReactionForce(Fixed inv_dt) const {
    const b2WideVec2 P = m_impulse * m_ay + m_springImpulse * m_ax;
    return {MulToFixed(P.x, inv_dt), MulToFixed(P.y, inv_dt)};
}

Fixed b2WheelJoint::GetReactionTorque(Fixed inv_dt) const { return MulToFixed(m_motorImpulse, inv_dt); }

Fixed b2WheelJoint::GetJointTranslation() const {
    const b2Vec2 pA = m_bodyA->GetWorldPoint(m_localAnchorA);
    const b2Vec2 pB = m_bodyB->GetWorldPoint(m_localAnchorB);
    const b2Vec2 axis = m_bodyA->GetWorldVector(m_localXAxisA);
    return b2Dot(pB - pA, axis);
}

Fixed b2WheelJoint::GetJointSpeed() const { return m_bodyB->GetAngularVelocity() - m_bodyA->GetAngularVelocity(); }

Fixed b2WheelJoint::GetMotorTorque(Fixed inv_dt) const { return MulToFixed(m_motorImpulse, inv_dt); }

void b2WheelJoint::EnableMotor(bool flag) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_enableMotor = flag;
}

void b2WheelJoint::SetMotorSpeed(Fixed speed) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_motorSpeed = speed;
}

void b2WheelJoint::SetMaxMotorTorque(Fixed torque) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_maxMotorTorque = torque;
}

}  // namespace lockbox
