#pragma once
/// @file
/// b2Vec2 and its free functions (the manual's Math module) on Q16.16.
///
/// Dot, cross and squared lengths accumulate exactly in 64 bits (a Q32.32 value) and are
/// rounded once, only when a Q16.16 result is asked for; the *Wide variants return the exact
/// sum. Length is the correctly rounded square root of that exact sum, so it neither overflows
/// nor loses precision from 1 ULP to the edge of the range.

#include <bit>
#include <cstdint>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Functions.h"
#include "lockbox/fixed/Wide.h"
#include "lockbox/fixed/detail/Sqrt.h"

namespace lockbox {

namespace detail {
/// a1*b1 + a2*b2 of raw Q16.16 values, exact as a Q32.32 raw (saturates only when all four
/// raws are at the very edge of the int32 range).
constexpr int64_t SumOfProducts(int32_t a1, int32_t b1, int32_t a2, int32_t b2) noexcept {
    int64_t r = 0;
    if (__builtin_add_overflow(int64_t{a1} * b1, int64_t{a2} * b2, &r)) [[unlikely]] {
        OnOverflow("SumOfProducts", a1, b1);
        return r < 0 ? INT64_MAX : -INT64_MAX;  // wrapped sign is the opposite of the true one
    }
    return r;
}
/// a1*b1 - a2*b2 of raw Q16.16 values, exact as a Q32.32 raw (saturating like SumOfProducts).
constexpr int64_t DiffOfProducts(int32_t a1, int32_t b1, int32_t a2, int32_t b2) noexcept {
    int64_t r = 0;
    if (__builtin_sub_overflow(int64_t{a1} * b1, int64_t{a2} * b2, &r)) [[unlikely]] {
        OnOverflow("DiffOfProducts", a1, b1);
        return r < 0 ? INT64_MAX : -INT64_MAX;
    }
    return r;
}
}  // namespace detail

/// A 2D column vector (metres, metres per second, newtons...).
struct b2Vec2 {
    /// The components, in the vector's unit (metres for positions).
    ///@{
    Fixed x;
    Fixed y;
    ///@}

    /// The zero vector (unlike Box2D, never uninitialised).
    constexpr b2Vec2() noexcept = default;
    /// The vector (xIn, yIn).
    constexpr b2Vec2(Fixed xIn, Fixed yIn) noexcept : x(xIn), y(yIn) {}

    /// Sets both components to zero.
    constexpr void SetZero() noexcept {
        x = Fixed();
        y = Fixed();
    }
    /// Sets the components to (x_, y_).
    constexpr void Set(Fixed x_, Fixed y_) noexcept {
        x = x_;
        y = y_;
    }

    /// The negated vector (-x, -y); each component saturates like Fixed's negation.
    constexpr b2Vec2 operator-() const noexcept { return {-x, -y}; }
    /// Component access: 0 is x, 1 is y.
    constexpr Fixed operator()(int i) const noexcept { return i == 0 ? x : y; }
    /// Mutable component access: 0 is x, any other index is y.
    constexpr Fixed& operator()(int i) noexcept { return i == 0 ? x : y; }

    /// In-place sum, difference and scaling by a scalar, component by component with Fixed's
    /// rounding and saturation.
    ///@{
    constexpr b2Vec2& operator+=(const b2Vec2& v) noexcept {
        x += v.x;
        y += v.y;
        return *this;
    }
    constexpr b2Vec2& operator-=(const b2Vec2& v) noexcept {
        x -= v.x;
        y -= v.y;
        return *this;
    }
    constexpr b2Vec2& operator*=(Fixed a) noexcept {
        x *= a;
        y *= a;
        return *this;
    }
    ///@}

    /// Exact x² + y² as Q32.32 (no overflow for any vector inside the world bounds).
    constexpr Wide LengthSquaredWide() const noexcept {
        return Wide::FromRaw(detail::SumOfProducts(x.Raw(), x.Raw(), y.Raw(), y.Raw()));
    }
    /// x² + y² rounded to Q16.16. Saturates beyond 181 m: prefer LengthSquaredWide.
    constexpr Fixed LengthSquared() const noexcept { return LengthSquaredWide().ToFixed(); }
    /// Correctly rounded length (metres), exact to 0.5 ULP over the whole range.
    constexpr Fixed Length() const noexcept {
        const uint64_t sum = static_cast<uint64_t>(LengthSquaredWide().Raw());
        return Fixed::FromRaw(static_cast<int32_t>(Clamp32(detail::IsqrtRound64(sum))));
    }
    /// Scales to unit length and returns the old length. The zero vector stays zero and
    /// returns 0. |result| - 1 is within 2 ULP for any non-zero input (the direction is
    /// computed at up to 31 significant bits before rounding, so tiny vectors keep it too).
    constexpr Fixed Normalize() noexcept;

    /// Always true: fixed-point values cannot be NaN or infinite. Kept for API parity.
    constexpr bool IsValid() const noexcept { return true; }

    /// The vector rotated by +90 degrees: (-y, x).
    constexpr b2Vec2 Skew() const noexcept { return {-y, x}; }

private:
    static constexpr int64_t Clamp32(uint64_t v) noexcept {
        return v > static_cast<uint64_t>(Fixed::kMaxRaw) ? Fixed::kMaxRaw : static_cast<int64_t>(v);
    }
};

constexpr Fixed b2Vec2::Normalize() noexcept {
    if (x.Raw() == 0 || y.Raw() == 0) {
        // Along an axis (a box's edges, axis-aligned offsets) the steps below give the unit axis
        // exactly: the scaled sum is a square, so its root r is exact, and r * floor(2^62 / r)
        // falls short of 2^62 by less than r < 2^31, which rounds away at 2^46. The length is the
        // component's magnitude, clamped like the root.
        const int64_t c = int64_t{x.Raw()} + y.Raw();
        if (c == 0) return Fixed();
        const auto unit = [](int32_t v) {
            return Fixed::FromRaw(v > 0 ? Fixed::kOneRaw : v < 0 ? -Fixed::kOneRaw : 0);
        };
        x = unit(x.Raw());
        y = unit(y.Raw());
        return Fixed::FromRaw(static_cast<int32_t>(Clamp32(static_cast<uint64_t>(c < 0 ? -c : c))));
    }
    const int64_t sumSigned = LengthSquaredWide().Raw();
    const uint64_t sum = static_cast<uint64_t>(sumSigned);
    const Fixed length = Fixed::FromRaw(static_cast<int32_t>(Clamp32(detail::IsqrtRound64(sum))));
    // Scale the exact sum up to [2^60, 2^62) by an even shift 2k, so that its square root has
    // 30-31 significant bits; the components scale by 2^k and stay below 2^31.
    const int k = (std::countl_zero(sum) - 2) / 2;
    if (k < 0) {
        // Only for |v| close to the range limit: plain division is already exact enough.
        x = Fixed::FromRaw(Fixed::DivRaw(int64_t{x.Raw()} * Fixed::kOneRaw, length.Raw(), "Normalize", x.Raw()));
        y = Fixed::FromRaw(Fixed::DivRaw(int64_t{y.Raw()} * Fixed::kOneRaw, length.Raw(), "Normalize", y.Raw()));
        return length;
    }
    const uint64_t rootScaled = detail::IsqrtRound64(sum << (2 * k));  // in [2^30, 2^31]
    // One division: a 32-bit reciprocal 2^62 / root, then x*2^16/root = (xs * recip) >> 46.
    // The reciprocal's truncation costs < 2^-30 relative, far below the final rounding.
    const int64_t recip = static_cast<int64_t>((uint64_t{1} << 62) / rootScaled);
    auto scale = [&](Fixed c) {
        const int64_t cs = int64_t{c.Raw()} * (int64_t{1} << k);  // |cs| <= root < 2^31
        return Fixed::FromRaw(static_cast<int32_t>(detail::ShiftRound(cs * recip, 46)));
    };
    x = scale(x);
    y = scale(y);
    return length;
}

/// Component-wise sum and difference, and scaling by a scalar (each product rounded once).
///@{
constexpr b2Vec2 operator+(const b2Vec2& a, const b2Vec2& b) noexcept { return {a.x + b.x, a.y + b.y}; }
constexpr b2Vec2 operator-(const b2Vec2& a, const b2Vec2& b) noexcept { return {a.x - b.x, a.y - b.y}; }
constexpr b2Vec2 operator*(Fixed s, const b2Vec2& v) noexcept { return {s * v.x, s * v.y}; }
///@}
/// Exact component-wise equality of the raw values.
///@{
constexpr bool operator==(const b2Vec2& a, const b2Vec2& b) noexcept { return a.x == b.x && a.y == b.y; }
constexpr bool operator!=(const b2Vec2& a, const b2Vec2& b) noexcept { return !(a == b); }
///@}

/// Exact dot product as Q32.32.
constexpr Wide b2DotWide(const b2Vec2& a, const b2Vec2& b) noexcept {
    return Wide::FromRaw(detail::SumOfProducts(a.x.Raw(), b.x.Raw(), a.y.Raw(), b.y.Raw()));
}
/// Dot product, rounded once.
constexpr Fixed b2Dot(const b2Vec2& a, const b2Vec2& b) noexcept { return b2DotWide(a, b).ToFixed(); }
/// Exact 2D cross product a.x*b.y - a.y*b.x as Q32.32.
constexpr Wide b2CrossWide(const b2Vec2& a, const b2Vec2& b) noexcept {
    return Wide::FromRaw(detail::DiffOfProducts(a.x.Raw(), b.y.Raw(), a.y.Raw(), b.x.Raw()));
}
/// 2D cross product (a scalar), rounded once.
constexpr Fixed b2Cross(const b2Vec2& a, const b2Vec2& b) noexcept { return b2CrossWide(a, b).ToFixed(); }
/// Cross of a vector and a scalar: (s*v.y, -s*v.x).
constexpr b2Vec2 b2Cross(const b2Vec2& a, Fixed s) noexcept { return {s * a.y, -(s * a.x)}; }
/// Cross of a scalar and a vector: (-s*v.y, s*v.x).
constexpr b2Vec2 b2Cross(Fixed s, const b2Vec2& a) noexcept { return {-(s * a.y), s * a.x}; }

/// Distance between two points, correctly rounded.
constexpr Fixed b2Distance(const b2Vec2& a, const b2Vec2& b) noexcept { return (a - b).Length(); }
/// Exact squared distance as Q32.32.
constexpr Wide b2DistanceSquaredWide(const b2Vec2& a, const b2Vec2& b) noexcept { return (a - b).LengthSquaredWide(); }
/// Squared distance rounded to Q16.16 (saturates beyond 181 m).
constexpr Fixed b2DistanceSquared(const b2Vec2& a, const b2Vec2& b) noexcept { return (a - b).LengthSquared(); }

/// Component-wise |a|.
constexpr b2Vec2 b2Abs(const b2Vec2& a) noexcept { return {math::Abs(a.x), math::Abs(a.y)}; }
/// Component-wise minimum.
constexpr b2Vec2 b2Min(const b2Vec2& a, const b2Vec2& b) noexcept { return {math::Min(a.x, b.x), math::Min(a.y, b.y)}; }
/// Component-wise maximum.
constexpr b2Vec2 b2Max(const b2Vec2& a, const b2Vec2& b) noexcept { return {math::Max(a.x, b.x), math::Max(a.y, b.y)}; }
/// Component-wise clamp of a into [lo, hi].
constexpr b2Vec2 b2Clamp(const b2Vec2& a, const b2Vec2& lo, const b2Vec2& hi) noexcept {
    return b2Max(lo, b2Min(a, hi));
}

/// The zero vector.
inline constexpr b2Vec2 b2Vec2_zero{};

}  // namespace lockbox
