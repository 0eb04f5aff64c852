#pragma once
// Internal helpers of the contact solver: impulse vectors in Q32.32 and their application to
// Q16.16 velocities with a single rounding per component.

#include "lockbox/fixed/Math.h"

namespace lockbox::solver {

// An impulse vector, N*s (Q32.32).
struct WVec2 {
    Wide x, y;
};

// lambda * d for a unit direction d.
inline WVec2 Scale(Wide lambda, const b2Vec2& d) noexcept { return {lambda * d.x, lambda * d.y}; }

inline WVec2 Add(const WVec2& a, const WVec2& b) noexcept { return {a.x + b.x, a.y + b.y}; }

// r x P (N*m*s), r in metres.
inline Wide Cross(const b2Vec2& r, const WVec2& p) noexcept { return r.x * p.y - r.y * p.x; }

// v -= invMass * P and w -= invI * (r x P); each velocity component is rounded once from the
// Q32.32 products.
inline void ApplyNeg(b2Vec2& v, Fixed& w, Wide invMass, Wide invI, const b2Vec2& r, const WVec2& p) noexcept {
    v.x -= MulToFixed(invMass, p.x);
    v.y -= MulToFixed(invMass, p.y);
    w -= MulToFixed(invI, Cross(r, p));
}

// v += invMass * P and w += invI * (r x P).
inline void ApplyPos(b2Vec2& v, Fixed& w, Wide invMass, Wide invI, const b2Vec2& r, const WVec2& p) noexcept {
    v.x += MulToFixed(invMass, p.x);
    v.y += MulToFixed(invMass, p.y);
    w += MulToFixed(invI, Cross(r, p));
}

// Relative velocity of the contact point on B with respect to A, m/s.
inline b2Vec2 RelativeVelocity(const b2Vec2& vA, Fixed wA, const b2Vec2& rA, const b2Vec2& vB, Fixed wB,
                               const b2Vec2& rB) noexcept {
    return vB + b2Cross(wB, rB) - vA - b2Cross(wA, rA);
}

// Effective mass denominator mA + mB + iA rnA^2 + iB rnB^2 (1/kg), with the squares exact.
inline Wide EffectiveInverseMass(Wide mA, Wide mB, Wide iA, Wide iB, Fixed rnA, Fixed rnB) noexcept {
    return mA + mB + iA * MulWide(rnA, rnA) + iB * MulWide(rnB, rnB);
}

}  // namespace lockbox::solver
