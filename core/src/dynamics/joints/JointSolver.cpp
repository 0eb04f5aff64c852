#include "dynamics/joints/JointSolver.h"

#include <algorithm>
#include <type_traits>

#include "JointMath.h"
#include "PointRow.h"
#include "dynamics/unchecked/UncheckedWide.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"

namespace lockbox {

using namespace jointmath;
using namespace pointrow;
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
    ApplyPointImpulse(row, vA, wA, vB, wB, px, py);
}

}  // namespace

void JointSolver::SolvePointRow(Row& row, const b2SolverData& data, bool uncheckedAllowed) noexcept {
    b2Velocity& velA = data.velocities[row.indexA];
    b2Velocity& velB = data.velocities[row.indexB];
#ifdef LOCKBOX_UNCHECKED_ROWS
    if (uncheckedAllowed && PointRowFits(row, velA, velB)) {
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

// A body's centre and angle in a position row, on Fixed or solver::UncheckedFixed.
template <class F>
struct Pose {
    F x, y, a;

    static Pose Load(const b2Position& p) noexcept { return {F(p.c.x), F(p.c.y), F(p.a)}; }
    void Store(b2Position& p) const noexcept {
        p.c = b2Vec2(Fixed(x), Fixed(y));
        p.a = Fixed(a);
    }
};

// The anchors' arms, and the impulse that closes the gap between the anchors.
struct Gap {
    b2Vec2 rA, rB;
    b2WideVec2 impulse;
    bool closed = false;  ///< the gap is within the linear slop
};

// The point-to-point part of b2RevoluteJoint::SolvePositionConstraints, the same operations in
// the same order, in two halves: the gap between the anchors and the impulse that closes it,
// then that impulse applied to both bodies (its ApplyNeg and ApplyPos written out). Each half
// runs on Fixed and Wide or, where it is proven to stay in range, on their unchecked twins.
template <class F, class N>
[[gnu::always_inline]] inline Gap PointGap(const JointSolver::PositionRow& row, const b2Rot& qA, const b2Rot& qB,
                                           const Pose<F>& A, const Pose<F>& B) noexcept {
    Gap g;
    PointArms<F>(row, qA, qB, g.rA, g.rB);
    const b2Vec2 C(Fixed(B.x + F(g.rB.x) - A.x - F(g.rA.x)), Fixed(B.y + F(g.rB.y) - A.y - F(g.rA.y)));
    g.closed = LengthWithin(C, b2_linearSlop);
    // On a proven row K cannot saturate, and a zero gap's solve gives exactly zero (zero
    // numerators): a joint at rest needs neither K nor the solve.
    if constexpr (!std::is_same_v<N, Wide>) {
        if (C.x == Fixed() && C.y == Fixed()) return g;
    }
    g.impulse = PointGapImpulse(C, g.rA, g.rB, N(row.mA), N(row.mB), N(row.iA), N(row.iB));
    return g;
}

template <class F, class N>
[[gnu::always_inline]] inline void ApplyGapImpulse(const JointSolver::PositionRow& row, const Gap& g, Pose<F>& A,
                                                   Pose<F>& B) noexcept {
    const N px = g.impulse.x, py = g.impulse.y;
    const F dxA = MulToFixed(N(row.mA), px), dyA = MulToFixed(N(row.mA), py);
    A.x -= dxA;
    A.y -= dyA;
    A.a -= MulToFixed(N(row.iA), ArmCross(g.rA, px, py));
    if (SharesLinearChange<N>(row)) {
        B.x += dxA;
        B.y += dyA;
    } else {
        B.x += MulToFixed(N(row.mB), px);
        B.y += MulToFixed(N(row.mB), py);
    }
    B.a += MulToFixed(N(row.iB), ArmCross(g.rB, px, py));
}

// The tested correction, applied to the bodies where they are stored.
void ApplyGap(const JointSolver::PositionRow& row, const Gap& g, b2Position& posA, b2Position& posB) noexcept {
    auto A = Pose<Fixed>::Load(posA), B = Pose<Fixed>::Load(posB);
    ApplyGapImpulse<Fixed, Wide>(row, g, A, B);
    A.Store(posA);
    B.Store(posB);
}

}  // namespace

bool JointSolver::SolvePointPositionRow(const PositionRow& row, const b2SolverData& data,
                                        bool uncheckedAllowed) noexcept {
    b2Position& posA = data.positions[row.indexA];
    b2Position& posB = data.positions[row.indexB];
    const b2Rot qA = data.Rotation(row.indexA, posA.a), qB = data.Rotation(row.indexB, posB.a);
#ifdef LOCKBOX_UNCHECKED_ROWS
    using solver::Folded;
    const uint64_t poses = solver::FoldedPair(posA.c, posA.a, posB.c, posB.a);
    if (uncheckedAllowed && solver::Within(poses, row.unchecked.poses)) {
        using solver::UncheckedFixed, solver::UncheckedWide;
        auto A = Pose<UncheckedFixed>::Load(posA), B = Pose<UncheckedFixed>::Load(posB);
        const Gap g = PointGap<UncheckedFixed, UncheckedWide>(row, qA, qB, A, B);
        // A zero impulse moves neither body.
        if (g.impulse.x == Wide() && g.impulse.y == Wide()) return g.closed;
        if (solver::Within(Folded(g.impulse.x) | Folded(g.impulse.y), row.unchecked.impulses)) {
            ApplyGapImpulse<UncheckedFixed, UncheckedWide>(row, g, A, B);
            A.Store(posA);
            B.Store(posB);
        } else {
            ApplyGap(row, g, posA, posB);
        }
        return g.closed;
    }
#else
    (void)uncheckedAllowed;
#endif
    const Gap g = PointGap<Fixed, Wide>(row, qA, qB, Pose<Fixed>::Load(posA), Pose<Fixed>::Load(posB));
    ApplyGap(row, g, posA, posB);
    return g.closed;
}

JointSolver::PositionWidths JointSolver::PositionRowWidths(const PositionRow& row) noexcept {
    using namespace solver;
    // The arms' local vectors, exact in 64 bits (the row subtracts them without a test when the
    // difference fits).
    const auto local = [](const b2Vec2& anchor, const b2Vec2& centre) {
        return Folded(int64_t{anchor.x.Raw()} - centre.x.Raw()) | Folded(int64_t{anchor.y.Raw()} - centre.y.Raw());
    };
    // A rotation has |c|, |s| <= 1 (raw 2^16), so |q v| <= 2 max(|v.x|, |v.y|): two bits wider.
    const int arm = WidthOf(local(row.localAnchorA, row.localCenterA) | local(row.localAnchorB, row.localCenterB)) + 2;
    // The gap B + rB - A - rA of bodies and arms within kPoseWidth stays below 2^31.
    if (arm > kPoseWidth) return {};
    const int mass = WidthOf(Folded(row.mA) | Folded(row.mB));
    const int turn = WidthOf(Folded(row.iA) | Folded(row.iB));
    // K: sums of four terms, inverse masses and i r^2 (an exact r^2 times i, rounded by 2^32).
    if (std::max(mass, turn + 2 * arm - 31) + 2 > kWidestResult) return {};
    // An impulse of width w changes a centre by m p (rounded by 2^48: mass + w - 47 bits) and an
    // angle by i (r x p) (r x p rounded by 2^16 to a Wide of arm + w - 14 bits, then by 2^48:
    // turn + arm + w - 61 bits). Changes within kPoseWidth keep the bodies below 2^30.
    const int impulses =
        std::min({kPoseWidth + 47 - mass, kWidestResult + 14 - arm, kPoseWidth + 61 - turn - arm, kWidestResult});
    return {static_cast<uint8_t>(kPoseWidth), static_cast<uint8_t>(std::max(impulses, 0))};
}

void JointSolver::Begin(int32 count) {
    if (m_rows.size() < static_cast<size_t>(count)) {
        m_rows.resize(static_cast<size_t>(count));
        m_positionRows.resize(static_cast<size_t>(count));
    }
    m_count = count;
}

void JointSolver::InitVelocityConstraints(b2Joint* const* joints, int32 begin, int32 end, const b2SolverData& data) {
#ifdef LOCKBOX_UNCHECKED_ROWS
    const bool uncheckedAllowed = solver::UncheckedRowsAllowed();
#endif
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
        PositionRow& position = m_positionRows[static_cast<size_t>(i)];
        const bool rowOnly = !revolute->m_enableMotor && !revolute->m_enableLimit;
#ifdef LOCKBOX_UNCHECKED_ROWS
        if (rowOnly && uncheckedAllowed && SetUpRow(*revolute, data, row, position)) continue;
#endif
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

        LoadPositionRow(position, row, *revolute, s.localCenterA, s.localCenterB);
#ifdef LOCKBOX_UNCHECKED_ROWS
        position.unchecked = PositionRowWidths(position);
#endif
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
    // The set-up applies the accumulated impulse itself in the same way (its warm start).
    const Slopes carriedCross = Plus(Times(kImpulse, arm, kFixedShift), 1);
    widest = Max(widest, Max(carriedCross, Sum(kVelocity, Times(kImpulse, resp, kWideShift))));
    widest = Max(widest, Sum(kVelocity, Times(carriedCross, resp, kWideShift)));
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
    const bool uncheckedAllowed = solver::UncheckedRowsAllowed();
    bool okay = true;
    for (int32 i = begin; i < end; ++i) {
        const Row& row = m_rows[static_cast<size_t>(i)];
        const bool jointOkay = row.revolute != nullptr ? SolvePointPositionRow(m_positionRows[static_cast<size_t>(i)],
                                                                               data, uncheckedAllowed)
                                                       : row.joint->SolvePositionConstraints(data);
        okay = okay && jointOkay;
    }
    return okay;
}

}  // namespace lockbox
