// b2PrismaticJoint solver (Box2D 2.2.1 b2PrismaticJoint.cpp) with a Q32.32 K matrix.
//
// Linear constraint along perp: Cdot1 = dot(perp, vB - vA) + s2 wB - s1 wA; angular:
// Cdot2 = wB - wA; axial limit/motor: Cdot = dot(axis, vB - vA) + a2 wB - a1 wA, where
// s1 = (d + rA) x perp, s2 = rB x perp, a1 = (d + rA) x axis, a2 = rB x axis.
#include "lockbox/dynamics/joints/PrismaticJoint.h"

#include "JointMath.h"

namespace lockbox {

using namespace jointmath;

void b2PrismaticJointDef::Initialize(b2Body* bA, b2Body* bB, const b2Vec2& anchor, const b2Vec2& axis) {
    bodyA = bA;
    bodyB = bB;
    localAnchorA = bodyA->GetLocalPoint(anchor);
    localAnchorB = bodyB->GetLocalPoint(anchor);
    localAxisA = bodyA->GetLocalVector(axis);
    localAxisA.Normalize();
    referenceAngle = bodyB->GetAngle() - bodyA->GetAngle();
}

b2PrismaticJoint::b2PrismaticJoint(const b2PrismaticJointDef* def) : b2Joint(def) {
    m_localAnchorA = def->localAnchorA;
    m_localAnchorB = def->localAnchorB;
    m_localXAxisA = def->localAxisA;
    m_localXAxisA.Normalize();
    m_localYAxisA = b2Cross(Fixed(1), m_localXAxisA);
    m_referenceAngle = def->referenceAngle;
    m_lowerTranslation = def->lowerTranslation;
    m_upperTranslation = def->upperTranslation;
    m_maxMotorForce = def->maxMotorForce;
    m_motorSpeed = def->motorSpeed;
    m_enableLimit = def->enableLimit;
    m_enableMotor = def->enableMotor;
}

namespace {
struct Frame {
    b2Vec2 rA, rB, d, axis, perp;
    Fixed a1, a2, s1, s2;
};

Frame MakeFrame(const b2Vec2& cA, Fixed aA, const b2Vec2& cB, Fixed aB, const b2Vec2& lA, const b2Vec2& lcA,
                const b2Vec2& lB, const b2Vec2& lcB, const b2Vec2& xAxis, const b2Vec2& yAxis) {
    Frame f;
    const b2Rot qA(aA), qB(aB);
    f.rA = b2Mul(qA, lA - lcA);
    f.rB = b2Mul(qB, lB - lcB);
    f.d = cB - cA + f.rB - f.rA;
    f.axis = b2Mul(qA, xAxis);
    f.a1 = b2Cross(f.d + f.rA, f.axis);
    f.a2 = b2Cross(f.rB, f.axis);
    f.perp = b2Mul(qA, yAxis);
    f.s1 = b2Cross(f.d + f.rA, f.perp);
    f.s2 = b2Cross(f.rB, f.perp);
    return f;
}

b2WideMat33 MakeK(Wide mA, Wide mB, Wide iA, Wide iB, Fixed s1, Fixed s2, Fixed a1, Fixed a2) {
    const Wide k11 = mA + mB + iA * MulWide(s1, s1) + iB * MulWide(s2, s2);
    const Wide k12 = iA * s1 + iB * s2;
    const Wide k13 = iA * MulWide(s1, a1) + iB * MulWide(s2, a2);
    Wide k22 = iA + iB;
    // For bodies with fixed rotation the angular row is decoupled: any non-zero value works.
    if (k22 == Wide()) k22 = Wide(1);
    const Wide k23 = iA * a1 + iB * a2;
    const Wide k33 = mA + mB + iA * MulWide(a1, a1) + iB * MulWide(a2, a2);
    b2WideMat33 K;
    K.ex = {k11, k12, k13};
    K.ey = {k12, k22, k23};
    K.ez = {k13, k23, k33};
    return K;
}

// P = px * perp + pz * axis, LA = px s1 + py + pz a1, LB = px s2 + py + pz a2; applied with
// sign -1 to A and +1 to B.
template <class Vec, class Scalar>
void ApplyFrameImpulse(Vec& vA, Scalar& wA, Vec& vB, Scalar& wB, Wide mA, Wide mB, Wide iA, Wide iB, const b2Vec2& perp,
                       const b2Vec2& axis, Fixed s1, Fixed s2, Fixed a1, Fixed a2, Wide px, Wide py, Wide pz) {
    const b2WideVec2 P = px * perp + pz * axis;
    const Wide LA = px * s1 + py + pz * a1;
    const Wide LB = px * s2 + py + pz * a2;
    ApplyLineImpulse(vA, wA, vB, wB, mA, mB, iA, iB, P, LA, LB);
}
}  // namespace

void b2PrismaticJoint::InitVelocityConstraints(const b2SolverData& data) {
    [[maybe_unused]] auto [A, B, cA, aA, vA, wA, cB, aB, vB, wB] = BeginSolve(*this, data);

    const Frame f = MakeFrame(cA, aA, cB, aB, m_localAnchorA, m_localCenterA, m_localAnchorB, m_localCenterB,
                              m_localXAxisA, m_localYAxisA);
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;
    m_axis = f.axis;
    m_perp = f.perp;
    m_a1 = f.a1;
    m_a2 = f.a2;
    m_s1 = f.s1;
    m_s2 = f.s2;
    m_motorMass = Invert(mA + mB + iA * MulWide(m_a1, m_a1) + iB * MulWide(m_a2, m_a2));
    m_K = MakeK(mA, mB, iA, iB, m_s1, m_s2, m_a1, m_a2);
    m_pointSolver = m_K.Upper22();
    m_pointMass = math::Inverse(m_pointSolver);

    if (m_enableLimit) {
        const Fixed jointTranslation = b2Dot(m_axis, f.d);
        // Limits closer than 2 linearSlop (1 cm) act as a fixed translation.
        if (b2Abs(m_upperTranslation - m_lowerTranslation) < Fixed(2) * b2_linearSlop) {
            m_limitState = e_equalLimits;
        } else if (jointTranslation <= m_lowerTranslation) {
            if (m_limitState != e_atLowerLimit) {
                m_limitState = e_atLowerLimit;
                m_impulse.z = Wide();
            }
        } else if (jointTranslation >= m_upperTranslation) {
            if (m_limitState != e_atUpperLimit) {
                m_limitState = e_atUpperLimit;
                m_impulse.z = Wide();
            }
        } else {
            m_limitState = e_inactiveLimit;
            m_impulse.z = Wide();
        }
    } else {
        m_limitState = e_inactiveLimit;
        m_impulse.z = Wide();
    }
    // An active limit state is only set with the limit enabled: exactly when the velocity
    // iterations solve the whole K.
    if (m_limitState != e_inactiveLimit) m_limitSolver = m_K.Prepared();

    if (!m_enableMotor) m_motorImpulse = Wide();

    if (data.step.warmStarting) {
        const Fixed r = data.step.dtRatio;
        m_impulse = {WarmScaled(m_impulse.x, r), WarmScaled(m_impulse.y, r), WarmScaled(m_impulse.z, r)};
        m_motorImpulse = WarmScaled(m_motorImpulse, r);
        ApplyFrameImpulse(vA, wA, vB, wB, mA, mB, iA, iB, m_perp, m_axis, m_s1, m_s2, m_a1, m_a2, m_impulse.x,
                          m_impulse.y, m_motorImpulse + m_impulse.z);
    } else {
        m_impulse.SetZero();
        m_motorImpulse = Wide();
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

void b2PrismaticJoint::SolveVelocityConstraints(const b2SolverData& data) {
    b2WideVec2 vA = data.velocities[m_indexA].v;
    Wide wA = data.velocities[m_indexA].w;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;

    // Axial velocity: dot(axis, vB - vA) + a2 wB - a1 wA, in Q32.32.
    auto axial = [&]() { return DotW(m_axis, vB - vA) + wB * m_a2 - wA * m_a1; };

    // Solve the linear motor constraint.
    if (m_enableMotor && m_limitState != e_equalLimits) {
        const Wide Cdot = axial();
        Wide impulse = m_motorMass * (Wide(m_motorSpeed) - Cdot);
        const Wide oldImpulse = m_motorImpulse;
        const Wide maxImpulse = MulWide(data.step.dt, m_maxMotorForce);
        m_motorImpulse = b2Clamp(m_motorImpulse + impulse, -maxImpulse, maxImpulse);
        impulse = m_motorImpulse - oldImpulse;
        ApplyFrameImpulse(vA, wA, vB, wB, mA, mB, iA, iB, m_perp, m_axis, m_s1, m_s2, m_a1, m_a2, Wide(), Wide(),
                          impulse);
    }

    const b2WideVec2 Cdot1(DotW(m_perp, vB - vA) + wB * m_s2 - wA * m_s1, wB - wA);

    if (m_enableLimit && m_limitState != e_inactiveLimit) {
        // Solve the prismatic and limit constraints together.
        const Wide Cdot2 = axial();
        const b2WideVec3 f1 = m_impulse;
        const b2WideVec3 df = m_limitSolver.Solve33(-b2WideVec3(Cdot1.x, Cdot1.y, Cdot2));
        m_impulse += df;

        if (m_limitState == e_atLowerLimit) {
            m_impulse.z = b2Max(m_impulse.z, Wide());
        } else if (m_limitState == e_atUpperLimit) {
            m_impulse.z = b2Min(m_impulse.z, Wide());
        }

        // f2(1:2) = invK(1:2,1:2) * (-Cdot(1:2) - K(1:2,3) * (f2(3) - f1(3))) + f1(1:2)
        const Wide dz = m_impulse.z - f1.z;
        const b2WideVec2 b = -Cdot1 - b2WideVec2(dz * m_K.ez.x, dz * m_K.ez.y);
        const b2WideVec2 f2r = m_pointSolver.Solve(b) + b2WideVec2(f1.x, f1.y);
        m_impulse.x = f2r.x;
        m_impulse.y = f2r.y;

        const b2WideVec3 d = m_impulse - f1;
        ApplyFrameImpulse(vA, wA, vB, wB, mA, mB, iA, iB, m_perp, m_axis, m_s1, m_s2, m_a1, m_a2, d.x, d.y, d.z);
    } else {
        // Limit is inactive: just solve the prismatic constraint in block form.
        const b2WideVec2 df = -math::Mul(m_pointMass, Cdot1);
        m_impulse.x += df.x;
        m_impulse.y += df.y;
        ApplyFrameImpulse(vA, wA, vB, wB, mA, mB, iA, iB, m_perp, m_axis, m_s1, m_s2, m_a1, m_a2, df.x, df.y, Wide());
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

bool b2PrismaticJoint::SolvePositionConstraints(const b2SolverData& data) {
    b2Vec2 cA = data.positions[m_indexA].c;
    Fixed aA = data.positions[m_indexA].a;
    b2Vec2 cB = data.positions[m_indexB].c;
    Fixed aB = data.positions[m_indexB].a;
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;

    const Frame f = MakeFrame(cA, aA, cB, aB, m_localAnchorA, m_localCenterA, m_localAnchorB, m_localCenterB,
                              m_localXAxisA, m_localYAxisA);

    // Body angles are wrapped to [-pi, pi) independently, so the relative angle is wrapped too.
    const b2Vec2 C1(b2Dot(f.perp, f.d), math::WrapAngle(aB - aA - m_referenceAngle));
    Fixed linearError = b2Abs(C1.x);
    const Fixed angularError = b2Abs(C1.y);

    bool active = false;
    Fixed C2;
    if (m_enableLimit) {
        const Fixed translation = b2Dot(f.axis, f.d);
        if (b2Abs(m_upperTranslation - m_lowerTranslation) < Fixed(2) * b2_linearSlop) {
            // Prevent large linear corrections. (2.2.1 clamps the raw translation here; the
            // error is measured from the common limit value.)
            C2 = b2Clamp(translation - m_lowerTranslation, -b2_maxLinearCorrection, b2_maxLinearCorrection);
            linearError = b2Max(linearError, b2Abs(translation - m_lowerTranslation));
            active = true;
        } else if (translation <= m_lowerTranslation) {
            // Prevent large linear corrections and allow some slop.
            C2 = b2Clamp(translation - m_lowerTranslation + b2_linearSlop, -b2_maxLinearCorrection, Fixed());
            linearError = b2Max(linearError, m_lowerTranslation - translation);
            active = true;
        } else if (translation >= m_upperTranslation) {
            C2 = b2Clamp(translation - m_upperTranslation - b2_linearSlop, Fixed(), b2_maxLinearCorrection);
            linearError = b2Max(linearError, translation - m_upperTranslation);
            active = true;
        }
    }

    const b2WideMat33 K = MakeK(mA, mB, iA, iB, f.s1, f.s2, f.a1, f.a2);
    b2WideVec3 impulse;
    if (active) {
        impulse = K.Solve33(-b2Vec3(C1.x, C1.y, C2));
    } else {
        const b2WideVec2 impulse1 = K.Solve22(-C1);
        impulse = {impulse1.x, impulse1.y, Wide()};
    }

    ApplyFrameImpulse(cA, aA, cB, aB, mA, mB, iA, iB, f.perp, f.axis, f.s1, f.s2, f.a1, f.a2, impulse.x, impulse.y,
                      impulse.z);

    data.positions[m_indexA].c = cA;
    data.positions[m_indexA].a = aA;
    data.positions[m_indexB].c = cB;
    data.positions[m_indexB].a = aB;

    return linearError <= b2_linearSlop && angularError <= b2_angularSlop;
}

b2Vec2 b2PrismaticJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_localAnchorA); }
b2Vec2 b2PrismaticJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2PrismaticJoint::GetReactionForce(Fixed inv_dt) const {
    const b2WideVec2 P = m_impulse.x * m_perp + (m_motorImpulse + m_impulse.z) * m_axis;
    return {MulToFixed(P.x, inv_dt), MulToFixed(P.y, inv_dt)};
}

Fixed b2PrismaticJoint::GetReactionTorque(Fixed inv_dt) const { return MulToFixed(m_impulse.y, inv_dt); }

Fixed b2PrismaticJoint::GetJointTranslation() const {
    const b2Vec2 pA = m_bodyA->GetWorldPoint(m_localAnchorA);
    const b2Vec2 pB = m_bodyB->GetWorldPoint(m_localAnchorB);
    const b2Vec2 axis = m_bodyA->GetWorldVector(m_localXAxisA);
    return b2Dot(pB - pA, axis);
}

Fixed b2PrismaticJoint::GetJointSpeed() const {
    const b2Body* bA = m_bodyA;
    const b2Body* bB = m_bodyB;
    const b2Vec2 rA = b2Mul(bA->GetTransform().q, m_localAnchorA - bA->GetLocalCenter());
    const b2Vec2 rB = b2Mul(bB->GetTransform().q, m_localAnchorB - bB->GetLocalCenter());
    const b2Vec2 d = (bB->GetWorldCenter() + rB) - (bA->GetWorldCenter() + rA);
    const b2Vec2 axis = b2Mul(bA->GetTransform().q, m_localXAxisA);
    const b2Vec2 vA = bA->GetLinearVelocity(), vB = bB->GetLinearVelocity();
    const Fixed wA = bA->GetAngularVelocity(), wB = bB->GetAngularVelocity();
    return (b2DotWide(d, b2Cross(wA, axis)) + b2DotWide(axis, vB + b2Cross(wB, rB) - vA - b2Cross(wA, rA))).ToFixed();
}

Fixed b2PrismaticJoint::GetMotorForce(Fixed inv_dt) const { return MulToFixed(m_motorImpulse, inv_dt); }

void b2PrismaticJoint::EnableLimit(bool flag) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    if (flag != m_enableLimit) m_impulse.z = Wide();
    m_enableLimit = flag;
}

void b2PrismaticJoint::SetLimits(Fixed lower, Fixed upper) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_lowerTranslation = lower;
    m_upperTranslation = upper;
}

void b2PrismaticJoint::EnableMotor(bool flag) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_enableMotor = flag;
}

void b2PrismaticJoint::SetMotorSpeed(Fixed speed) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_motorSpeed = speed;
}

void b2PrismaticJoint::SetMaxMotorForce(Fixed force) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_maxMotorForce = force;
}

}  // namespace lockbox
