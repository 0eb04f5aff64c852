// The velocity set-up of a revolute joint iterated as a compact row (JointSolver.h): written
// straight into the row and its position row instead of into the joint, with the arms, the point
// block and the warm start unchecked where the rows' bounds prove them in range.
#include "JointMath.h"
#include "PointRow.h"
#include "dynamics/joints/JointSolver.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"

namespace lockbox {

using namespace pointrow;
using JointSolver = core_detail::Engine::Joints::Solver;

void JointSolver::LoadPositionRow(PositionRow& position, const Row& row, const b2RevoluteJoint& joint,
                                  const b2Vec2& localCenterA, const b2Vec2& localCenterB) noexcept {
    position.indexA = row.indexA;
    position.indexB = row.indexB;
    position.localAnchorA = joint.m_localAnchorA;
    position.localCenterA = localCenterA;
    position.localAnchorB = joint.m_localAnchorB;
    position.localCenterB = localCenterB;
    position.mA = row.mA;
    position.mB = row.mB;
    position.iA = row.iA;
    position.iB = row.iB;
}

#ifdef LOCKBOX_UNCHECKED_ROWS
bool JointSolver::SetUpRow(b2RevoluteJoint& joint, const b2SolverData& data, Row& row, PositionRow& position) noexcept {
    // b2RevoluteJoint::SetUpVelocity for a joint with its motor and limit disabled, written
    // straight into the rows. With the motor disabled the motor impulse is zero; with a zero
    // limit impulse the warm start's angular term is r x P alone, as an iteration's. Anything
    // else takes the joint's own set-up.
    const jointmath::BodyData A = jointmath::Load(joint.m_bodyA), B = jointmath::Load(joint.m_bodyB);
    if (joint.m_impulse.z != Wide() || (solver::Folded(A.invI) | solver::Folded(B.invI)) >= jointmath::kNarrowTurn) {
        return false;
    }
    row.indexA = A.index;
    row.indexB = B.index;
    row.mA = A.invMass;
    row.mB = B.invMass;
    row.iA = A.invI;
    row.iB = B.invI;
    LoadPositionRow(position, row, joint, A.localCenter, B.localCenter);
    // The position row's bound covers the arms and K that the set-up forms from the same
    // anchors, centres and masses.
    position.unchecked = PositionRowWidths(position);
    if (position.unchecked.poses == 0) return false;

    const Fixed aA = data.positions[A.index].a, aB = data.positions[B.index].a;
    PointArms<solver::UncheckedFixed>(position, data.Rotation(A.index, aA), data.Rotation(B.index, aB), row.rA, row.rB);
    using solver::UncheckedWide;
    const b2WideMat22 K = jointmath::PointK(row.rA, row.rB, UncheckedWide(A.invMass), UncheckedWide(B.invMass),
                                            UncheckedWide(A.invI), UncheckedWide(B.invI));
    row.pointMass = math::Inverse(b2WideSolver22(K.ex, K.ey));
    row.unchecked = PointRowWidths(row);
    row.revolute = &joint;

    joint.m_motorImpulse = Wide();
    joint.TrackAngle(aA, aB);
    joint.m_limitState = e_inactiveLimit;
    if (!data.step.warmStarting) {
        joint.m_impulse.SetZero();
        row.impulse = b2WideVec2();
        return true;
    }
    const Fixed ratio = data.step.dtRatio;
    joint.m_impulse = {WarmScaled(joint.m_impulse.x, ratio), WarmScaled(joint.m_impulse.y, ratio), Wide()};
    row.impulse = b2WideVec2(joint.m_impulse.x, joint.m_impulse.y);
    WarmStartPointRow(row, data, true);
    return true;
}
#endif

void JointSolver::WarmStartPointRow(const Row& row, const b2SolverData& data, bool uncheckedAllowed) noexcept {
    b2Velocity& velA = data.velocities[row.indexA];
    b2Velocity& velB = data.velocities[row.indexB];
#ifdef LOCKBOX_UNCHECKED_ROWS
    // PointRowWidths bounds the carried impulse's application too.
    if (uncheckedAllowed && PointRowFits(row, velA, velB)) {
        using solver::UncheckedWide;
        auto vA = solver::UncheckedVec2::From(velA.v), vB = solver::UncheckedVec2::From(velB.v);
        UncheckedWide wA = velA.w, wB = velB.w;
        ApplyPointImpulse(row, vA, wA, vB, wB, UncheckedWide(row.impulse.x), UncheckedWide(row.impulse.y));
        velA = b2Velocity{vA.ToWide(), wA.ToWide()};
        velB = b2Velocity{vB.ToWide(), wB.ToWide()};
        return;
    }
#else
    (void)uncheckedAllowed;
#endif
    ApplyPointImpulse(row, velA.v, velA.w, velB.v, velB.w, row.impulse.x, row.impulse.y);
}

}  // namespace lockbox
