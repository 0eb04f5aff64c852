#pragma once
// Internal helpers of the contact solver: impulse vectors in Q32.32 and their application to
// the Q32.32 solver velocities.

#include <cstdint>
#include <limits>

#include "lockbox/fixed/Math.h"
#include "lockbox/fixed/WideVec.h"

namespace lockbox::solver {

// Writes a body's solved state back, unless the body has no mass (static or kinematic): the
// contact solver never changes such a body (every push and turn on it is zero), so it is only
// read. This is what lets the contacts of one colour be solved at the same time while they
// share a static ground (dynamics/Colours.h): no two of them write the same place.
template <class State, class Linear, class Angular>
[[gnu::always_inline]] inline void Store(State& state, const Linear& linear, const Angular& angular, Wide invMass,
                                         Wide invI) noexcept {
    if (invMass == Wide() && invI == Wide()) return;
    state = State{linear, angular};
}

// The impulse lambda d on the pair's linear velocities: vA -= lambda pushA, vB += lambda pushB,
// with pushA = mA d and pushB = mB d, added in Q32.32. With equal pushes B's change is A's
// (computed, and reported on saturation, once). V is a pair of N: b2WideVec2 and Wide, or the
// proven row's unchecked types (UncheckedWide.h), which give the same bits.
template <class V, class N>
[[gnu::always_inline]] inline void PushPair(V& vA, V& vB, N lambda, const V& pushA, const V& pushB,
                                            bool samePush) noexcept {
    const N dxA = lambda * pushA.x;
    const N dyA = lambda * pushA.y;
    vA.x -= dxA;
    vA.y -= dyA;
    if (samePush) {
        vB.x += dxA;
        vB.y += dyA;
    } else {
        vB.x += lambda * pushB.x;
        vB.y += lambda * pushB.y;
    }
}

// The speed of B's contact point relative to A's along the unit direction d, in Q32.32:
// d . (vB - vA) + wB (rB x d) - wA (rA x d), where armA = rA x d and armB = rB x d. Each
// product is rounded once at 2^-32; on Wide the sums are checked (saturate and report, never wrap).
template <class V, class N>
[[gnu::always_inline]] inline N SpeedAlong(const V& vA, N wA, Fixed armA, const V& vB, N wB, Fixed armB,
                                           const b2Vec2& d) noexcept {
    const N dx = vB.x - vA.x;
    const N dy = vB.y - vA.y;
    const N linear = dx * d.x + dy * d.y;
    return linear + wB * armB - wA * armA;
}

// The impulse lambda d on the pair: PushPair, then wA -= lambda turnA and wB += lambda turnB,
// where turnA = iA (rA x d) and turnB = iB (rB x d).
template <class V, class N>
[[gnu::always_inline]] inline void ApplyAlong(V& vA, N& wA, V& vB, N& wB, N lambda, const V& pushA, const V& pushB,
                                              bool samePush, N turnA, N turnB) noexcept {
    PushPair(vA, vB, lambda, pushA, pushB, samePush);
    wA -= lambda * turnA;
    wB += lambda * turnB;
}

// Effective mass denominator mA + mB + iA rnA^2 + iB rnB^2 (1/kg), with the squares exact, on
// Wide or a proven set-up's UncheckedWide.
template <class N>
inline N EffectiveInverseMass(N mA, N mB, N iA, N iB, Fixed rnA, Fixed rnB) noexcept {
    return mA + mB + iA * N(MulWide(rnA, rnA)) + iB * N(MulWide(rnB, rnB));
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
