// b2GearJoint solver (Box2D 2.2.1 b2GearJoint.cpp) with Q32.32 masses and impulses.
//
// C = coordA + ratio * coordB - constant. Revolute: coord = aBody - aGround - reference,
// J = [0 1 0 -1] in (v, w) of (body, ground). Prismatic: coord = dot(pBody - pGround, axis),
// J = [u, rBody x u, -u, -(rGround x u)]. Bodies: A, B geared; C, D their grounds.
#include "lockbox/dynamics/joints/GearJoint.h"

#include "JointMath.h"
#include "lockbox/dynamics/joints/PrismaticJoint.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"

namespace lockbox {

using namespace jointmath;

b2GearJoint::Side b2GearJoint::MakeSide(b2Joint* joint) {
    Side s;
    s.type = joint->GetType();
    s.ground = joint->GetBodyA();
    s.body = joint->GetBodyB();
    if (s.type == e_revoluteJoint) {
        const auto* revolute = static_cast<const b2RevoluteJoint*>(joint);
        s.localAnchorGround = revolute->GetLocalAnchorA();
        s.localAnchorBody = revolute->GetLocalAnchorB();
        s.referenceAngle = revolute->GetReferenceAngle();
        s.angleBase = math::WrapAngle(s.body->GetAngle() - s.ground->GetAngle() - s.referenceAngle);
    } else {
        const auto* prismatic = static_cast<const b2PrismaticJoint*>(joint);
        s.localAnchorGround = prismatic->GetLocalAnchorA();
        s.localAnchorBody = prismatic->GetLocalAnchorB();
        s.referenceAngle = prismatic->GetReferenceAngle();
        s.localAxisGround = prismatic->GetLocalAxisA();
    }
    return s;
}

Fixed b2GearJoint::Coordinate(const Side& s, const b2Vec2& cG, Fixed aG, const b2Vec2& c, Fixed a, const b2Vec2& lcG,
                              const b2Vec2& lc) {
    if (s.type == e_revoluteJoint) {
        // Continuous angle: the branch nearest the last one (body angles wrap each step).
        return s.angleBase + math::WrapAngle(a - aG - s.referenceAngle - s.angleBase);
    }
    const b2Rot qG(aG), q(a);
    const b2Vec2 pG = s.localAnchorGround - lcG;
    const b2Vec2 p = b2MulT(qG, b2Mul(q, s.localAnchorBody - lc) + (c - cG));
    return b2Dot(p - pG, s.localAxisGround);
}

b2GearJoint::b2GearJoint(const b2GearJointDef* def) : b2Joint(def) {
    m_joint1 = def->joint1;
    m_joint2 = def->joint2;
    m_sideA = MakeSide(m_joint1);
    m_sideB = MakeSide(m_joint2);
    m_bodyA = m_sideA.body;
    m_bodyB = m_sideB.body;
    m_ratio = def->ratio;
    m_constant = GetCoordinateA() + m_ratio * GetCoordinateB();
}

Fixed b2GearJoint::GetCoordinateA() const {
    const b2Body* g = m_sideA.ground;
    const b2Body* b = m_sideA.body;
    return Coordinate(m_sideA, g->GetWorldCenter(), g->GetAngle(), b->GetWorldCenter(), b->GetAngle(),
                      g->GetLocalCenter(), b->GetLocalCenter());
}

Fixed b2GearJoint::GetCoordinateB() const {
    const b2Body* g = m_sideB.ground;
    const b2Body* b = m_sideB.body;
    return Coordinate(m_sideB, g->GetWorldCenter(), g->GetAngle(), b->GetWorldCenter(), b->GetAngle(),
                      g->GetLocalCenter(), b->GetLocalCenter());
}

void b2GearJoint::InitVelocityConstraints(const b2SolverData& data) {
    const BodyData A = Load(m_bodyA), B = Load(m_bodyB), C = Load(m_sideA.ground), D = Load(m_sideB.ground);
    m_indexA = A.index;
    m_indexB = B.index;
    m_indexC = C.index;
    m_indexD = D.index;
    m_lcA = A.localCenter;
    m_lcB = B.localCenter;
    m_lcC = C.localCenter;
    m_lcD = D.localCenter;
    m_mA = A.invMass;
    m_mB = B.invMass;
    m_mC = C.invMass;
    m_mD = D.invMass;
    m_iA = A.invI;
    m_iB = B.invI;
    m_iC = C.invI;
    m_iD = D.invI;

    const b2Position& pA = data.positions[m_indexA];
    const b2Position& pB = data.positions[m_indexB];
    const b2Position& pC = data.positions[m_indexC];
    const b2Position& pD = data.positions[m_indexD];
    b2WideVec2 vA = data.velocities[m_indexA].v, vB = data.velocities[m_indexB].v;
    b2WideVec2 vC = data.velocities[m_indexC].v, vD = data.velocities[m_indexD].v;
    Wide wA = data.velocities[m_indexA].w, wB = data.velocities[m_indexB].w;
    Wide wC = data.velocities[m_indexC].w, wD = data.velocities[m_indexD].w;

    // Move the revolute angle bases to this step's branch. A base past kMaxContinuousAngle
    // drops its whole turns, and the constant drops the same amount (times the ratio on the
    // B side), so C is unchanged and nothing saturates however long the gears spin.
    if (m_sideA.type == e_revoluteJoint) {
        const Fixed angle = Coordinate(m_sideA, pC.c, pC.a, pA.c, pA.a, m_lcC, m_lcA);
        const Fixed shift = b2Abs(angle) > kMaxContinuousAngle ? angle - math::WrapAngle(angle) : Fixed();
        m_sideA.angleBase = angle - shift;
        m_constant -= shift;
    }
    if (m_sideB.type == e_revoluteJoint) {
        const Fixed angle = Coordinate(m_sideB, pD.c, pD.a, pB.c, pB.a, m_lcD, m_lcB);
        const Fixed shift = b2Abs(angle) > kMaxContinuousAngle ? angle - math::WrapAngle(angle) : Fixed();
        m_sideB.angleBase = angle - shift;
        m_constant -= m_ratio * shift;
    }

    const b2Rot qA = data.Rotation(m_indexA, pA.a), qB = data.Rotation(m_indexB, pB.a),
                qC = data.Rotation(m_indexC, pC.a), qD = data.Rotation(m_indexD, pD.a);
    Wide mass;
    if (m_sideA.type == e_revoluteJoint) {
        m_JvAC.SetZero();
        m_JwA = 1;
        m_JwC = 1;
        mass += m_iA + m_iC;
    } else {
        const b2Vec2 u = b2Mul(qC, m_sideA.localAxisGround);
        const b2Vec2 rC = b2Mul(qC, m_sideA.localAnchorGround - m_lcC);
        const b2Vec2 rA = b2Mul(qA, m_sideA.localAnchorBody - m_lcA);
        m_JvAC = u;
        m_JwC = b2Cross(rC, u);
        m_JwA = b2Cross(rA, u);
        mass += m_mC + m_mA + m_iC * MulWide(m_JwC, m_JwC) + m_iA * MulWide(m_JwA, m_JwA);
    }
    if (m_sideB.type == e_revoluteJoint) {
        m_JvBD.SetZero();
        m_JwB = m_ratio;
        m_JwD = m_ratio;
        mass += (m_iB + m_iD) * MulWide(m_ratio, m_ratio);
    } else {
        const b2Vec2 u = b2Mul(qD, m_sideB.localAxisGround);
        const b2Vec2 rD = b2Mul(qD, m_sideB.localAnchorGround - m_lcD);
        const b2Vec2 rB = b2Mul(qB, m_sideB.localAnchorBody - m_lcB);
        m_JvBD = m_ratio * u;
        m_JwD = m_ratio * b2Cross(rD, u);
        m_JwB = m_ratio * b2Cross(rB, u);
        mass += (m_mD + m_mB) * MulWide(m_ratio, m_ratio) + m_iD * MulWide(m_JwD, m_JwD) + m_iB * MulWide(m_JwB, m_JwB);
    }
    m_mass = Invert(mass);

    if (data.step.warmStarting) {
        m_impulse = WarmScaled(m_impulse, data.step.dtRatio);
    } else {
        m_impulse = Wide();
    }
    const Wide L = m_impulse;
    vA.x += (m_mA * L) * m_JvAC.x;
    vA.y += (m_mA * L) * m_JvAC.y;
    wA += (m_iA * L) * m_JwA;
    vB.x += (m_mB * L) * m_JvBD.x;
    vB.y += (m_mB * L) * m_JvBD.y;
    wB += (m_iB * L) * m_JwB;
    vC.x -= (m_mC * L) * m_JvAC.x;
    vC.y -= (m_mC * L) * m_JvAC.y;
    wC -= (m_iC * L) * m_JwC;
    vD.x -= (m_mD * L) * m_JvBD.x;
    vD.y -= (m_mD * L) * m_JvBD.y;
    wD -= (m_iD * L) * m_JwD;

    data.velocities[m_indexA] = {vA, wA};
    data.velocities[m_indexB] = {vB, wB};
    data.velocities[m_indexC] = {vC, wC};
    data.velocities[m_indexD] = {vD, wD};
}

void b2GearJoint::SolveVelocityConstraints(const b2SolverData& data) {
    b2WideVec2 vA = data.velocities[m_indexA].v, vB = data.velocities[m_indexB].v;
    b2WideVec2 vC = data.velocities[m_indexC].v, vD = data.velocities[m_indexD].v;
    Wide wA = data.velocities[m_indexA].w, wB = data.velocities[m_indexB].w;
    Wide wC = data.velocities[m_indexC].w, wD = data.velocities[m_indexD].w;

    const Wide Cdot = DotW(m_JvAC, vA - vC) + DotW(m_JvBD, vB - vD) + wA * m_JwA - wC * m_JwC + wB * m_JwB - wD * m_JwD;
    const Wide impulse = -(m_mass * Cdot);
    m_impulse += impulse;

    vA.x += (m_mA * impulse) * m_JvAC.x;
    vA.y += (m_mA * impulse) * m_JvAC.y;
    wA += (m_iA * impulse) * m_JwA;
    vB.x += (m_mB * impulse) * m_JvBD.x;
    vB.y += (m_mB * impulse) * m_JvBD.y;
    wB += (m_iB * impulse) * m_JwB;
    vC.x -= (m_mC * impulse) * m_JvAC.x;
    vC.y -= (m_mC * impulse) * m_JvAC.y;
    wC -= (m_iC * impulse) * m_JwC;
    vD.x -= (m_mD * impulse) * m_JvBD.x;
    vD.y -= (m_mD * impulse) * m_JvBD.y;
    wD -= (m_iD * impulse) * m_JwD;

    data.velocities[m_indexA] = {vA, wA};
    data.velocities[m_indexB] = {vB, wB};
    data.velocities[m_indexC] = {vC, wC};
    data.velocities[m_indexD] = {vD, wD};
}

bool b2GearJoint::SolvePositionConstraints(const b2SolverData& data) {
    b2Vec2 cA = data.positions[m_indexA].c, cB = data.positions[m_indexB].c;
    b2Vec2 cC = data.positions[m_indexC].c, cD = data.positions[m_indexD].c;
    Fixed aA = data.positions[m_indexA].a, aB = data.positions[m_indexB].a;
    Fixed aC = data.positions[m_indexC].a, aD = data.positions[m_indexD].a;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB), qC = data.Rotation(m_indexC, aC),
                qD = data.Rotation(m_indexD, aD);
    b2Vec2 JvAC, JvBD;
    Fixed JwA, JwB, JwC, JwD;
    Wide mass;
    if (m_sideA.type == e_revoluteJoint) {
        JwA = 1;
        JwC = 1;
        mass += m_iA + m_iC;
    } else {
        const b2Vec2 u = b2Mul(qC, m_sideA.localAxisGround);
        const b2Vec2 rC = b2Mul(qC, m_sideA.localAnchorGround - m_lcC);
        const b2Vec2 rA = b2Mul(qA, m_sideA.localAnchorBody - m_lcA);
        JvAC = u;
        JwC = b2Cross(rC, u);
        JwA = b2Cross(rA, u);
        mass += m_mC + m_mA + m_iC * MulWide(JwC, JwC) + m_iA * MulWide(JwA, JwA);
    }
    if (m_sideB.type == e_revoluteJoint) {
        JwB = m_ratio;
        JwD = m_ratio;
        mass += (m_iB + m_iD) * MulWide(m_ratio, m_ratio);
    } else {
        const b2Vec2 u = b2Mul(qD, m_sideB.localAxisGround);
        const b2Vec2 rD = b2Mul(qD, m_sideB.localAnchorGround - m_lcD);
        const b2Vec2 rB = b2Mul(qB, m_sideB.localAnchorBody - m_lcB);
        JvBD = m_ratio * u;
        JwD = m_ratio * b2Cross(rD, u);
        JwB = m_ratio * b2Cross(rB, u);
        mass += (m_mD + m_mB) * MulWide(m_ratio, m_ratio) + m_iD * MulWide(JwD, JwD) + m_iB * MulWide(JwB, JwB);
    }

    const Fixed coordinateA = Coordinate(m_sideA, cC, aC, cA, aA, m_lcC, m_lcA);
    const Fixed coordinateB = Coordinate(m_sideB, cD, aD, cB, aB, m_lcD, m_lcB);
    const Fixed C = (coordinateA + m_ratio * coordinateB) - m_constant;
    const Wide impulse = mass > Wide() ? -(Wide(C) / mass) : Wide();

    cA.x += MulToFixed(m_mA * impulse, JvAC.x);
    cA.y += MulToFixed(m_mA * impulse, JvAC.y);
    aA += MulToFixed(m_iA * impulse, JwA);
    cB.x += MulToFixed(m_mB * impulse, JvBD.x);
    cB.y += MulToFixed(m_mB * impulse, JvBD.y);
    aB += MulToFixed(m_iB * impulse, JwB);
    cC.x -= MulToFixed(m_mC * impulse, JvAC.x);
    cC.y -= MulToFixed(m_mC * impulse, JvAC.y);
    aC -= MulToFixed(m_iC * impulse, JwC);
    cD.x -= MulToFixed(m_mD * impulse, JvBD.x);
    cD.y -= MulToFixed(m_mD * impulse, JvBD.y);
    aD -= MulToFixed(m_iD * impulse, JwD);

    data.positions[m_indexA] = {cA, aA};
    data.positions[m_indexB] = {cB, aB};
    data.positions[m_indexC] = {cC, aC};
    data.positions[m_indexD] = {cD, aD};

    // 2.2.1 reports the gear as always solved (its linearError stays 0): the other joints
    // decide the early exit.
    return true;
}

b2Vec2 b2GearJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_sideA.localAnchorBody); }
b2Vec2 b2GearJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_sideB.localAnchorBody); }

b2Vec2 b2GearJoint::GetReactionForce(Fixed inv_dt) const {
    const Wide f = m_impulse * inv_dt;
    return {MulToFixed(f, m_JvAC.x), MulToFixed(f, m_JvAC.y)};
}

Fixed b2GearJoint::GetReactionTorque(Fixed inv_dt) const { return MulToFixed(m_impulse * inv_dt, m_JwA); }

}  // namespace lockbox
