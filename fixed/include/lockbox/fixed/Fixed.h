#pragma once
/// @file
/// lockbox::Fixed: the Q16.16 state type (positions, velocities, angles, rotations, the time
/// step). Range [-32768, 32768) with a resolution of 2^-16 (1.53e-5).
///
/// Rounding rule, everywhere in fixed/: round to nearest, ties away from zero. It is symmetric,
/// so (-a)*b == -(a*b) and a mirrored scene rounds as a mirror. Overflow saturates or traps, see
/// Overflow.h. Conversions from floating point exist only at compile time (`consteval`), so a
/// run-time float can never slip into the simulation; `FromDoubleNondeterministic` is the one
/// named escape hatch, for tools.

#include <compare>
#include <concepts>
#include <cstdint>
#include <limits>
#include <string_view>

#include "lockbox/Export.h"
#include "lockbox/fixed/Overflow.h"
#include "lockbox/fixed/detail/Decimal.h"
#include "lockbox/fixed/detail/Int128.h"

namespace lockbox {

namespace detail {
/// Correctly rounded double -> raw conversion for compile-time literals. Exact: scaling a double
/// by a power of two is exact, and the rounding is done on the integer and remainder.
consteval int64_t RoundDoubleToRaw(double v, int fracBits) {
    if (!(v == v)) throw "lockbox: NaN literal";  // not a constant expression: compile error
    double scaled = v;
    for (int i = 0; i < fracBits; ++i) scaled *= 2.0;
    const bool negative = scaled < 0;
    const double mag = negative ? -scaled : scaled;
    if (mag >= 9.2e18) throw "lockbox: literal out of range";
    const int64_t whole = static_cast<int64_t>(mag);  // truncation, exact for mag < 2^63
    const double rest = mag - static_cast<double>(whole);
    const int64_t r = whole + (rest >= 0.5 ? 1 : 0);
    return negative ? -r : r;
}

/// Saturating narrow of an int64 raw result to int32, reporting overflow.
constexpr int32_t NarrowRaw(int64_t v, const char* op, int64_t a, int64_t b) noexcept {
    constexpr int64_t kMax = std::numeric_limits<int32_t>::max();
    if (v > kMax || v < -kMax) [[unlikely]] {
        OnOverflow(op, a, b);
        return v > 0 ? static_cast<int32_t>(kMax) : static_cast<int32_t>(-kMax);
    }
    return static_cast<int32_t>(v);
}

/// (p + half) >> shift with ties away from zero; p must leave room for the bias (|p| < 2^62).
constexpr int64_t ShiftRound(int64_t p, int shift) noexcept {
    const int64_t half = int64_t{1} << (shift - 1);
    // For negative p the bias is half - 1, so an exact tie floors to the larger magnitude.
    return (p + half + (p >> 63)) >> shift;
}
}  // namespace detail

/// The integer types a Fixed converts from implicitly and exactly: every built-in integral type
/// except bool.
template <typename T>
concept FixedIntegral = std::integral<T> && !std::same_as<T, bool>;

/// Q16.16 fixed-point number: a 32-bit signed integer counting units of 2^-16. It is the type of
/// positions (m), angles (rad), velocities, forces, coefficients and the time step (s); mass,
/// inertia and impulses are Wide. Arithmetic rounds to nearest with ties away from zero and
/// saturates to +-kMaxRaw (or traps in checked builds, see Overflow.h), so it never produces the
/// raw INT32_MIN. Construct from integers, `_fx` literals, compile-time float literals, FromRatio,
/// Parse or FromRaw.
class LOCKBOX_API Fixed {
public:
    /// Number of fractional bits: a raw value r means r / 2^16.
    static constexpr int kFractionBits = 16;
    /// The raw value of 1.0 (65536).
    static constexpr int32_t kOneRaw = int32_t{1} << kFractionBits;
    /// Largest raw value (INT32_MAX, just under 32768.0); the saturation limit is +-kMaxRaw.
    static constexpr int32_t kMaxRaw = std::numeric_limits<int32_t>::max();

    /// Zero.
    constexpr Fixed() noexcept = default;

    /// Exact conversion from an integer in [-32767, 32767]; out of range saturates (or traps).
    template <FixedIntegral I>
    constexpr Fixed(I v) noexcept : m_raw(FromInteger(v)) {}  // NOLINT: implicit, exact

    /// Compile-time conversion of a floating-point literal, correctly rounded (ties away from
    /// zero). A run-time float or double does not compile: use the `_fx` literal, FromRatio,
    /// Parse, or the named FromDoubleNondeterministic.
    consteval Fixed(double v) : m_raw(CheckedLiteral(detail::RoundDoubleToRaw(v, kFractionBits))) {}  // NOLINT
    /// Compile-time conversion of a float literal; same rules as the double overload.
    consteval Fixed(float v)  // NOLINT
        : m_raw(CheckedLiteral(detail::RoundDoubleToRaw(static_cast<double>(v), kFractionBits))) {}

    /// Bit-exact construction from a raw Q16.16 value.
    static constexpr Fixed FromRaw(int32_t raw) noexcept {
        Fixed f;
        f.m_raw = raw;
        return f;
    }
    /// The raw Q16.16 value.
    constexpr int32_t Raw() const noexcept { return m_raw; }

    /// num/den correctly rounded (ties away from zero); den must not be 0.
    static constexpr Fixed FromRatio(int64_t num, int64_t den) noexcept;

    /// Parses decimal text exactly ("-12.375", "1e-3"); no floating point is involved.
    /// Returns false and leaves `out` unchanged on malformed or out-of-range text.
    static constexpr bool Parse(std::string_view text, Fixed& out, const char** error = nullptr) noexcept {
        const detail::DecimalResult r = detail::ParseDecimal(text, kFractionBits, kMaxRaw);
        if (r.error != detail::DecimalError::None) {
            if (error) *error = detail::DecimalErrorMessage(r.error);
            return false;
        }
        out = FromRaw(static_cast<int32_t>(r.raw));
        return true;
    }

    /// For display and debug draw only.
    constexpr double ToDouble() const noexcept { return static_cast<double>(m_raw) / kOneRaw; }
    /// For display and debug draw only: ToDouble() narrowed to float.
    constexpr float ToFloat() const noexcept { return static_cast<float>(ToDouble()); }

    /// Run-time conversion from double for tools (scene editors, plots). NOT deterministic
    /// across platforms (x87 excess precision, FMA); never use it in simulation code.
    static Fixed FromDoubleNondeterministic(double v) noexcept;

    /// Compares the raw values: the order and equality of the numbers they represent.
    ///@{
    constexpr auto operator<=>(const Fixed&) const noexcept = default;
    constexpr bool operator==(const Fixed&) const noexcept = default;
    ///@}

    /// Unary plus returns the value; unary minus negates it exactly (the raw INT32_MIN, which
    /// arithmetic never produces, saturates to kMaxRaw).
    ///@{
    constexpr Fixed operator+() const noexcept { return *this; }
    constexpr Fixed operator-() const noexcept {
        if (m_raw == std::numeric_limits<int32_t>::min()) [[unlikely]] {
            detail::OnOverflow("Fixed::operator- (negate)", m_raw, 0);
            return FromRaw(kMaxRaw);
        }
        return FromRaw(-m_raw);
    }
    ///@}

    /// Arithmetic on two Fixed values. + and - are exact unless the result leaves the range; * and
    /// / round the exact result to the nearest multiple of 2^-16, ties away from zero. Out-of-range
    /// results and division by zero saturate to +-kMaxRaw (or trap in checked builds, see
    /// Overflow.h).
    ///@{
    friend constexpr Fixed operator+(Fixed a, Fixed b) noexcept {
        return FromRaw(detail::NarrowRaw(int64_t{a.m_raw} + b.m_raw, "Fixed::operator+", a.m_raw, b.m_raw));
    }
    friend constexpr Fixed operator-(Fixed a, Fixed b) noexcept {
        return FromRaw(detail::NarrowRaw(int64_t{a.m_raw} - b.m_raw, "Fixed::operator-", a.m_raw, b.m_raw));
    }
    friend constexpr Fixed operator*(Fixed a, Fixed b) noexcept {
        const int64_t p = int64_t{a.m_raw} * b.m_raw;
        return FromRaw(detail::NarrowRaw(detail::ShiftRound(p, kFractionBits), "Fixed::operator*", a.m_raw, b.m_raw));
    }
    friend constexpr Fixed operator/(Fixed a, Fixed b) noexcept {
        return FromRaw(DivRaw(int64_t{a.m_raw} * kOneRaw, b.m_raw, "Fixed::operator/", a.m_raw));
    }
    ///@}

    /// Compound assignment: `a op= b` is `a = a op b`, with the same rounding and saturation.
    ///@{
    constexpr Fixed& operator+=(Fixed b) noexcept { return *this = *this + b; }
    constexpr Fixed& operator-=(Fixed b) noexcept { return *this = *this - b; }
    constexpr Fixed& operator*=(Fixed b) noexcept { return *this = *this * b; }
    constexpr Fixed& operator/=(Fixed b) noexcept { return *this = *this / b; }
    ///@}

    /// round(num / den) into raw, ties away from zero, saturating; num is any int64 with
    /// |num| < 2^62. Shared by division, FromRatio and the wide type's narrowing.
    static constexpr int32_t DivRaw(int64_t num, int64_t den, const char* op, int64_t a) noexcept {
        if (den == 0) [[unlikely]] {
            detail::OnOverflow(op, a, 0);
            return num == 0 ? 0 : (num > 0 ? kMaxRaw : -kMaxRaw);
        }
        const bool negative = (num < 0) != (den < 0);
        const uint64_t n = num < 0 ? uint64_t{0} - static_cast<uint64_t>(num) : static_cast<uint64_t>(num);
        const uint64_t d = den < 0 ? uint64_t{0} - static_cast<uint64_t>(den) : static_cast<uint64_t>(den);
        uint64_t q = n / d;
        const uint64_t r = n - q * d;
        if (r >= d - r) ++q;  // 2r >= d without overflow: ties away from zero
        if (q > static_cast<uint64_t>(kMaxRaw)) [[unlikely]] {
            detail::OnOverflow(op, a, den);
            return negative ? -kMaxRaw : kMaxRaw;
        }
        return negative ? -static_cast<int32_t>(q) : static_cast<int32_t>(q);
    }

private:
    template <FixedIntegral I>
    static constexpr int32_t FromInteger(I v) noexcept {
        constexpr int64_t kLimit = kMaxRaw >> kFractionBits;  // 32767
        if constexpr (std::is_signed_v<I>) {
            if (v > kLimit || v < -kLimit) [[unlikely]] {
                detail::OnOverflow("Fixed(integer)", static_cast<int64_t>(v), 0);
                return v > 0 ? kMaxRaw : -kMaxRaw;
            }
            return static_cast<int32_t>(static_cast<int64_t>(v) * kOneRaw);
        } else {
            if (v > static_cast<uint64_t>(kLimit)) [[unlikely]] {
                detail::OnOverflow("Fixed(integer)", static_cast<int64_t>(v > INT64_MAX ? INT64_MAX : v), 0);
                return kMaxRaw;
            }
            return static_cast<int32_t>(static_cast<int64_t>(v) * kOneRaw);
        }
    }

    static consteval int32_t CheckedLiteral(int64_t raw) {
        if (raw > kMaxRaw || raw < -kMaxRaw) throw "lockbox: Fixed literal out of range";
        return static_cast<int32_t>(raw);
    }

    int32_t m_raw = 0;
};

constexpr Fixed Fixed::FromRatio(int64_t num, int64_t den) noexcept {
    if (den == 0) [[unlikely]] {
        detail::OnOverflow("Fixed::FromRatio (division by zero)", num, den);
        return FromRaw(num == 0 ? 0 : (num > 0 ? kMaxRaw : -kMaxRaw));
    }
    const detail::S128 n = detail::MulS64(num, kOneRaw);
    const detail::S128 d = detail::MulS64(den, 1);
    const detail::S128 q = detail::DivRoundS128(n, d);
    if (q.mag.hi != 0 || q.mag.lo > static_cast<uint64_t>(kMaxRaw)) [[unlikely]] {
        detail::OnOverflow("Fixed::FromRatio", num, den);
        return FromRaw(q.negative ? -kMaxRaw : kMaxRaw);
    }
    const int32_t m = static_cast<int32_t>(q.mag.lo);
    return FromRaw(q.negative ? -m : m);
}

/// Scalar helpers on Fixed and Wide (and the angle functions of Functions.h). They live in a
/// namespace of their own so that `using namespace lockbox;` does not bring names as common as
/// Min, Max or Round into a game's code; the manual's b2Min, b2Max, b2Abs... call them.
namespace math {

/// |a|; |min raw| saturates.
constexpr Fixed Abs(Fixed a) noexcept { return a < Fixed() ? -a : a; }
/// The smaller of a and b.
constexpr Fixed Min(Fixed a, Fixed b) noexcept { return b < a ? b : a; }
/// The larger of a and b.
constexpr Fixed Max(Fixed a, Fixed b) noexcept { return a < b ? b : a; }
/// Clamps a into [lo, hi]; lo must not exceed hi.
constexpr Fixed Clamp(Fixed a, Fixed lo, Fixed hi) noexcept { return Max(lo, Min(a, hi)); }
/// Largest integer value <= a.
constexpr Fixed Floor(Fixed a) noexcept { return Fixed::FromRaw(a.Raw() & ~(Fixed::kOneRaw - 1)); }
/// Smallest integer value >= a (saturates near the top of the range).
constexpr Fixed Ceil(Fixed a) noexcept {
    const int64_t r = (int64_t{a.Raw()} + (Fixed::kOneRaw - 1)) & ~int64_t{Fixed::kOneRaw - 1};
    return Fixed::FromRaw(detail::NarrowRaw(r, "Ceil", a.Raw(), 0));
}
/// Nearest integer value, ties away from zero.
constexpr Fixed Round(Fixed a) noexcept {
    const int64_t r = detail::ShiftRound(a.Raw(), Fixed::kFractionBits) * Fixed::kOneRaw;
    return Fixed::FromRaw(detail::NarrowRaw(r, "Round", a.Raw(), 0));
}
/// Sign as -1, 0 or +1.
constexpr int Sign(Fixed a) noexcept { return (a.Raw() > 0) - (a.Raw() < 0); }

}  // namespace math

// Inline, as std::literals is: `using namespace lockbox;` brings `_fx` too.
inline namespace literals {
/// Exact decimal literal: `12.375_fx`, `1e-3_fx`. Rounded to nearest, ties away from zero.
template <char... Chars>
consteval Fixed operator""_fx() {
    constexpr char text[] = {Chars...};
    constexpr detail::DecimalResult r =
        detail::ParseDecimal(std::string_view(text, sizeof...(Chars)), Fixed::kFractionBits, Fixed::kMaxRaw);
    static_assert(r.error == detail::DecimalError::None, "lockbox: invalid or out-of-range _fx literal");
    return Fixed::FromRaw(static_cast<int32_t>(r.raw));
}
}  // namespace literals

}  // namespace lockbox

/// Fixed as a numeric type: a bounded, exact, signed binary format with 31 value bits, which rounds
/// to nearest (ties away from zero) and has no infinity or NaN.
template <>
class std::numeric_limits<lockbox::Fixed> {
public:
    /// The traits of Q16.16: signed, exact (no representation error for the values it can hold),
    /// not an integer type, bounded, not modular (overflow saturates), radix 2 with 31 value digits
    /// (9 decimal), no infinity or NaN, rounding to nearest.
    ///@{
    static constexpr bool is_specialized = true;
    static constexpr bool is_signed = true;
    static constexpr bool is_integer = false;
    static constexpr bool is_exact = true;
    static constexpr bool has_infinity = false;
    static constexpr bool has_quiet_NaN = false;
    static constexpr bool has_signaling_NaN = false;
    static constexpr bool is_bounded = true;
    static constexpr bool is_modulo = false;
    static constexpr int radix = 2;
    static constexpr int digits = 31;
    static constexpr int digits10 = 9;
    static constexpr std::float_round_style round_style = std::round_to_nearest;
    ///@}
    /// Smallest positive value (one raw unit, 2^-16), as min() means for floating types; the most
    /// negative value is lowest().
    static constexpr lockbox::Fixed min() noexcept { return lockbox::Fixed::FromRaw(1); }
    /// Most negative value: -kMaxRaw raw (about -32768.0); saturation never goes below it.
    static constexpr lockbox::Fixed lowest() noexcept { return lockbox::Fixed::FromRaw(-lockbox::Fixed::kMaxRaw); }
    /// Largest value: kMaxRaw raw (32767.99998).
    static constexpr lockbox::Fixed max() noexcept { return lockbox::Fixed::FromRaw(lockbox::Fixed::kMaxRaw); }
    /// Distance from 1.0 to the next value: one raw unit, 2^-16.
    static constexpr lockbox::Fixed epsilon() noexcept { return lockbox::Fixed::FromRaw(1); }
    /// Largest rounding error of one operation in units of epsilon(), as the standard defines it
    /// for float: 0.5 (round to nearest).
    static constexpr lockbox::Fixed round_error() noexcept {
        return lockbox::Fixed::FromRaw(lockbox::Fixed::kOneRaw / 2);
    }
    /// Smallest positive value (one raw unit); the format has no subnormals.
    static constexpr lockbox::Fixed denorm_min() noexcept { return lockbox::Fixed::FromRaw(1); }
};
