#pragma once
// Internal helpers of the contact solver: impulse vectors in Q32.32 and their application to
// Q16.16 velocities with a single rounding per component.

#include <cstdint>
#include <limits>

#include "lockbox/fixed/Math.h"

namespace lockbox::solver {

// An impulse vector, N*s (Q32.32).
struct WVec2 {
    Wide x, y;
};

// lambda * d for a unit direction d.
[[gnu::always_inline]] inline WVec2 Scale(Wide lambda, const b2Vec2& d) noexcept {
    return {lambda * d.x, lambda * d.y};
}

[[gnu::always_inline]] inline WVec2 Add(const WVec2& a, const WVec2& b) noexcept {
    return {a.x + b.x, a.y + b.y};
}

// r x P (N*m*s), r in metres.
[[gnu::always_inline]] inline Wide Cross(const b2Vec2& r, const WVec2& p) noexcept {
    return r.x * p.y - r.y * p.x;
}

// invMass * p for body A and body B (m/s, each rounded once from the Q32.32 product). Both
// bodies of a contact often have the same inverse mass; then B's product is A's value and is
// not computed again. A value at the Fixed limit may be a saturation, which the second
// evaluation would report again: it is recomputed then, so overflow reports stay identical.
[[gnu::always_inline]] inline void LinearChanges(Wide mA, Wide mB, Wide p, Fixed& dA,
                                                 Fixed& dB) noexcept {
    dA = MulToFixed(mA, p);
    const bool reuse = mA == mB && dA.Raw() != Fixed::kMaxRaw && dA.Raw() != -Fixed::kMaxRaw;
    dB = reuse ? dA : MulToFixed(mB, p);
}

// vA -= mA P, wA -= iA (rA x P), vB += mB P, wB += iB (rB x P), each velocity component rounded
// once from the Q32.32 products; the linear products are shared through LinearChanges.
[[gnu::always_inline]] inline void ApplyPair(b2Vec2& vA, Fixed& wA, b2Vec2& vB, Fixed& wB, Wide mA,
                                             Wide iA, Wide mB, Wide iB, const b2Vec2& rA,
                                             const b2Vec2& rB, const WVec2& p) noexcept {
    Fixed dxA, dxB, dyA, dyB;
    LinearChanges(mA, mB, p.x, dxA, dxB);
    LinearChanges(mA, mB, p.y, dyA, dyB);
    vA.x -= dxA;
    vA.y -= dyA;
    wA -= MulToFixed(iA, Cross(rA, p));
    vB.x += dxB;
    vB.y += dyB;
    wB += MulToFixed(iB, Cross(rB, p));
}

// Relative velocity of the contact point on B with respect to A, m/s.
[[gnu::always_inline]] inline b2Vec2 RelativeVelocity(const b2Vec2& vA, Fixed wA, const b2Vec2& rA,
                                                      const b2Vec2& vB, Fixed wB,
                                                      const b2Vec2& rB) noexcept {
    return vB + b2Cross(wB, rB) - vA - b2Cross(wA, rA);
}

// Effective mass denominator mA + mB + iA rnA^2 + iB rnB^2 (1/kg), with the squares exact.
inline Wide EffectiveInverseMass(Wide mA, Wide mB, Wide iA, Wide iB, Fixed rnA,
                                 Fixed rnB) noexcept {
    return mA + mB + iA * MulWide(rnA, rnA) + iB * MulWide(rnB, rnB);
}

// The body origin c - q * localCenter (m). For a shape centred on its body (localCenter zero)
// the rotated offset is exactly zero, with no rounding or saturation, and subtracting zero
// leaves c unchanged; only an INT32_MIN raw would saturate in that subtraction, so it takes
// the full computation.
[[gnu::always_inline]] inline b2Vec2 BodyOrigin(const b2Vec2& c, const b2Rot& q,
                                                const b2Vec2& localCenter) noexcept {
    constexpr int32_t kMinRaw = std::numeric_limits<int32_t>::min();
    if (localCenter == b2Vec2_zero && c.x.Raw() != kMinRaw && c.y.Raw() != kMinRaw) return c;
    return c - b2Mul(q, localCenter);
}

}  // namespace lockbox::solver
