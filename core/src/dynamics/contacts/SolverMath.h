#pragma once
// Internal helpers of the contact solver: impulse vectors in Q32.32 and their application to
// Q16.16 velocities with a single rounding per component.

#include <cstdint>
#include <limits>

#include "lockbox/fixed/Math.h"
#include "lockbox/fixed/WideVec.h"

namespace lockbox::solver {

// The impulse lambda d on the pair's linear velocities: vA -= lambda pushA, vB += lambda pushB,
// with pushA = mA d and pushB = mB d; each component rounded once. With equal pushes B's change
// is A's (computed, and reported on saturation, once).
[[gnu::always_inline]] inline void PushPair(b2Vec2& vA, b2Vec2& vB, Wide lambda, const b2WideVec2& pushA,
                                            const b2WideVec2& pushB, bool samePush) noexcept {
    const Fixed dxA = MulToFixed(lambda, pushA.x);
    const Fixed dyA = MulToFixed(lambda, pushA.y);
    vA.x -= dxA;
    vA.y -= dyA;
    if (samePush) {
        vB.x += dxA;
        vB.y += dyA;
    } else {
        vB.x += MulToFixed(lambda, pushB.x);
        vB.y += MulToFixed(lambda, pushB.y);
    }
}

// The speed of B's contact point relative to A's along the unit direction d, in Q32.32 with
// no rounding: d . (vB - vA) + wB (rB x d) - wA (rA x d), where armA = rA x d and
// armB = rB x d. The velocity differences are exact in 33 bits and |d| < 2^31 raw, so each
// linear product stays below 2^63; the sums are checked (saturate and report, never wrap).
[[gnu::always_inline]] inline Wide SpeedAlong(const b2Vec2& vA, Fixed wA, Fixed armA, const b2Vec2& vB, Fixed wB,
                                              Fixed armB, const b2Vec2& d) noexcept {
    const int64_t dvx = int64_t{vB.x.Raw()} - vA.x.Raw();
    const int64_t dvy = int64_t{vB.y.Raw()} - vA.y.Raw();
    const Wide linear = Wide::FromRaw(dvx * d.x.Raw()) + Wide::FromRaw(dvy * d.y.Raw());
    return linear + MulWide(wB, armB) - MulWide(wA, armA);
}

// The impulse lambda d on the pair: PushPair, then wA -= lambda turnA and wB += lambda turnB,
// where turnA = iA (rA x d) and turnB = iB (rB x d).
[[gnu::always_inline]] inline void ApplyAlong(b2Vec2& vA, Fixed& wA, b2Vec2& vB, Fixed& wB, Wide lambda,
                                              const b2WideVec2& pushA, const b2WideVec2& pushB, bool samePush,
                                              Wide turnA, Wide turnB) noexcept {
    PushPair(vA, vB, lambda, pushA, pushB, samePush);
    wA -= MulToFixed(lambda, turnA);
    wB += MulToFixed(lambda, turnB);
}

// Effective mass denominator mA + mB + iA rnA^2 + iB rnB^2 (1/kg), with the squares exact.
inline Wide EffectiveInverseMass(Wide mA, Wide mB, Wide iA, Wide iB, Fixed rnA, Fixed rnB) noexcept {
    return mA + mB + iA * MulWide(rnA, rnA) + iB * MulWide(rnB, rnB);
}

// The body origin c - q * localCenter (m). For a shape centred on its body (localCenter zero)
// the rotated offset is exactly zero, with no rounding or saturation, and subtracting zero
// leaves c unchanged; only an INT32_MIN raw would saturate in that subtraction, so it takes
// the full computation.
[[gnu::always_inline]] inline b2Vec2 BodyOrigin(const b2Vec2& c, const b2Rot& q, const b2Vec2& localCenter) noexcept {
    constexpr int32_t kMinRaw = std::numeric_limits<int32_t>::min();
    if (localCenter == b2Vec2_zero && c.x.Raw() != kMinRaw && c.y.Raw() != kMinRaw) return c;
    return c - b2Mul(q, localCenter);
}

}  // namespace lockbox::solver
