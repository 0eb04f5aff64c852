// b2RevoluteJoint solver (Box2D 2.2.1 b2RevoluteJoint.cpp) with a Q32.32 K matrix solved
// exactly (WideMatrix.h) and a continuous joint angle for limits across turns.
//
// Point-to-point constraint: Cdot = vB + wB x rB - vA - wA x rA. Motor: Cdot = wB - wA.
// Limit: C = angle - limit, one-sided inequality.
#include "lockbox/dynamics/joints/RevoluteJoint.h"

#include "JointMath.h"
#include "dynamics/unchecked/Widths.h"

namespace lockbox {

using namespace jointmath;

void b2RevoluteJointDef::Initialize(b2Body* bA, b2Body* bB, const b2Vec2& anchor) {
    bodyA = bA;
    bodyB = bB;
    localAnchorA = bodyA->GetLocalPoint(anchor);
    localAnchorB = bodyB->GetLocalPoint(anchor);
    referenceAngle = bodyB->GetAngle() - bodyA->GetAngle();
}

b2RevoluteJoint::b2RevoluteJoint(const b2RevoluteJointDef* def) : b2Joint(def) {
    m_localAnchorA = def->localAnchorA;
    m_localAnchorB = def->localAnchorB;
    m_referenceAngle = def->referenceAngle;
    m_lowerAngle = def->lowerAngle;
    m_upperAngle = def->upperAngle;
    m_maxMotorTorque = def->maxMotorTorque;
    m_motorSpeed = def->motorSpeed;
    m_enableLimit = def->enableLimit;
    m_enableMotor = def->enableMotor;
    m_angleBase = math::WrapAngle(m_bodyB->GetAngle() - m_bodyA->GetAngle() - m_referenceAngle);
}

Fixed b2RevoluteJoint::ContinuousAngle(Fixed aA, Fixed aB) const noexcept {
    // aB - aA - ref differs from the continuous angle by whole turns; WrapAngle picks the
    // turn count that puts it within pi of the last value (exact 2 pi, 0.5 ULP, no drift).
    return m_angleBase + math::WrapAngle(aB - aA - m_referenceAngle - m_angleBase);
}

Fixed b2RevoluteJoint::TrackAngle(Fixed aA, Fixed aB) noexcept {
    Fixed jointAngle = ContinuousAngle(aA, aB);
    // Without a limit, beyond kMaxContinuousAngle the turn count restarts from the wrapped
    // angle, so a joint that spins freely for hours never saturates Q16.16. With a limit the
    // angle is held near the limits (|limit| <= 16000 rad) and is never reset.
    if (!m_enableLimit && b2Abs(jointAngle) > kMaxContinuousAngle) jointAngle = math::WrapAngle(jointAngle);
    m_angleBase = jointAngle;
    return jointAngle;
}

namespace {
// The point-plus-angle K of 2.2.1 (symmetric). A joint iterated as a row reads only the point
// block (pointOnly): its angular column is then formed only when it could saturate
// (kNarrowTurn), so that every overflow 2.2.1's whole K reports is still counted.
b2WideMat33 PointAngleK(Wide mA, Wide mB, Wide iA, Wide iB, const b2Vec2& rA, const b2Vec2& rB, bool pointOnly) {
    b2WideMat33 K;
    K.ex.x = mA + mB + iA * MulWide(rA.y, rA.y) + iB * MulWide(rB.y, rB.y);
    K.ey.x = -(iA * MulWide(rA.y, rA.x)) - iB * MulWide(rB.y, rB.x);
    K.ex.y = K.ey.x;
    K.ey.y = mA + mB + iA * MulWide(rA.x, rA.x) + iB * MulWide(rB.x, rB.x);
    if (pointOnly && (solver::Folded(iA) | solver::Folded(iB)) < kNarrowTurn) return K;
    K.ez.x = -(iA * rA.y) - iB * rB.y;
    K.ez.y = iA * rA.x + iB * rB.x;
    K.ex.z = K.ez.x;
    K.ey.z = K.ez.y;
    K.ez.z = iA + iB;
    return K;
}
}  // namespace

void b2RevoluteJoint::InitVelocityConstraints(const b2SolverData& data) { SetUpVelocity(data, true); }

b2RevoluteJoint::PointSetUp b2RevoluteJoint::SetUpVelocity(const b2SolverData& data, bool keepSolverFields) {
    [[maybe_unused]] auto [A, B, cA, aA, vA, wA, cB, aB, vB, wB] =
        keepSolverFields ? BeginSolve(*this, data) : core_detail::Engine::Joints::LoadSolve(*this, data);

    PointSetUp out;
    out.indexA = A.index;
    out.indexB = B.index;
    out.localCenterA = A.localCenter;
    out.localCenterB = B.localCenter;
    out.mA = A.invMass;
    out.mB = B.invMass;
    out.iA = A.invI;
    out.iB = B.invI;

    const b2Rot qA = data.Rotation(A.index, aA), qB = data.Rotation(B.index, aB);
    out.rA = b2Mul(qA, m_localAnchorA - A.localCenter);
    out.rB = b2Mul(qB, m_localAnchorB - B.localCenter);

    const Wide iA = A.invI, iB = B.invI;
    const bool fixedRotation = (iA + iB == Wide());
    const b2WideMat33 K = PointAngleK(A.invMass, B.invMass, iA, iB, out.rA, out.rB, !keepSolverFields);
    const b2WideSolver22 pointSolver = K.Upper22();
    out.pointMass = math::Inverse(pointSolver);
    if (keepSolverFields) {
        // Only the motor and the limit read the motor mass (a division); a row joint has neither.
        m_motorMass = Invert(iA + iB);
        m_rA = out.rA;
        m_rB = out.rB;
        m_mass = K;
        m_pointSolver = pointSolver;
        m_pointMass = out.pointMass;
    }

    if (!m_enableMotor || fixedRotation) m_motorImpulse = Wide();

    const Fixed jointAngle = TrackAngle(aA, aB);
    if (m_enableLimit && !fixedRotation) {
        // Equal limits within 2 angularSlop (4 degrees) are solved as a fixed angle.
        if (b2Abs(m_upperAngle - m_lowerAngle) < Fixed(2) * b2_angularSlop) {
            m_limitState = e_equalLimits;
        } else if (jointAngle <= m_lowerAngle) {
            if (m_limitState != e_atLowerLimit) m_impulse.z = Wide();
            m_limitState = e_atLowerLimit;
        } else if (jointAngle >= m_upperAngle) {
            if (m_limitState != e_atUpperLimit) m_impulse.z = Wide();
            m_limitState = e_atUpperLimit;
        } else {
            m_limitState = e_inactiveLimit;
            m_impulse.z = Wide();
        }
    } else {
        m_limitState = e_inactiveLimit;
    }
    // An active limit state is only set with the limit enabled and rotation free: exactly when
    // the velocity iterations solve the whole K (and the solver fields are kept).
    if (m_limitState != e_inactiveLimit) m_limitSolver = K.Prepared();

    if (data.step.warmStarting) {
        // Scale impulses to support a variable time step.
        const Fixed r = data.step.dtRatio;
        m_impulse = {WarmScaled(m_impulse.x, r), WarmScaled(m_impulse.y, r), WarmScaled(m_impulse.z, r)};
        m_motorImpulse = WarmScaled(m_motorImpulse, r);

        const b2WideVec2 P(m_impulse.x, m_impulse.y);
        vA.x -= A.invMass * P.x;
        vA.y -= A.invMass * P.y;
        wA -= iA * (b2Cross(out.rA, P) + m_motorImpulse + m_impulse.z);
        vB.x += B.invMass * P.x;
        vB.y += B.invMass * P.y;
        wB += iB * (b2Cross(out.rB, P) + m_motorImpulse + m_impulse.z);
    } else {
        m_impulse.SetZero();
        m_motorImpulse = Wide();
    }

    data.velocities[A.index].v = vA;
    data.velocities[A.index].w = wA;
    data.velocities[B.index].v = vB;
    data.velocities[B.index].w = wB;
    return out;
}

void b2RevoluteJoint::SolveVelocityConstraints(const b2SolverData& data) {
    b2WideVec2 vA = data.velocities[m_indexA].v;
    Wide wA = data.velocities[m_indexA].w;
    b2WideVec2 vB = data.velocities[m_indexB].v;
    Wide wB = data.velocities[m_indexB].w;

    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;
    const bool fixedRotation = (iA + iB == Wide());

    // Solve the motor constraint.
    if (m_enableMotor && m_limitState != e_equalLimits && !fixedRotation) {
        const Wide Cdot = wB - wA - Wide(m_motorSpeed);
        Wide impulse = -(m_motorMass * Cdot);
        const Wide oldImpulse = m_motorImpulse;
        const Wide maxImpulse = MulWide(data.step.dt, m_maxMotorTorque);
        m_motorImpulse = b2Clamp(m_motorImpulse + impulse, -maxImpulse, maxImpulse);
        impulse = m_motorImpulse - oldImpulse;
        wA -= iA * impulse;
        wB += iB * impulse;
    }

    const b2WideVec2 Cdot1 = PointVelocity(vB, wB, m_rB) - PointVelocity(vA, wA, m_rA);

    // Solve the limit constraint.
    if (m_enableLimit && m_limitState != e_inactiveLimit && !fixedRotation) {
        const Wide Cdot2 = wB - wA;
        b2WideVec3 impulse = -m_limitSolver.Solve33(b2WideVec3(Cdot1.x, Cdot1.y, Cdot2));

        if (m_limitState == e_equalLimits) {
            m_impulse += impulse;
        } else if (m_limitState == e_atLowerLimit || m_limitState == e_atUpperLimit) {
            const Wide newImpulse = m_impulse.z + impulse.z;
            const bool violates = m_limitState == e_atLowerLimit ? newImpulse < Wide() : newImpulse > Wide();
            if (violates) {
                // Clamp the accumulated limit impulse to zero and re-solve the point part.
                const b2WideVec2 rhs =
                    -b2WideVec2(Cdot1) + b2WideVec2(m_impulse.z * m_mass.ez.x, m_impulse.z * m_mass.ez.y);
                const b2WideVec2 reduced = m_pointSolver.Solve(rhs);
                impulse.x = reduced.x;
                impulse.y = reduced.y;
                impulse.z = -m_impulse.z;
                m_impulse.x += reduced.x;
                m_impulse.y += reduced.y;
                m_impulse.z = Wide();
            } else {
                m_impulse += impulse;
            }
        }

        const b2WideVec2 P(impulse.x, impulse.y);
        vA.x -= mA * P.x;
        vA.y -= mA * P.y;
        wA -= iA * (b2Cross(m_rA, P) + impulse.z);
        vB.x += mB * P.x;
        vB.y += mB * P.y;
        wB += iB * (b2Cross(m_rB, P) + impulse.z);
    } else {
        // Solve the point-to-point constraint.
        const b2WideVec2 impulse = -math::Mul(m_pointMass, Cdot1);
        m_impulse.x += impulse.x;
        m_impulse.y += impulse.y;
        const BodyData A{m_indexA, m_localCenterA, mA, iA};
        const BodyData B{m_indexB, m_localCenterB, mB, iB};
        ApplyNeg(vA, wA, A, m_rA, impulse);
        ApplyPos(vB, wB, B, m_rB, impulse);
    }

    data.velocities[m_indexA].v = vA;
    data.velocities[m_indexA].w = wA;
    data.velocities[m_indexB].v = vB;
    data.velocities[m_indexB].w = wB;
}

bool b2RevoluteJoint::SolvePositionConstraints(const b2SolverData& data) {
    b2Vec2 cA = data.positions[m_indexA].c;
    Fixed aA = data.positions[m_indexA].a;
    b2Vec2 cB = data.positions[m_indexB].c;
    Fixed aB = data.positions[m_indexB].a;

    Fixed angularError;
    const Wide mA = m_invMassA, mB = m_invMassB, iA = m_invIA, iB = m_invIB;
    const bool fixedRotation = (iA + iB == Wide());

    // Solve the angular limit constraint.
    if (m_enableLimit && m_limitState != e_inactiveLimit && !fixedRotation) {
        const Fixed angle = ContinuousAngle(aA, aB);
        Fixed C;
        if (m_limitState == e_equalLimits) {
            // Prevent large angular corrections.
            C = b2Clamp(angle - m_lowerAngle, -b2_maxAngularCorrection, b2_maxAngularCorrection);
            angularError = b2Abs(C);
        } else if (m_limitState == e_atLowerLimit) {
            C = angle - m_lowerAngle;
            angularError = -C;
            // Prevent large angular corrections and allow some slop.
            C = b2Clamp(C + b2_angularSlop, -b2_maxAngularCorrection, Fixed());
        } else {
            C = angle - m_upperAngle;
            angularError = C;
            C = b2Clamp(C - b2_angularSlop, Fixed(), b2_maxAngularCorrection);
        }
        const Wide limitImpulse = -(m_motorMass * C);
        aA -= MulToFixed(iA, limitImpulse);
        aB += MulToFixed(iB, limitImpulse);
    }

    // Solve the point-to-point constraint.
    const b2Rot qA = data.Rotation(m_indexA, aA), qB = data.Rotation(m_indexB, aB);
    const b2Vec2 rA = b2Mul(qA, m_localAnchorA - m_localCenterA);
    const b2Vec2 rB = b2Mul(qB, m_localAnchorB - m_localCenterB);
    const b2Vec2 C = cB + rB - cA - rA;
    const bool closed = LengthWithin(C, b2_linearSlop);

    const b2WideVec2 impulse = PointGapImpulse(C, rA, rB, mA, mB, iA, iB);

    const BodyData A{m_indexA, m_localCenterA, mA, iA};
    const BodyData B{m_indexB, m_localCenterB, mB, iB};
    ApplyNeg(cA, aA, A, rA, impulse);
    ApplyPos(cB, aB, B, rB, impulse);

    data.positions[m_indexA].c = cA;
    data.positions[m_indexA].a = aA;
    data.positions[m_indexB].c = cB;
    data.positions[m_indexB].a = aB;

    return closed && angularError <= b2_angularSlop;
}

b2Vec2 b2RevoluteJoint::GetAnchorA() const { return m_bodyA->GetWorldPoint(m_localAnchorA); }
b2Vec2 b2RevoluteJoint::GetAnchorB() const { return m_bodyB->GetWorldPoint(m_localAnchorB); }

b2Vec2 b2RevoluteJoint::GetReactionForce(Fixed inv_dt) const {
    return {MulToFixed(m_impulse.x, inv_dt), MulToFixed(m_impulse.y, inv_dt)};
}

Fixed b2RevoluteJoint::GetReactionTorque(Fixed inv_dt) const { return MulToFixed(m_impulse.z, inv_dt); }

Fixed b2RevoluteJoint::GetJointAngle() const { return ContinuousAngle(m_bodyA->GetAngle(), m_bodyB->GetAngle()); }

Fixed b2RevoluteJoint::GetJointSpeed() const { return m_bodyB->GetAngularVelocity() - m_bodyA->GetAngularVelocity(); }

Fixed b2RevoluteJoint::GetMotorTorque(Fixed inv_dt) const { return MulToFixed(m_motorImpulse, inv_dt); }

void b2RevoluteJoint::EnableMotor(bool flag) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_enableMotor = flag;
}

void b2RevoluteJoint::SetMotorSpeed(Fixed speed) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_motorSpeed = speed;
}

void b2RevoluteJoint::SetMaxMotorTorque(Fixed torque) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_maxMotorTorque = torque;
}

void b2RevoluteJoint::EnableLimit(bool flag) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    if (flag != m_enableLimit) m_impulse.z = Wide();
    m_enableLimit = flag;
}

void b2RevoluteJoint::SetLimits(Fixed lower, Fixed upper) {
    m_bodyA->SetAwake(true);
    m_bodyB->SetAwake(true);
    m_lowerAngle = lower;
    m_upperAngle = upper;
}

}  // namespace lockbox
