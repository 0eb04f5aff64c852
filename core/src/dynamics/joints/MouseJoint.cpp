// b2MouseJoint solver (Box2D 2.2.1 b2MouseJoint.cpp) with Q32.32 spring, mass and impulses.
//
// Soft point constraint C = pB - target: Cdot + beta * C + gamma * impulse = 0, with the
// accumulated impulse clamped to a disc of radius h * maxForce.
#include "lockbox/dynamics/joints/MouseJoint.h"

#include "JointMath.h"

namespace lockbox {

using namespace jointmath;
using namespace lockbox::literals;

b2MouseJoint::b2MouseJoint(const b2MouseJointDef* def) : b2Joint(def) {
    m_targetA = def->target;
    m_localAnchorB = b2MulT(m_bodyB->GetTransform(), m_targetA);
    m_maxForce = def->maxForce;
    m_frequencyHz = def->frequencyHz;
    m_dampingRatio = def->dampingRatio;
}

void b2MouseJoint::SetTarget(const b2Vec2& target) {
    if (!m_bodyB->IsAwake()) m_bodyB->SetAwake(true);
    m_targetA = target;
}

void b2MouseJoint::InitVelocityConstraints(const b2SolverData& data) {
    const BodyData B = Load(m_bodyB);
    m_indexB = B.index;
    m_localCenterB = B.localCenter;
    m_invMassB = B.invMass;
    m_invIB = B.invI;

    const b2Vec2 cB = data.positions[m_indexB].c;
    const Fixed aB = data.positions[m_indexB].a;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;

    const b2Rot qB = data.Rotation(m_indexB, aB);
    const Wide mass = m_bodyB->GetMass();

    // Spring coefficients in Q32.32 (k = m omega^2 is 3.3e7 N/m for 1000 kg at 29 Hz).
    const Soft soft = SoftCoefficients(mass, m_frequencyHz, m_dampingRatio, data.step.dt);
    m_gamma = soft.gamma;
    m_beta = soft.biasRate;

    // Compute the effective mass matrix.
    m_rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    const Wide mB = m_invMassB, iB = m_invIB;
    b2WideMat22 K;
    K.ex.x = mB + iB * MulWide(m_rB.y, m_rB.y) + m_gamma;
    K.ex.y = -(iB * MulWide(m_rB.x, m_rB.y));
    K.ey.x = K.ex.y;
    K.ey.y = mB + iB * MulWide(m_rB.x, m_rB.x) + m_gamma;
    m_K = K.Prepared();

    const b2Vec2 C = cB + m_rB - m_targetA;
    m_C = {m_beta * C.x, m_beta * C.y};

    // Cheat with some damping (2.2.1 does this to calm the grabbed body's spin).
    wB = wB * 0.98_fx;

    if (data.step.warmStarting) {
        m_impulse = WarmScaled(m_impulse, data.step.dtRatio);
        vB.x += mB * m_impulse.x;
        vB.y += mB * m_impulse.y;
        wB += iB * b2Cross(m_rB, m_impulse);
    } else {
        m_impulse.SetZero();
    }

    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

void b2MouseJoint::SolveVelocityConstraints(const b2SolverData& data) {
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;

    // Cdot = v + cross(w, r)
    const b2WideVec2 Cdot = PointVelocity(vB, wB, m_rB);
    const b2WideVec2 rhs = -(Cdot + m_C + b2WideVec2(m_gamma * m_impulse.x, m_gamma * m_impulse.y));
    b2WideVec2 impulse = m_K.Solve(rhs);

    const b2WideVec2 oldImpulse = m_impulse;
    m_impulse += impulse;
    m_impulse = b2ClampLength(m_impulse, m_maxForce * data.step.dt);
    impulse = m_impulse - oldImpulse;

    vB.x += m_invMassB * impulse.x;
    vB.y += m_invMassB * impulse.y;
    wB += m_invIB * b2Cross(m_rB, impulse);

    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

bool b2MouseJoint::SolvePositionConstraints(const b2SolverData&) { return true; }

b2Vec2 b2MouseJoint::GetAnchorA() const { return m_targetA; }
b2Vec2 b2MouseJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2MouseJoint::GetReactionForce(Fixed inv_dt) const {
    return {MulToFixed(m_impulse.x, inv_dt), MulToFixed(m_impulse.y, inv_dt)};
}

Fixed b2MouseJoint::GetReactionTorque(Fixed) const { return Fixed(); }

}  // namespace lockbox
