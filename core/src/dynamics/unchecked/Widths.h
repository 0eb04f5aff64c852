#pragma once
// Bit widths for the solver rows that run without range tests. A row's set-up bounds the width of
// every value the row can form from the widths of its constants and of its inputs; while the
// inputs are within the bound, no value can leave Q32.32, Wide's tests can never fire, and the
// row may run on UncheckedWide with Wide's bits.
//
// A quantity has width w when |raw| < 2^w. If the velocities have width at most Ev and the
// accumulated impulses at most Ei, each quantity of a row has width at most max(Ev + a, Ei + b)
// for slopes a and b that depend only on the row's constants, since rows multiply inputs only
// by constants:
//   a + b, a - b      one more than the wider of a and b;
//   a * c, rounded    width(a) + width(c) - shift + 1 (the rounding adds at most one unit, and a
//   by 2^shift        product under half a unit rounds to zero, so this holds for any widths);
//   a clamp to +-m    width(m), whatever the clamped value;
//   -a                width(a).
// Every Wide test passes while a result has width at most 63: a product by a Q32.32 value is
// formed in 128 bits without overflow, rounded, and fits; one by a Q16.16 value is formed in 64
// bits, which needs width(a) + width(f) <= 62 as well; a sum is exact and not INT64_MIN.

#include <algorithm>
#include <bit>
#include <cstdint>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Wide.h"

namespace lockbox::solver {

// raw ^ (raw >> 63): |raw| for raw >= 0 and |raw| - 1 below, so |raw| <= Folded(raw) + 1. As
// cheap as a sign test, and INT64_MIN needs no negation.
[[gnu::always_inline]] constexpr uint64_t Folded(int64_t raw) noexcept {
    return static_cast<uint64_t>(raw ^ (raw >> 63));
}
inline uint64_t Folded(Wide w) noexcept { return Folded(w.Raw()); }
inline uint64_t Folded(Fixed f) noexcept { return Folded(f.Raw()); }

// The OR of the folded raws of a pair's velocities or poses (A's linear and angular, then B's).
template <class V, class N>
[[gnu::always_inline]] inline uint64_t FoldedPair(const V& vA, N wA, const V& vB, N wB) noexcept {
    return Folded(vA.x) | Folded(vA.y) | Folded(wA) | Folded(vB.x) | Folded(vB.y) | Folded(wB);
}

// A width of every value folded into `folded` (|x| <= Folded(x) + 1 <= folded + 1).
inline int WidthOf(uint64_t folded) noexcept { return static_cast<int>(std::bit_width(folded + 1)); }

// Whether every value folded into `folded` has width at most `width` (0 to 63): then
// |x| <= folded + 1 < 2^width.
[[gnu::always_inline]] constexpr bool Within(uint64_t folded, int width) noexcept {
    return ((folded + 1) >> width) == 0;
}

// The widest inputs a row may take unchecked, set by its set-up each step (0: none).
struct InputWidths {
    uint8_t velocities = 0;
    uint8_t impulses = 0;
};

// The widest result every Wide operation takes without a test firing.
inline constexpr int kWidestResult = 63;
// The bodies' centres and angles within which the position rows (a revolute joint's, a contact
// face's) form their points without range tests: |raw| < 2^29, 8192 m or rad.
inline constexpr int kPoseWidth = 29;
// The slope of a quantity that an input does not reach.
inline constexpr int kUnreached = -(1 << 20);

// A quantity's width is at most max(Ev + v, Ei + i).
struct Slopes {
    int v = kUnreached;
    int i = kUnreached;
};
inline constexpr Slopes kVelocity{0, kUnreached};
inline constexpr Slopes kImpulse{kUnreached, 0};
constexpr Slopes Max(Slopes a, Slopes b) noexcept { return {std::max(a.v, b.v), std::max(a.i, b.i)}; }
// a + b or a - b.
constexpr Slopes Sum(Slopes a, Slopes b) noexcept { return {std::max(a.v, b.v) + 1, std::max(a.i, b.i) + 1}; }
// Wider by `bits`.
constexpr Slopes Plus(Slopes a, int bits) noexcept { return {a.v + bits, a.i + bits}; }
// A product by a constant of width `width`, rounded by 2^shift.
constexpr Slopes Times(Slopes a, int width, int shift) noexcept {
    const int grow = width - shift + 1;
    return {a.v + grow, a.i + grow};
}
// A product by a Q16.16 constant of width `width` formed in 64 bits: its bound against 63.
constexpr Slopes Product64(Slopes a, int width) noexcept { return {a.v + width + 1, a.i + width + 1}; }

// The widest inputs for which every quantity within `widest` stays within kWidestResult.
constexpr InputWidths WidthsFor(Slopes widest) noexcept {
    const auto width = [](int slope) {
        return static_cast<uint8_t>(std::clamp(kWidestResult - slope, 0, kWidestResult));
    };
    return {width(widest.v), width(widest.i)};
}

}  // namespace lockbox::solver
