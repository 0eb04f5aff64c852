// b2WeldJoint solver (Box2D 2.2.1 b2WeldJoint.cpp) with a Q32.32 K matrix solved exactly.
//
// Point: Cdot1 = vB + wB x rB - vA - wA x rA; angle: Cdot2 = wB - wA. Where 2.2.1 multiplies
// by K's (2x2 or symmetric 3x3) inverse, this solves with K directly: the same result, with
// one rounding instead of two.
#include "lockbox/dynamics/joints/WeldJoint.h"

#include "JointMath.h"

namespace lockbox {

using namespace jointmath;

void b2WeldJointDef::Initialize(b2Body* bA, b2Body* bB, const b2Vec2& anchor) {
    bodyA = bA;
    bodyB = bB;
    localAnchorA = bodyA->GetLocalPoint(anchor);
    localAnchorB = bodyB->GetLocalPoint(anchor);
    referenceAngle = bodyB->GetAngle() - bodyA->GetAngle();
}

b2WeldJoint::b2WeldJoint(const b2WeldJointDef* def) : b2Joint(def) {
    m_localAnchorA = def->localAnchorA;
    m_localAnchorB = def->localAnchorB;
    m_referenceAngle = def->referenceAngle;
    m_frequencyHz = def->frequencyHz;
    m_dampingRatio = def->dampingRatio;
}

namespace {
b2WideMat33 WeldK(Wide mA, Wide mB, Wide iA, Wide iB, const b2Vec2& rA, const b2Vec2& rB) {
    b2WideMat33 K;
    K.ex.x = mA + mB + iA * MulWide(rA.y, rA.y) + iB * MulWide(rB.y, rB.y);
    K.ey.x = -(iA * MulWide(rA.y, rA.x)) - iB * MulWide(rB.y, rB.x);
    K.ez.x = -(iA * rA.y) - iB * rB.y;
    K.ex.y = K.ey.x;
    K.ey.y = mA + mB + iA * MulWide(rA.x, rA.x) + iB * MulWide(rB.x, rB.x);
    K.ez.y = iA * rA.x + iB * rB.x;
    K.ex.z = K.ez.x;
    K.ey.z = K.ez.y;
    K.ez.z = iA + iB;
    return K;
}

template <class Vec, class Scalar>
void ApplyAnchorImpulse(Vec& vA, Scalar& wA, Vec& vB, Scalar& wB, Wide mA, Wide mB, Wide iA, Wide iB, const b2Vec2& rA,
                        const b2Vec2& rB, const b2WideVec2& P, Wide L) {
    SubProduct(vA.x, mA, P.x);
    SubProduct(vA.y, mA, P.y);
    SubProduct(wA, iA, b2Cross(rA, P) + L);
    AddProduct(vB.x, mB, P.x);
    AddProduct(vB.y, mB, P.y);
    AddProduct(wB, iB, b2Cross(rB, P) + L);
}
}  // namespace

void b2WeldJoint::InitVelocityConstraints(const b2SolverData& data) {
    [[maybe_unused]] auto [A, B, cA, aA, vA, wA, cB, aB, vB, wB] = BeginSolve(*this, data);
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    m_rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    m_rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    m_K = WeldK(mA, mB, iA, iB, m_rA, m_rB);

    if (m_frequencyHz > Fixed()) {
        Wide invM = iA + iB;
        const Wide m = Invert(invM);
        // Body angles are wrapped independently: wrap the relative angle too.
        const Fixed C = math::WrapAngle(aB - aA - m_referenceAngle);
        const Soft soft = SoftCoefficients(m, m_frequencyHz, m_dampingRatio, data.step.dt);
        m_gamma = soft.gamma;
        m_bias = soft.biasRate * C;
        invM += m_gamma;
        m_angularMass = Invert(invM);
        m_pointSolver = m_K.Upper22();
        m_pointMass = math::Inverse(m_pointSolver);
    } else {
        m_gamma = Wide();
        m_bias = Wide();
        m_angularMass = Wide();
        m_rigidSolver = m_K.Prepared();
    }

    if (data.step.warmStarting) {
        const Fixed r = data.step.dtRatio;
        m_impulse = {WarmScaled(m_impulse.x, r), WarmScaled(m_impulse.y, r), WarmScaled(m_impulse.z, r)};
        ApplyAnchorImpulse(vA, wA, vB, wB, mA, mB, iA, iB, m_rA, m_rB, b2WideVec2(m_impulse.x, m_impulse.y),
                           m_impulse.z);
    } else {
        m_impulse.SetZero();
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

void b2WeldJoint::SolveVelocityConstraints(const b2SolverData& data) {
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;
    b2WideVec2 vA = data.velocities[m_indexA].v;
    Wide wA = data.velocities[m_indexA].w;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;

    if (m_frequencyHz > Fixed()) {
        const Wide Cdot2 = wB - wA;
        const Wide impulse2 = -(m_angularMass * (Cdot2 + m_bias + m_gamma * m_impulse.z));
        m_impulse.z += impulse2;
        wA -= iA * impulse2;
        wB += iB * impulse2;

        const b2WideVec2 Cdot1 = PointVelocity(vB, wB, m_rB) - PointVelocity(vA, wA, m_rA);
        const b2WideVec2 impulse1 = -math::Mul(m_pointMass, Cdot1);
        m_impulse.x += impulse1.x;
        m_impulse.y += impulse1.y;
        ApplyAnchorImpulse(vA, wA, vB, wB, mA, mB, iA, iB, m_rA, m_rB, impulse1, Wide());
    } else {
        const b2WideVec2 Cdot1 = PointVelocity(vB, wB, m_rB) - PointVelocity(vA, wA, m_rA);
        const Wide Cdot2 = wB - wA;
        const b2WideVec3 impulse = -m_rigidSolver.Solve33(b2WideVec3(Cdot1.x, Cdot1.y, Cdot2));
        m_impulse += impulse;
        ApplyAnchorImpulse(vA, wA, vB, wB, mA, mB, iA, iB, m_rA, m_rB, b2WideVec2(impulse.x, impulse.y), impulse.z);
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

bool b2WeldJoint::SolvePositionConstraints(const b2SolverData& data) {
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;
    b2Vec2 cA = data.positions[m_indexA].c;
    Fixed aA = data.positions[m_indexA].a;
    b2Vec2 cB = data.positions[m_indexB].c;
    Fixed aB = data.positions[m_indexB].a;

    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    const b2Vec2 rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    const b2Vec2 rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    const b2WideMat33 K = WeldK(mA, mB, iA, iB, rA, rB);

    const b2Vec2 C1 = cB + rB - cA - rA;
    const bool closed = LengthWithin(C1, b2_linearSlop);
    Fixed angularError;

    if (m_frequencyHz > Fixed()) {
        const b2WideVec2 P = -K.Solve22(C1);
        ApplyAnchorImpulse(cA, aA, cB, aB, mA, mB, iA, iB, rA, rB, P, Wide());
    } else {
        const Fixed C2 = math::WrapAngle(aB - aA - m_referenceAngle);
        angularError = b2Abs(C2);
        const b2WideVec3 impulse = -K.Solve33(b2Vec3(C1.x, C1.y, C2));
        ApplyAnchorImpulse(cA, aA, cB, aB, mA, mB, iA, iB, rA, rB, b2WideVec2(impulse.x, impulse.y), impulse.z);
    }

    data.positions[m_indexA].c = cA;
    data.positions[m_indexA].a = aA;
    data.positions[m_indexB].c = cB;
    data.positions[m_indexB].a = aB;

    return closed && angularError <= b2_angularSlop;
}

b2Vec2 b2WeldJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_localAnchorA); }
b2Vec2 b2WeldJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2WeldJoint::GetReactionForce(Fixed inv_dt) const {
    return {MulToFixed(m_impulse.x, inv_dt), MulToFixed(m_impulse.y, inv_dt)};
}

Fixed b2WeldJoint::GetReactionTorque(Fixed inv_dt) const { return MulToFixed(m_impulse.z, inv_dt); }

}  // namespace lockbox
