#pragma once
// The arithmetic a revolute point row shares between its set-up (JointRowSetUp.cpp) and its
// iterations (JointSolver.cpp): the anchors' arms and the application of a point impulse, each
// written once over the number types (Fixed and Wide, or their unchecked twins where a row's
// bound proves the result in range, which gives the same bits).

#include <type_traits>

#include "dynamics/joints/JointSolver.h"
#include "dynamics/unchecked/UncheckedWide.h"

namespace lockbox::pointrow {

// r x P for the point row, on either number type.
inline Wide ArmCross(const b2Vec2& r, Wide px, Wide py) noexcept { return b2Cross(r, b2WideVec2(px, py)); }
#ifdef LOCKBOX_UNCHECKED_ROWS
inline solver::UncheckedWide ArmCross(const b2Vec2& r, solver::UncheckedWide px, solver::UncheckedWide py) noexcept {
    return solver::UncheckedWide::Cross(r, px, py);
}
#endif

// Whether a row on number type N may give B the very linear change of A, formed once: on a
// proven row (N unchecked) whose bodies have equal inverse masses. The tested row forms both
// products, so that a saturation is reported as often as in 2.2.1's order. R is a velocity or a
// position row.
template <class N, class R>
[[gnu::always_inline]] inline bool SharesLinearChange(const R& row) noexcept {
    return !std::is_same_v<N, Wide> && row.mB == row.mA;
}

// The point impulse (px, py) on a row's bodies: A takes -mA P and -iA (rA x P), B takes mB P and
// iB (rB x P). An iteration applies its increment so; the set-up, the carried impulse.
template <class N, class V>
[[gnu::always_inline]] inline void ApplyPointImpulse(const core_detail::Engine::Joints::Solver::Row& row, V& vA, N& wA,
                                                     V& vB, N& wB, N px, N py) noexcept {
    const N dxA = N(row.mA) * px, dyA = N(row.mA) * py;
    vA.x -= dxA;
    vA.y -= dyA;
    wA -= N(row.iA) * ArmCross(row.rA, px, py);
    if (SharesLinearChange<N>(row)) {
        vB.x += dxA;
        vB.y += dyA;
    } else {
        vB.x += N(row.mB) * px;
        vB.y += N(row.mB) * py;
    }
    wB += N(row.iB) * ArmCross(row.rB, px, py);
}

// Whether a point row's velocities and accumulated impulse are within its widths: then its
// iteration and its warm start may run unchecked.
inline bool PointRowFits(const core_detail::Engine::Joints::Solver::Row& row, const b2Velocity& velA,
                         const b2Velocity& velB) noexcept {
    const uint64_t velocities = solver::FoldedPair(velA.v, velA.w, velB.v, velB.w);
    const uint64_t impulse = solver::Folded(row.impulse.x) | solver::Folded(row.impulse.y);
    return solver::Within(velocities, row.unchecked.velocities) && solver::Within(impulse, row.unchecked.impulses);
}

// The anchors' arms q (localAnchor - localCenter), as the joint forms them, on Fixed or, where
// PositionRowWidths proves them in range, on solver::UncheckedFixed.
template <class F>
[[gnu::always_inline]] inline void PointArms(const core_detail::Engine::Joints::Solver::PositionRow& row,
                                             const b2Rot& qA, const b2Rot& qB, b2Vec2& rA, b2Vec2& rB) noexcept {
    rA = solver::Rotate(qA, F(row.localAnchorA.x) - F(row.localCenterA.x),
                        F(row.localAnchorA.y) - F(row.localCenterA.y));
    rB = solver::Rotate(qB, F(row.localAnchorB.x) - F(row.localCenterB.x),
                        F(row.localAnchorB.y) - F(row.localCenterB.y));
}

}  // namespace lockbox::pointrow
