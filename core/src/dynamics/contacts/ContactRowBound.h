#pragma once
// Which contact rows may run without range tests (dynamics/unchecked/Widths.h): the widest
// velocities and accumulated impulses for which no value of the row (ContactRow.h) can leave
// Q32.32, from the widths of the row's constants.

#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/unchecked/Widths.h"

namespace lockbox::solver {

// The widths of a row's constants by kind: its directions (normal and tangent), lever arms,
// effective masses (and the block's inverse), responses (pushes, turns, K) and friction.
struct RowWidths {
    int dir = 0, arm = 0, mass = 0, resp = 0, friction = 0;
};

// The widest slopes of the values of a row with `points` (1 or 2) points and constants of
// widths w (every width at least 0, resp at most kWidestResult): the row's operations in order.
Slopes RowSlopesBySteps(const RowWidths& w, int points) noexcept;
// RowSlopesBySteps in closed form, equal to it for every such w.
Slopes RowSlopes(const RowWidths& w, int points) noexcept;

// The widths of vc's inputs under which it runs unchecked, set once per step after vc's constants.
InputWidths UncheckedWidths(const b2ContactVelocityConstraint& vc) noexcept;

// Whether vc may run unchecked on the pair's velocities and its accumulated impulses.
template <class V, class N>
[[gnu::always_inline]] inline bool UncheckedRowFits(const b2ContactVelocityConstraint& vc, const V& vA, N wA,
                                                    const V& vB, N wB) noexcept {
    const uint64_t velocities = FoldedPair(vA, wA, vB, wB);
    uint64_t impulses = 0;
    for (int32 j = 0; j < vc.pointCount; ++j)
        impulses |= Folded(vc.points[j].normalImpulse) | Folded(vc.points[j].tangentImpulse);
    return Within(velocities, vc.unchecked.velocities) && Within(impulses, vc.unchecked.impulses);
}

}  // namespace lockbox::solver
