#include "dynamics/joints/JointSolver.h"

#include "JointMath.h"
#include "dynamics/unchecked/UncheckedWide.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"

namespace lockbox {

using namespace jointmath;
using JointSolver = core_detail::Engine::Joints::Solver;

namespace {
// The set-up's first touch of a joint misses the cache in a large graph (the joints are spread
// over the heap); asking for a joint some places ahead overlaps those misses with the set-up's
// arithmetic. A hint only: it changes no result.
constexpr int32 kPrefetchAhead = 4;
void Prefetch(const b2Joint* joint) noexcept {
#if defined(__GNUC__) || defined(__clang__)
    const auto* bytes = reinterpret_cast<const char*>(joint);
    for (int line = 0; line < 4; ++line) __builtin_prefetch(bytes + 64 * line);
#else
    (void)joint;
#endif
}

// r x P for the point row, on either number type.
inline Wide ArmCross(const b2Vec2& r, Wide px, Wide py) noexcept { return b2Cross(r, b2WideVec2(px, py)); }
#ifdef LOCKBOX_UNCHECKED_ROWS
inline solver::UncheckedWide ArmCross(const b2Vec2& r, solver::UncheckedWide px, solver::UncheckedWide py) noexcept {
    return solver::UncheckedWide::Cross(r, px, py);
}
#endif

// One iteration of a revolute joint whose motor and limit are idle: the point-to-point branch
// of b2RevoluteJoint::SolveVelocityConstraints, the same operations in the same order (its
// PointVelocity, math::Mul, ApplyNeg and ApplyPos written out), on Wide or, for a row proven to
// stay in range, on UncheckedWide.
template <class N, class V>
[[gnu::always_inline]] inline void PointRow(const JointSolver::Row& row, V& vA, N& wA, V& vB, N& wB,
                                            V& accumulated) noexcept {
    const N cx = (vB.x - wB * row.rB.y) - (vA.x - wA * row.rA.y);
    const N cy = (vB.y + wB * row.rB.x) - (vA.y + wA * row.rA.x);
    const b2WideMat22& m = row.pointMass;
    const N px = -(N(m.ex.x) * cx + N(m.ey.x) * cy);
    const N py = -(N(m.ex.y) * cx + N(m.ey.y) * cy);
    accumulated.x += px;
    accumulated.y += py;
    vA.x -= N(row.mA) * px;
    vA.y -= N(row.mA) * py;
    wA -= N(row.iA) * ArmCross(row.rA, px, py);
    vB.x += N(row.mB) * px;
    vB.y += N(row.mB) * py;
    wB += N(row.iB) * ArmCross(row.rB, px, py);
}

}  // namespace

void JointSolver::SolvePointRow(Row& row, const b2SolverData& data, bool uncheckedAllowed) noexcept {
    b2Velocity& velA = data.velocities[row.indexA];
    b2Velocity& velB = data.velocities[row.indexB];
#ifdef LOCKBOX_UNCHECKED_ROWS
    const uint64_t velocities = solver::FoldedPair(velA.v, velA.w, velB.v, velB.w);
    const uint64_t impulse = solver::Folded(row.impulse.x) | solver::Folded(row.impulse.y);
    if (uncheckedAllowed && solver::Within(velocities, row.unchecked.velocities) &&
        solver::Within(impulse, row.unchecked.impulses)) {
        using solver::UncheckedVec2, solver::UncheckedWide;
        auto vA = UncheckedVec2::From(velA.v), vB = UncheckedVec2::From(velB.v);
        UncheckedWide wA = velA.w, wB = velB.w;
        auto accumulated = UncheckedVec2::From(row.impulse);
        PointRow(row, vA, wA, vB, wB, accumulated);
        velA.v = vA.ToWide();
        velA.w = wA.ToWide();
        velB.v = vB.ToWide();
        velB.w = wB.ToWide();
        row.impulse = accumulated.ToWide();
        return;
    }
#else
    (void)uncheckedAllowed;
#endif
    b2WideVec2 vA = velA.v;
    Wide wA = velA.w;
    b2WideVec2 vB = velB.v;
    Wide wB = velB.w;
    PointRow(row, vA, wA, vB, wB, row.impulse);
    velA.v = vA;
    velA.w = wA;
    velB.v = vB;
    velB.w = wB;
}

namespace {

// One position iteration of a revolute joint whose limit is idle: the point-to-point part of
// b2RevoluteJoint::SolvePositionConstraints (the angular error is then zero).
bool SolvePointPositionRow(const JointSolver::PositionRow& row, const b2SolverData& data) noexcept {
    b2Position& posA = data.positions[row.indexA];
    b2Position& posB = data.positions[row.indexB];
    b2Vec2 cA = posA.c;
    Fixed aA = posA.a;
    b2Vec2 cB = posB.c;
    Fixed aB = posB.a;

    const Wide mA = row.mA, mB = row.mB, iA = row.iA, iB = row.iB;
    const b2Rot qA = data.Rotation(row.indexA, aA), qB = data.Rotation(row.indexB, aB);
    const b2Vec2 rA = b2Mul(qA, row.localAnchorA - row.localCenterA);
    const b2Vec2 rB = b2Mul(qB, row.localAnchorB - row.localCenterB);
    const b2Vec2 C = cB + rB - cA - rA;
    const bool closed = LengthWithin(C, b2_linearSlop);

    const b2WideVec2 impulse = PointGapImpulse(C, rA, rB, mA, mB, iA, iB);

    const BodyData A{row.indexA, row.localCenterA, mA, iA};
    const BodyData B{row.indexB, row.localCenterB, mB, iB};
    ApplyNeg(cA, aA, A, rA, impulse);
    ApplyPos(cB, aB, B, rB, impulse);

    posA.c = cA;
    posA.a = aA;
    posB.c = cB;
    posB.a = aB;

    return closed;
}
}  // namespace

void JointSolver::Begin(int32 count) {
    if (m_rows.size() < static_cast<size_t>(count)) {
        m_rows.resize(static_cast<size_t>(count));
        m_positionRows.resize(static_cast<size_t>(count));
    }
    m_count = count;
}

void JointSolver::InitVelocityConstraints(b2Joint* const* joints, int32 begin, int32 end, const b2SolverData& data) {
    for (int32 i = begin; i < end; ++i) {
        b2Joint* joint = joints[i];
        if (i + kPrefetchAhead < end) Prefetch(joints[i + kPrefetchAhead]);
        Row& row = m_rows[static_cast<size_t>(i)];
        row.joint = joint;
        row.revolute = nullptr;
        if (joint->m_type != e_revoluteJoint) {
            joint->InitVelocityConstraints(data);
            continue;
        }

        // The iteration takes the point-only branch exactly when the motor block and the limit
        // block are both skipped; the switches they test are fixed for the step by the set-up.
        // With both disabled the joint is certain to be a row, and its own solver fields, which
        // only its own iterations would read, are not written.
        auto* revolute = static_cast<b2RevoluteJoint*>(joint);
        const bool rowOnly = !revolute->m_enableMotor && !revolute->m_enableLimit;
        const b2RevoluteJoint::PointSetUp s = revolute->SetUpVelocity(data, !rowOnly);
        const bool fixedRotation = (s.iA + s.iB == Wide());
        const bool motor = revolute->m_enableMotor && revolute->m_limitState != e_equalLimits && !fixedRotation;
        const bool limit = revolute->m_enableLimit && revolute->m_limitState != e_inactiveLimit && !fixedRotation;
        if (motor || limit) continue;
        row.indexA = s.indexA;
        row.indexB = s.indexB;
        row.rA = s.rA;
        row.rB = s.rB;
        row.mA = s.mA;
        row.mB = s.mB;
        row.iA = s.iA;
        row.iB = s.iB;
        row.pointMass = s.pointMass;
        row.impulse = b2WideVec2(revolute->m_impulse.x, revolute->m_impulse.y);
        row.revolute = revolute;
        row.unchecked = PointRowWidths(row);

        PositionRow& position = m_positionRows[static_cast<size_t>(i)];
        position.indexA = s.indexA;
        position.indexB = s.indexB;
        position.localAnchorA = revolute->m_localAnchorA;
        position.localCenterA = s.localCenterA;
        position.localAnchorB = revolute->m_localAnchorB;
        position.localCenterB = s.localCenterB;
        position.mA = s.mA;
        position.mB = s.mB;
        position.iA = s.iA;
        position.iB = s.iB;
    }
}

solver::InputWidths JointSolver::PointRowWidths(const Row& row) noexcept {
    using namespace solver;
    constexpr int kWideShift = Wide::kFractionBits;
    constexpr int kFixedShift = Fixed::kFractionBits;
    const int arm = WidthOf(Folded(row.rA.x) | Folded(row.rA.y) | Folded(row.rB.x) | Folded(row.rB.y));
    const b2WideMat22& m = row.pointMass;
    const int mass = WidthOf(Folded(m.ex.x) | Folded(m.ex.y) | Folded(m.ey.x) | Folded(m.ey.y));
    const int resp = WidthOf(Folded(row.mA) | Folded(row.mB) | Folded(row.iA) | Folded(row.iB));
    // The point's relative velocity: v - w r (w r in 64 bits), B's less A's.
    const Slopes point = Sum(kVelocity, Times(kVelocity, arm, kFixedShift));
    const Slopes cdot = Sum(point, point);
    // The impulse -(M Cdot), added to the accumulated one.
    const Slopes impulse = Sum(Times(cdot, mass, kWideShift), Times(cdot, mass, kWideShift));
    // r x P: two products exact in 128 bits, their difference rounded once.
    const Slopes cross = Plus(Times(impulse, arm, kFixedShift), 1);
    Slopes widest = Max(Max(cdot, Product64(kVelocity, arm)), Sum(kImpulse, impulse));
    widest = Max(widest, Max(cross, Sum(kVelocity, Times(impulse, resp, kWideShift))));
    widest = Max(widest, Sum(kVelocity, Times(cross, resp, kWideShift)));
    return WidthsFor(widest);
}

void JointSolver::SolveVelocityConstraints(const b2SolverData& data, int32 begin, int32 end) {
    Row* rows = m_rows.data();
    const bool uncheckedAllowed = solver::UncheckedRowsAllowed();
    for (int32 i = begin; i < end; ++i) {
        Row& row = rows[i];
        if (row.revolute != nullptr) {
            SolvePointRow(row, data, uncheckedAllowed);
        } else {
            row.joint->SolveVelocityConstraints(data);
        }
    }
}

void JointSolver::StoreImpulses(int32 begin, int32 end) const {
    for (int32 i = begin; i < end; ++i) {
        const Row& row = m_rows[static_cast<size_t>(i)];
        if (row.revolute == nullptr) continue;
        row.revolute->m_impulse.x = row.impulse.x;
        row.revolute->m_impulse.y = row.impulse.y;
    }
}

}  // namespace lockbox

namespace lockbox {

bool JointSolver::SolvePositionConstraints(const b2SolverData& data, int32 begin, int32 end) const {
    bool okay = true;
    for (int32 i = begin; i < end; ++i) {
        const Row& row = m_rows[static_cast<size_t>(i)];
        const bool jointOkay = row.revolute != nullptr
                                   ? SolvePointPositionRow(m_positionRows[static_cast<size_t>(i)], data)
                                   : row.joint->SolvePositionConstraints(data);
        okay = okay && jointOkay;
    }
    return okay;
}

}  // namespace lockbox
