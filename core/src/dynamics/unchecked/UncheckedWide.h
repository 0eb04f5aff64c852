#pragma once
// Q32.32 and Q16.16 arithmetic with Wide's and Fixed's rounding and no range tests, for a solver
// row (a contact's, a revolute joint's point row and its position row) or a contact's velocity
// set-up whose every result is proven to stay in range before it runs (Widths.h). Where Wide's
// or Fixed's result is in range it is exactly these types', so a proven row gives their bits; out
// of range these operations wrap where Wide and Fixed saturate, which is why nothing may use them
// without the proof.
//
// Products by a Q32.32 value are formed in 128 bits, so they never overflow before their
// rounding; only the rounded result must fit. That needs a native 128-bit integer: elsewhere the
// row always runs on Wide.

#include <cstdint>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Rot.h"
#include "lockbox/fixed/Vec2.h"
#include "lockbox/fixed/Wide.h"
#include "lockbox/fixed/WideVec.h"
#include "lockbox/fixed/detail/Int128.h"

namespace lockbox::solver {

// Whether rows proven to stay in range may run unchecked (the default). Both paths give the same
// bits; tests switch it to compare them.
bool UncheckedRowsAllowed() noexcept;
void AllowUncheckedRows(bool allow) noexcept;

// The Wide of a row's number, for a result stored in a Wide field (the UncheckedWide overload
// is below).
inline Wide AsWide(Wide w) noexcept { return w; }

// The tested twins of the unchecked Rotate, Cross and Dot below, for rows written over either
// number type.
// q v for v = (x, y), as b2Mul(b2Rot, b2Vec2).
inline b2Vec2 Rotate(const b2Rot& q, Fixed x, Fixed y) noexcept { return b2Mul(q, b2Vec2(x, y)); }
// r x d of the arm r = (x, y), as b2Cross(b2Vec2, b2Vec2).
inline Fixed Cross(Fixed x, Fixed y, const b2Vec2& d) noexcept { return b2Cross(b2Vec2(x, y), d); }
// r . d of r = (x, y), as b2Dot.
inline Fixed Dot(Fixed x, Fixed y, const b2Vec2& d) noexcept { return b2Dot(b2Vec2(x, y), d); }

}  // namespace lockbox::solver

#ifdef LOCKBOX_NATIVE_INT128
#define LOCKBOX_UNCHECKED_ROWS 1

namespace lockbox::solver {

// floor((p + 2^(shift-1) - [p < 0]) / 2^shift) of an exact product p (|p| < 2^126, 0 < shift <
// 64): round half away from zero. With p = q 2^shift + f (0 <= f < 2^shift) that is q plus the
// carry of f + 2^(shift-1) - [p < 0] into bit `shift`, which keeps every step in 64-bit
// registers; of q only the low 64 bits are kept, which are the result when it fits.
[[gnu::always_inline]] constexpr int64_t RoundShift(detail::NativeI128 product, int shift) noexcept {
    const auto p = static_cast<detail::NativeU128>(product);
    const auto negative = static_cast<uint64_t>(static_cast<int64_t>(static_cast<uint64_t>(p >> 64)) >> 63);
    const auto q = static_cast<uint64_t>(p >> shift);
    const uint64_t f = static_cast<uint64_t>(p) & ((uint64_t{1} << shift) - 1);
    const uint64_t carry = (f + (uint64_t{1} << (shift - 1)) + negative) >> shift;
    return static_cast<int64_t>(q + carry);
}

// An exact Q32.32 raw p (|p| < 2^62), held in an unsigned integer so that it wraps instead of
// being undefined, rounded to Q16.16 with ties away from zero, as Wide::ToFixed where its result
// fits; of the rounded value only the low 32 bits are kept.
[[gnu::always_inline]] constexpr Fixed RoundToFixed(uint64_t p) noexcept {
    const uint64_t biased = p + (uint64_t{1} << 15) + static_cast<uint64_t>(static_cast<int64_t>(p) >> 63);
    return Fixed::FromRaw(static_cast<int32_t>(static_cast<int64_t>(biased) >> Fixed::kFractionBits));
}

class UncheckedWide {
public:
    constexpr UncheckedWide() noexcept = default;
    constexpr UncheckedWide(Wide w) noexcept : m_raw(w.Raw()) {}  // NOLINT: the same number
    // Exact widening, as Wide(Fixed).
    constexpr explicit UncheckedWide(Fixed f) noexcept : m_raw(int64_t{f.Raw()} * (int64_t{1} << 16)) {}

    constexpr Wide ToWide() const noexcept { return Wide::FromRaw(m_raw); }
    constexpr explicit operator Wide() const noexcept { return ToWide(); }
    constexpr int64_t Raw() const noexcept { return m_raw; }
    // Rounded to Q16.16, as Wide::ToFixed.
    [[gnu::always_inline]] constexpr Fixed ToFixed() const noexcept {
        return RoundToFixed(static_cast<uint64_t>(m_raw));
    }

    constexpr auto operator<=>(const UncheckedWide&) const noexcept = default;
    constexpr bool operator==(const UncheckedWide&) const noexcept = default;

    // Sums and differences through unsigned integers: they wrap instead of being undefined.
    [[gnu::always_inline]] friend constexpr UncheckedWide operator+(UncheckedWide a, UncheckedWide b) noexcept {
        return FromRaw(static_cast<int64_t>(static_cast<uint64_t>(a.m_raw) + static_cast<uint64_t>(b.m_raw)));
    }
    [[gnu::always_inline]] friend constexpr UncheckedWide operator-(UncheckedWide a, UncheckedWide b) noexcept {
        return FromRaw(static_cast<int64_t>(static_cast<uint64_t>(a.m_raw) - static_cast<uint64_t>(b.m_raw)));
    }
    [[gnu::always_inline]] constexpr UncheckedWide operator-() const noexcept {
        return FromRaw(static_cast<int64_t>(uint64_t{0} - static_cast<uint64_t>(m_raw)));
    }
    constexpr UncheckedWide& operator+=(UncheckedWide b) noexcept { return *this = *this + b; }
    constexpr UncheckedWide& operator-=(UncheckedWide b) noexcept { return *this = *this - b; }

    // Wide * Wide, rounded to 2^-32 with ties away from zero, as Wide's.
    [[gnu::always_inline]] friend constexpr UncheckedWide operator*(UncheckedWide a, UncheckedWide b) noexcept {
        return FromRaw(solver::RoundShift(static_cast<detail::NativeI128>(a.m_raw) * b.m_raw, Wide::kFractionBits));
    }
    // r x P of a Q16.16 arm and a Q32.32 impulse, exact in 128 bits and rounded once, as
    // b2Cross(b2Vec2, b2WideVec2).
    [[gnu::always_inline]] static constexpr UncheckedWide Cross(const b2Vec2& r, UncheckedWide px,
                                                                UncheckedWide py) noexcept {
        using I128 = detail::NativeI128;
        const I128 e = static_cast<I128>(r.x.Raw()) * py.m_raw - static_cast<I128>(r.y.Raw()) * px.m_raw;
        return FromRaw(solver::RoundShift(e, Fixed::kFractionBits));
    }
    // By a Fixed the product is formed in 64 bits (which the row's bound also covers), through
    // unsigned integers so that an unproven use wraps instead of being undefined.
    [[gnu::always_inline]] friend constexpr UncheckedWide operator*(UncheckedWide a, Fixed b) noexcept {
        const uint64_t p = static_cast<uint64_t>(a.m_raw) * static_cast<uint64_t>(int64_t{b.Raw()});
        const uint64_t biased = p + (uint64_t{1} << 15) + static_cast<uint64_t>(static_cast<int64_t>(p) >> 63);
        return FromRaw(static_cast<int64_t>(biased) >> Fixed::kFractionBits);
    }

private:
    static constexpr UncheckedWide FromRaw(int64_t raw) noexcept {
        UncheckedWide w;
        w.m_raw = raw;
        return w;
    }
    int64_t m_raw = 0;
};

inline Wide AsWide(UncheckedWide w) noexcept { return w.ToWide(); }

// A pair of components, as b2WideVec2 is for Wide.
struct UncheckedVec2 {
    UncheckedWide x, y;

    static constexpr UncheckedVec2 From(const b2WideVec2& v) noexcept { return {v.x, v.y}; }
    constexpr b2WideVec2 ToWide() const noexcept { return {x.ToWide(), y.ToWide()}; }
};

// Q16.16 with Fixed's rounding and no range tests: positions in a proven position row. Sums and
// differences go through unsigned integers, so they wrap instead of being undefined.
class UncheckedFixed {
public:
    constexpr UncheckedFixed() noexcept = default;
    constexpr UncheckedFixed(Fixed f) noexcept : m_raw(f.Raw()) {}  // NOLINT: the same number

    static constexpr UncheckedFixed FromRaw(int32_t raw) noexcept {
        UncheckedFixed f;
        f.m_raw = raw;
        return f;
    }
    constexpr Fixed ToFixed() const noexcept { return Fixed::FromRaw(m_raw); }
    constexpr explicit operator Fixed() const noexcept { return ToFixed(); }
    constexpr int32_t Raw() const noexcept { return m_raw; }

    [[gnu::always_inline]] friend constexpr UncheckedFixed operator+(UncheckedFixed a, UncheckedFixed b) noexcept {
        return FromRaw(static_cast<int32_t>(static_cast<uint32_t>(a.m_raw) + static_cast<uint32_t>(b.m_raw)));
    }
    [[gnu::always_inline]] friend constexpr UncheckedFixed operator-(UncheckedFixed a, UncheckedFixed b) noexcept {
        return FromRaw(static_cast<int32_t>(static_cast<uint32_t>(a.m_raw) - static_cast<uint32_t>(b.m_raw)));
    }
    [[gnu::always_inline]] constexpr UncheckedFixed operator-() const noexcept {
        return FromRaw(static_cast<int32_t>(uint32_t{0} - static_cast<uint32_t>(m_raw)));
    }
    constexpr UncheckedFixed& operator+=(UncheckedFixed b) noexcept { return *this = *this + b; }
    constexpr UncheckedFixed& operator-=(UncheckedFixed b) noexcept { return *this = *this - b; }
    // Rounded to 2^-16 with ties away from zero, as Fixed's: the product of two raws is exact in
    // 64 bits and leaves room for the bias, so only the result can leave the range.
    [[gnu::always_inline]] friend constexpr UncheckedFixed operator*(UncheckedFixed a, UncheckedFixed b) noexcept {
        const int64_t p = int64_t{a.m_raw} * b.m_raw;
        return FromRaw(static_cast<int32_t>((p + (int64_t{1} << 15) + (p >> 63)) >> Fixed::kFractionBits));
    }

private:
    int32_t m_raw = 0;
};

// Wide * Wide rounded once to Q16.16, as MulToFixed(Wide, Wide).
[[gnu::always_inline]] constexpr UncheckedFixed MulToFixed(UncheckedWide a, UncheckedWide b) noexcept {
    const int64_t r = RoundShift(static_cast<detail::NativeI128>(a.Raw()) * b.Raw(), Wide::kFractionBits + 16);
    return UncheckedFixed::FromRaw(static_cast<int32_t>(r));
}

// Wide * Fixed rounded once to Q16.16, as MulToFixed(Wide, Fixed): the product is exact in 128
// bits.
[[gnu::always_inline]] constexpr UncheckedFixed MulToFixed(UncheckedWide a, Fixed b) noexcept {
    const int64_t r = RoundShift(static_cast<detail::NativeI128>(a.Raw()) * b.Raw(), Wide::kFractionBits);
    return UncheckedFixed::FromRaw(static_cast<int32_t>(r));
}

// q v for v = (x, y), as b2Mul(b2Rot, b2Vec2): each component an exact sum of two products
// (below 2^48 for a rotation's |c|, |s| <= 1), rounded once.
[[gnu::always_inline]] constexpr b2Vec2 Rotate(const b2Rot& q, UncheckedFixed x, UncheckedFixed y) noexcept {
    // Through unsigned integers, so that an unproven use wraps instead of being undefined.
    const auto product = [](Fixed a, UncheckedFixed b) {
        return static_cast<uint64_t>(int64_t{a.Raw()} * b.Raw());  // below 2^62 for any raws
    };
    return {RoundToFixed(product(q.c, x) - product(q.s, y)), RoundToFixed(product(q.s, x) + product(q.c, y))};
}

// r x d of the arm r = (x, y): the exact difference of two products, rounded once, as
// b2Cross(b2Vec2, b2Vec2).
[[gnu::always_inline]] constexpr Fixed Cross(UncheckedFixed x, UncheckedFixed y, const b2Vec2& d) noexcept {
    // Each product is exact in 64 bits for any raws; their difference wraps when unproven.
    const auto product = [](UncheckedFixed a, Fixed b) { return static_cast<uint64_t>(int64_t{a.Raw()} * b.Raw()); };
    return RoundToFixed(product(x, d.y) - product(y, d.x));
}

// r . d of r = (x, y): the exact sum of two products, rounded once, as b2Dot.
[[gnu::always_inline]] constexpr Fixed Dot(UncheckedFixed x, UncheckedFixed y, const b2Vec2& d) noexcept {
    const auto product = [](UncheckedFixed a, Fixed b) { return static_cast<uint64_t>(int64_t{a.Raw()} * b.Raw()); };
    return RoundToFixed(product(x, d.x) + product(y, d.y));
}

}  // namespace lockbox::solver

#endif
