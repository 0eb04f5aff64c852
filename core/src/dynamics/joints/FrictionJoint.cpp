// b2FrictionJoint solver (Box2D 2.2.1 b2FrictionJoint.cpp) with Q32.32 masses and impulses.
//
// Linear: Cdot = vB + wB x rB - vA - wA x rA, impulse clamped to a disc of radius
// h * maxForce. Angular: Cdot = wB - wA, impulse clamped to h * maxTorque.
#include "lockbox/dynamics/joints/FrictionJoint.h"

#include "JointMath.h"

namespace lockbox {

using namespace jointmath;

void b2FrictionJointDef::Initialize(b2Body* bA, b2Body* bB, const b2Vec2& anchor) {
    bodyA = bA;
    bodyB = bB;
    localAnchorA = bodyA->GetLocalPoint(anchor);
    localAnchorB = bodyB->GetLocalPoint(anchor);
}

b2FrictionJoint::b2FrictionJoint(const b2FrictionJointDef* def) : b2Joint(def) {
    m_localAnchorA = def->localAnchorA;
    m_localAnchorB = def->localAnchorB;
    m_maxForce = def->maxForce;
    m_maxTorque = def->maxTorque;
}

void b2FrictionJoint::InitVelocityConstraints(const b2SolverData& data) {
    [[maybe_unused]] auto [A, B, cA, aA, vA, wA, cB, aB, vB, wB] = BeginSolve(*this, data);
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    m_rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    m_rB = b2Mul(qB, m_localAnchorB - m_localCenterB);

    b2WideMat22 K;
    K.ex.x = mA + mB + iA * MulWide(m_rA.y, m_rA.y) + iB * MulWide(m_rB.y, m_rB.y);
    K.ex.y = -(iA * MulWide(m_rA.x, m_rA.y)) - iB * MulWide(m_rB.x, m_rB.y);
    K.ey.x = K.ex.y;
    K.ey.y = mA + mB + iA * MulWide(m_rA.x, m_rA.x) + iB * MulWide(m_rB.x, m_rB.x);
    m_linearK = K.Prepared();
    m_angularMass = Invert(iA + iB);

    if (data.step.warmStarting) {
        const Fixed r = data.step.dtRatio;
        m_linearImpulse = WarmScaled(m_linearImpulse, r);
        m_angularImpulse = WarmScaled(m_angularImpulse, r);
        const b2WideVec2 P = m_linearImpulse;
        vA.x -= mA * P.x;
        vA.y -= mA * P.y;
        wA -= iA * (b2Cross(m_rA, P) + m_angularImpulse);
        vB.x += mB * P.x;
        vB.y += mB * P.y;
        wB += iB * (b2Cross(m_rB, P) + m_angularImpulse);
    } else {
        m_linearImpulse.SetZero();
        m_angularImpulse = Wide();
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

void b2FrictionJoint::SolveVelocityConstraints(const b2SolverData& data) {
    b2WideVec2 vA = data.velocities[m_indexA].v;
    Wide wA = data.velocities[m_indexA].w;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;
    const Wide iA = m_invIA, iB = m_invIB;
    const Fixed h = data.step.dt;

    // Solve angular friction.
    {
        const Wide Cdot = wB - wA;
        Wide impulse = -(m_angularMass * Cdot);
        const Wide oldImpulse = m_angularImpulse;
        const Wide maxImpulse = MulWide(h, m_maxTorque);
        m_angularImpulse = b2Clamp(m_angularImpulse + impulse, -maxImpulse, maxImpulse);
        impulse = m_angularImpulse - oldImpulse;
        wA -= iA * impulse;
        wB += iB * impulse;
    }

    // Solve linear friction.
    {
        const b2WideVec2 Cdot = PointVelocity(vB, wB, m_rB) - PointVelocity(vA, wA, m_rA);
        const b2WideVec2 oldImpulse = m_linearImpulse;
        m_linearImpulse += -m_linearK.Solve(Cdot);
        m_linearImpulse = b2ClampLength(m_linearImpulse, MulWide(h, m_maxForce));
        const b2WideVec2 impulse = m_linearImpulse - oldImpulse;

        const BodyData A{m_indexA, m_localCenterA, m_invMassA, m_invIA};
        const BodyData B{m_indexB, m_localCenterB, m_invMassB, m_invIB};
        ApplyNeg(vA, wA, A, m_rA, impulse);
        ApplyPos(vB, wB, B, m_rB, impulse);
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

bool b2FrictionJoint::SolvePositionConstraints(const b2SolverData&) { return true; }

b2Vec2 b2FrictionJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_localAnchorA); }
b2Vec2 b2FrictionJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2FrictionJoint::GetReactionForce(Fixed inv_dt) const {
    return {MulToFixed(m_linearImpulse.x, inv_dt), MulToFixed(m_linearImpulse.y, inv_dt)};
}

Fixed b2FrictionJoint::GetReactionTorque(Fixed inv_dt) const { return MulToFixed(m_angularImpulse, inv_dt); }

}  // namespace lockbox
