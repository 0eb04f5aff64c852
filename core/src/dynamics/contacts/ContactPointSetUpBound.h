#pragma once
// Which contacts' velocity set-up (ContactPointSetUp.h) may run without range tests
// (dynamics/unchecked/Widths.h): the widest velocities for which no value of the set-up can leave
// its format, from the widths of the arms, the directions, the masses and the restitution. It is
// formed per contact, before the set-up, so it must cost far less than the tests it spares.

#include <algorithm>

#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/unchecked/Widths.h"

namespace lockbox::solver {

// The widest velocities (0: none) for which vc's set-up at the world points and the bodies'
// centres cA, cB stays in range, given vc's normal, masses, restitution and point count.
[[gnu::always_inline]] inline int SetUpVelocityWidth(const b2ContactVelocityConstraint& vc, const b2Vec2* points,
                                                     const b2Vec2& cA, const b2Vec2& cB) noexcept {
    // A unit normal has |raw| <= 2^16, and so has its tangent (the same raws, turned). The pushes
    // m d are products by it formed in 64 bits.
    constexpr int kDirection = Fixed::kFractionBits + 1;
    constexpr int kMassWidest = kWidestResult - kDirection - 1;
    constexpr int kFixedWidest = 31;
    // The widest Wide that rounds to Fixed without saturating.
    constexpr int kWidestToFixed = kFixedWidest + Fixed::kFractionBits - 1;
    if (!Within(Folded(vc.normal.x) | Folded(vc.normal.y), kDirection) ||
        !Within(Folded(vc.invMassA) | Folded(vc.invMassB), kMassWidest))
        return 0;
    // The arms p - c, exact in 64 bits (Fixed's subtraction does not saturate while they fit).
    // Bounding the loop by the manifold's size lets it unroll.
    uint64_t arms = 0;
    for (int32 j = 0; j < b2_maxManifoldPoints && j < vc.pointCount; ++j) {
        const b2Vec2& p = points[j];
        arms |= Folded(int64_t{p.x.Raw()} - cA.x.Raw()) | Folded(int64_t{p.y.Raw()} - cA.y.Raw()) |
                Folded(int64_t{p.x.Raw()} - cB.x.Raw()) | Folded(int64_t{p.y.Raw()} - cB.y.Raw());
    }
    // r x d: two exact products, their difference, rounded by 2^16 to Fixed.
    const int lever = WidthOf(arms) + kDirection + 1 - Fixed::kFractionBits + 1;
    const int turn = WidthOf(Folded(vc.invIA) | Folded(vc.invIB));
    // A denominator: mA + mB (within the masses' widest), then two terms i (r x d)^2, an exact
    // square by a Wide rounded by 2^32, each added. The turns i (r x d) are formed in 64 bits.
    if (lever > kFixedWidest || turn + 2 * lever - 31 + 2 > kWidestResult || turn + lever + 1 > kWidestResult) return 0;

    // The speed along the normal (SpeedAlong) on velocities of width v: vB - vA (v + 1), by the
    // direction in 64 bits (v + 1 + kDirection + 1 <= 63), rounded (v + kDirection - 14) and
    // summed (v + kDirection - 13); w (r x d) in 64 bits (v + lever + 1 <= 63), rounded (v +
    // lever - 15); two sums. So the speed has width v + speed.
    const int speed = std::max(kDirection - 11, lever - 13);
    // The bias: the speed by the restitution in 64 bits (v + speed + restitution + 1 <= 63),
    // rounded by 2^16 (v + speed + restitution - 15), then to Fixed.
    const int restitution = WidthOf(Folded(vc.restitution));
    const int widest = std::min(
        {kWidestResult - 2 - kDirection, kWidestResult - 1 - lever, kWidestToFixed + 15 - speed - restitution});
    return std::max(widest, 0);
}

}  // namespace lockbox::solver
