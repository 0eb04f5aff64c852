#pragma once
/// @file
/// Scalar math functions on lockbox::Fixed (Q16.16): square root, sine/cosine, atan2 and angle
/// wrapping, plus the angle constants. All are integer-only and bit-identical on every platform.
/// Accuracy is given in ULP = 2^-16 (1.53e-5); "correctly rounded" means <= 0.5 ULP.
///
/// The functions live in lockbox::math, out of the way of `using namespace lockbox;`; the
/// manual's names for them (b2_pi, b2Sqrt, b2Atan2, b2Abs, b2Min, b2Max, b2Clamp, ...) are in
/// lockbox, at the end of this file.

#include <bit>
#include <cstdint>
#include <type_traits>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Wide.h"
#include "lockbox/fixed/detail/Sqrt.h"
#include "lockbox/fixed/detail/Trig.h"

namespace lockbox {

namespace math {

/// pi, correctly rounded: raw 205887 (3.1415863; 0.42 ULP below pi).
inline constexpr Fixed kPi = Fixed::FromRaw(detail::kPiRaw);
/// 2 pi, correctly rounded: raw 411775 (0.17 ULP above 2 pi; not 2 * kPi).
inline constexpr Fixed kTwoPi = Fixed::FromRaw(detail::kTwoPiRaw);
/// pi / 2, correctly rounded: raw 102944 (0.29 ULP above pi/2).
inline constexpr Fixed kHalfPi = Fixed::FromRaw(detail::kHalfPiRaw);

/// Square root of x >= 0, correctly rounded (<= 0.5 ULP; checked exhaustively over all 2^31
/// non-negative inputs). Result in [0, 181.02]. A negative x is a domain error: it traps in checked builds and
/// returns 0 (counted as a saturation) otherwise.
constexpr Fixed Sqrt(Fixed x) noexcept {
    if (x.Raw() < 0) [[unlikely]]
        detail::OnOverflow("Sqrt (negative argument)", x.Raw(), 0);
    return Fixed::FromRaw(detail::SqrtRaw(x.Raw()));
}

/// Sine and cosine of one angle in radians, computed together (what b2Rot::Set needs).
/// angle: any value, [-32768, 32768) rad; the argument reduction is exact, so large angles keep
/// full accuracy. s and c are in [-1, 1], each within 1 ULP of the true value (and correctly
/// rounded for all but ~1 in 4 million inputs). sin(0) = 0 and cos(0) = 1 exactly;
/// sin(-a) = -sin(a) and cos(-a) = cos(a) exactly.
inline void SinCos(Fixed angle, Fixed& s, Fixed& c) noexcept {
    int32_t s_raw = 0;
    int32_t c_raw = 0;
    detail::SinCosRaw(angle.Raw(), &s_raw, &c_raw);
    s = Fixed::FromRaw(s_raw);
    c = Fixed::FromRaw(c_raw);
}

/// Result of SinCos(Fixed): sin and cos of the same angle, both in [-1, 1].
struct SinCosResult {
    Fixed sin;  ///< sine, within 1 ULP
    Fixed cos;  ///< cosine, within 1 ULP
};

/// Sine and cosine of one angle in radians, as a struct. Same contract as
/// SinCos(Fixed, Fixed&, Fixed&).
inline SinCosResult SinCos(Fixed angle) noexcept {
    SinCosResult r;
    SinCos(angle, r.sin, r.cos);
    return r;
}

/// Sine of an angle in radians (any value). Within 1 ULP; same kernel as SinCos.
inline Fixed Sin(Fixed angle) noexcept { return SinCos(angle).sin; }

/// Cosine of an angle in radians (any value). Within 1 ULP; same kernel as SinCos.
inline Fixed Cos(Fixed angle) noexcept { return SinCos(angle).cos; }

/// Angle of the vector (x, y) in radians, in [-pi, pi] (raw [-205887, 205887]). Any inputs:
/// only the ratio matters, and there is no overflow even for extreme values. Within 1 ULP for
/// every (y, x). Atan2(0, 0) = 0; Atan2(0, x < 0) = +pi; the axes and diagonals give
/// correctly rounded 0, +-pi/2, +-pi/4, +-3pi/4, pi. Atan2(-y, x) = -Atan2(y, x) for y != 0.
inline Fixed Atan2(Fixed y, Fixed x) noexcept { return Fixed::FromRaw(detail::Atan2Raw(y.Raw(), x.Raw())); }

/// Wraps an angle in radians into [-pi, pi) by removing whole turns of the exact 2 pi.
/// The result is the Q16.16 value nearest to a - n 2pi, with n chosen so that the exact value
/// lies in [-pi, pi); error <= 0.5 ULP, no drift from an inexact 2 pi. Raw result range
/// [-205887, 205887] (both ends are inside [-pi, pi), since pi is not representable);
/// WrapAngle(kPi) == kPi. Values already in range are returned unchanged.
inline Fixed WrapAngle(Fixed angle) noexcept { return Fixed::FromRaw(detail::WrapAngleRaw(angle.Raw())); }

/// WrapAngle that also returns the number of whole turns removed:
/// angle ~ result + turns * 2 pi (up to the 0.5 ULP rounding). turns is in [-5215, 5215].
inline Fixed WrapAngle(Fixed angle, int32_t& turns) noexcept {
    return Fixed::FromRaw(detail::WrapAngleTurnsRaw(angle.Raw(), &turns));
}

}  // namespace math

// ---- The manual's scalar names (Box2D 2.2.1's b2Settings.h and b2Math.h) -----------------

/// pi (rad), correctly rounded: raw 205887, as math::kPi.
inline constexpr Fixed b2_pi = math::kPi;

/// Always true: a Fixed cannot be NaN or infinite. Kept for API parity.
constexpr bool b2IsValid(Fixed) noexcept { return true; }

/// Square root of x >= 0, correctly rounded (math::Sqrt).
constexpr Fixed b2Sqrt(Fixed x) noexcept { return math::Sqrt(x); }
/// Angle of (x, y) in radians, in [-pi, pi], within 1 ULP (math::Atan2).
inline Fixed b2Atan2(Fixed y, Fixed x) noexcept { return math::Atan2(y, x); }

/// |a|; the most negative raw saturates.
constexpr Fixed b2Abs(Fixed a) noexcept { return math::Abs(a); }
/// |a|; the most negative raw saturates.
constexpr Wide b2Abs(Wide a) noexcept { return math::Abs(a); }
/// |a| of an integer (as Box2D's template); a must not be the type's most negative value.
template <FixedIntegral T>
constexpr T b2Abs(T a) noexcept {
    if constexpr (std::is_signed_v<T>) {
        return a < 0 ? static_cast<T>(-a) : a;
    } else {
        return a;
    }
}

/// The smaller of a and b.
constexpr Fixed b2Min(Fixed a, Fixed b) noexcept { return math::Min(a, b); }
/// The smaller of a and b.
constexpr Wide b2Min(Wide a, Wide b) noexcept { return math::Min(a, b); }
/// The smaller of two integers of one type (as Box2D's template).
template <FixedIntegral T>
constexpr T b2Min(T a, T b) noexcept {
    return a < b ? a : b;
}

/// The larger of a and b.
constexpr Fixed b2Max(Fixed a, Fixed b) noexcept { return math::Max(a, b); }
/// The larger of a and b.
constexpr Wide b2Max(Wide a, Wide b) noexcept { return math::Max(a, b); }
/// The larger of two integers of one type (as Box2D's template).
template <FixedIntegral T>
constexpr T b2Max(T a, T b) noexcept {
    return a > b ? a : b;
}

/// a clamped into [low, high]; low must not exceed high.
constexpr Fixed b2Clamp(Fixed a, Fixed low, Fixed high) noexcept { return math::Clamp(a, low, high); }
/// a clamped into [low, high]; low must not exceed high.
constexpr Wide b2Clamp(Wide a, Wide low, Wide high) noexcept { return math::Clamp(a, low, high); }
/// An integer clamped into [low, high] (as Box2D's template).
template <FixedIntegral T>
constexpr T b2Clamp(T a, T low, T high) noexcept {
    return b2Max(low, b2Min(a, high));
}

/// Exchanges a and b.
template <typename T>
constexpr void b2Swap(T& a, T& b) noexcept {
    T tmp = a;
    a = b;
    b = tmp;
}

/// The smallest power of two greater than x, for x < 2^31; 0 for larger x (none fits 32 bits;
/// Box2D's bit trick gives 0 there too).
constexpr uint32_t b2NextPowerOfTwo(uint32_t x) noexcept { return x >= 0x80000000u ? 0u : std::bit_ceil(x + 1u); }

/// True when x is a power of two (x > 0).
constexpr bool b2IsPowerOfTwo(uint32_t x) noexcept { return x > 0 && (x & (x - 1)) == 0; }

}  // namespace lockbox
