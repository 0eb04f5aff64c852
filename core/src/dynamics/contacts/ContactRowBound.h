#pragma once
// Which contact rows may run without range tests. A row's set-up bounds, from the bit widths of
// its constants, every value the row can form (ContactRow.h) in terms of the width of its inputs:
// the two bodies' velocities and the row's accumulated impulses. While the inputs are narrow
// enough that no value can leave Q32.32, the row's tests can never fire, and the unchecked
// arithmetic gives Wide's bits; otherwise the tested row runs, saturations and reports included.

#include <cstdint>

#include "dynamics/contacts/ContactSolver.h"

namespace lockbox::solver {

// raw ^ (raw >> 63): |raw| for raw >= 0 and |raw| - 1 below, so |raw| <= Folded(raw) + 1. As
// cheap as a sign test, and INT64_MIN needs no negation.
[[gnu::always_inline]] constexpr uint64_t Folded(int64_t raw) noexcept {
    return static_cast<uint64_t>(raw ^ (raw >> 63));
}

// The limits of vc's inputs, set once per step after vc's constants (zero when the row must keep
// its tests).
b2UncheckedLimits UncheckedLimits(const b2ContactVelocityConstraint& vc) noexcept;

// Whether vc may run unchecked on the pair's velocities and its accumulated impulses.
template <class V, class N>
[[gnu::always_inline]] inline bool UncheckedRowFits(const b2ContactVelocityConstraint& vc, const V& vA, N wA,
                                                    const V& vB, N wB) noexcept {
    const uint64_t velocities = Folded(vA.x.Raw()) | Folded(vA.y.Raw()) | Folded(wA.Raw()) | Folded(vB.x.Raw()) |
                                Folded(vB.y.Raw()) | Folded(wB.Raw());
    uint64_t impulses = 0;
    for (int32 j = 0; j < vc.pointCount; ++j)
        impulses |= Folded(vc.points[j].normalImpulse.Raw()) | Folded(vc.points[j].tangentImpulse.Raw());
    return velocities < vc.unchecked.velocitiesBelow && impulses < vc.unchecked.impulsesBelow;
}

}  // namespace lockbox::solver
