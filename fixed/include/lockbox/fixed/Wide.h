#pragma once
/// @file
/// lockbox::Wide: Q32.32 in an int64_t, for the quantities Q16.16 cannot carry (docs/numerics.md):
/// mass, rotational inertia and their inverses, effective masses, impulses, spring
/// coefficients and squared lengths. Range +-2.1e9, resolution 2.3e-10.
///
/// Every change between Fixed and Wide is explicit: Wide(Fixed) widens exactly, ToFixed()
/// rounds (ties away from zero) and saturates. Products use a 64x64->128 multiply (native or
/// the portable limb version, which gives the same bits).

#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/detail/Int128.h"

namespace lockbox {

namespace detail {
/// Saturating narrow of a 128-bit signed value to a Q32.32 raw.
constexpr int64_t NarrowWide(const S128& v, const char* op, int64_t a, int64_t b) noexcept {
    constexpr uint64_t kMax = static_cast<uint64_t>(std::numeric_limits<int64_t>::max());
    if (v.mag.hi != 0 || v.mag.lo > kMax) [[unlikely]] {
        OnOverflow(op, a, b);
        return v.negative ? -static_cast<int64_t>(kMax) : static_cast<int64_t>(kMax);
    }
    return v.negative ? -static_cast<int64_t>(v.mag.lo) : static_cast<int64_t>(v.mag.lo);
}

#ifdef LOCKBOX_NATIVE_INT128
/// A rounded magnitude with its sign as a Q32.32 raw, saturating to +-INT64_MAX (with the
/// overflow report of operation `op` on operands a and b), as NarrowWide does for limbs.
[[gnu::always_inline]] constexpr int64_t NarrowMagnitude(NativeU128 mag, bool negative, const char* op, int64_t a,
                                                         int64_t b) noexcept {
    constexpr uint64_t kMax = static_cast<uint64_t>(std::numeric_limits<int64_t>::max());
    if (mag > kMax) [[unlikely]] {
        OnOverflow(op, a, b);
        return negative ? -static_cast<int64_t>(kMax) : static_cast<int64_t>(kMax);
    }
    const auto m = static_cast<int64_t>(mag);
    return negative ? -m : m;
}
#endif

/// round(a * b / 2^shift), ties away from zero, saturating to +-INT64_MAX.
// Always inlined: the hot solver loops call it several hundred times per contact, and the
// fast path is a handful of instructions once the shift is a constant.
[[gnu::always_inline]] constexpr int64_t MulShiftRound64(int64_t a, int64_t b, int shift, const char* op) noexcept {
    // Fast path (shift in 1..62): when a*b and the biased a*b + half - (a*b < 0) both fit in
    // int64, the 128-bit computation below works on the very same integer and its floor shift
    // gives the same value, which cannot saturate (|result| <= 2^(63 - shift)). So this path
    // returns bit-identical results without the 128-bit product; anything else falls through.
    int64_t product = 0;
    if (!__builtin_mul_overflow(a, b, &product)) [[likely]] {
        const int64_t bias = (int64_t{1} << (shift - 1)) + (product >> 63);
        int64_t biased = 0;
        if (!__builtin_add_overflow(product, bias, &biased)) [[likely]]
            return biased >> shift;
    }
#ifdef LOCKBOX_NATIVE_INT128
    // On magnitudes: floor((p + half - (p < 0)) / 2^shift) of the signed product p equals the
    // sign of p times floor((|p| + half) / 2^shift) (ties away from zero either way), so one
    // unsigned 64x64 multiply does. |a b| <= 2^126 leaves room for the bias. On overflow the
    // result has the product's sign, which is then non-zero.
    const NativeU128 mag = static_cast<NativeU128>(AbsU64(a)) * AbsU64(b);
    const NativeU128 r = (mag + (static_cast<NativeU128>(1) << (shift - 1))) >> shift;
    return NarrowMagnitude(r, (a < 0) != (b < 0), op, a, b);
#else
    return NarrowWide(ShrRoundS128(MulS64(a, b), shift), op, a, b);
#endif
}

/// round(a * 2^shift / b), ties away from zero, saturating; b == 0 reports and saturates.
constexpr int64_t DivShiftRound64(int64_t a, int64_t b, int shift, const char* op) noexcept {
    if (b == 0) [[unlikely]] {
        OnOverflow(op, a, 0);
        return a == 0 ? 0 : (a > 0 ? std::numeric_limits<int64_t>::max() : -std::numeric_limits<int64_t>::max());
    }
    // Fast paths (shift in 1..63) for a quotient that fits in 64 bits. They compute the same
    // truncated quotient and remainder of |a| 2^shift / |b| as DivRoundS128, round up iff
    // 2 rem >= |b| (written without overflow as rem >= |b| - rem, since rem < |b|), and narrow
    // through the same NarrowWide, so value and overflow reports are identical.
    const uint64_t magA = AbsU64(a);
    const uint64_t den = AbsU64(b);
    const bool shiftOk = shift > 0 && shift < 64;  // every caller uses 32; others skip ahead
    const uint64_t numHi = shiftOk ? magA >> (64 - shift) : 0;
    const uint64_t numLo = shiftOk ? magA << shift : 0;
    const bool negative = (a < 0) != (b < 0);
    auto finish = [&](uint64_t q, uint64_t rem) {
        // q + 1 wraps only for q = 2^64 - 1; the carry then goes to the high limb.
        U128 mag{0, q};
        if (rem >= den - rem) mag = AddU128(mag, 1);
        const S128 r{negative && (mag.hi | mag.lo) != 0, mag};
        return NarrowWide(r, op, a, b);
    };
    if (shiftOk && numHi == 0) [[likely]] {
        const uint64_t q = numLo / den;
        return finish(q, numLo - q * den);
    }
#if defined(__x86_64__) && defined(LOCKBOX_NATIVE_INT128)
    // One hardware 128/64 division; numHi < den guarantees the quotient fits (no #DE).
    if (!std::is_constant_evaluated() && shiftOk && numHi < den) {
        uint64_t q = 0, rem = 0;
        __asm__("divq %4" : "=a"(q), "=d"(rem) : "a"(numLo), "d"(numHi), "rm"(den) : "cc");
        return finish(q, rem);
    }
#endif
    S128 n;
    n.negative = a < 0;
    n.mag = ShlU128(U128{0, magA}, shift);
    S128 d;
    d.negative = b < 0;
    d.mag = U128{0, den};
    return NarrowWide(DivRoundS128(n, d), op, a, b);
}
}  // namespace detail

/// Q32.32 fixed-point number in an int64_t: the type of mass, inertia and their inverses, effective
/// masses, impulses and squared lengths, which overflow or lose too much precision in Q16.16. Range
/// about +-2.1e9, resolution 2^-32. Arithmetic rounds to nearest (ties away from zero) and
/// saturates to +-kMaxRaw (or traps in checked builds, see Overflow.h); conversions to and from
/// Fixed are explicit.
class Wide {
public:
    /// Number of fractional bits: a raw value r means r / 2^32.
    static constexpr int kFractionBits = 32;
    /// The raw value of 1.0 (2^32).
    static constexpr int64_t kOneRaw = int64_t{1} << kFractionBits;
    /// Largest raw value (INT64_MAX, just under 2^31); the saturation limit is +-kMaxRaw.
    static constexpr int64_t kMaxRaw = std::numeric_limits<int64_t>::max();

    constexpr Wide() noexcept = default;

    /// Exact conversion from an integer in [-2^31+1, 2^31-1]; beyond saturates (or traps).
    template <FixedIntegral I>
    constexpr Wide(I v) noexcept : m_raw(FromInteger(v)) {}  // NOLINT: implicit, exact

    /// Compile-time literal, correctly rounded.
    consteval Wide(double v) : m_raw(detail::RoundDoubleToRaw(v, kFractionBits)) {}  // NOLINT

    /// Exact widening of a Q16.16 value.
    constexpr explicit Wide(Fixed f) noexcept : m_raw(int64_t{f.Raw()} * (int64_t{1} << 16)) {}

    /// Bit-exact construction from a raw Q32.32 value.
    static constexpr Wide FromRaw(int64_t raw) noexcept {
        Wide w;
        w.m_raw = raw;
        return w;
    }
    /// The raw Q32.32 value.
    constexpr int64_t Raw() const noexcept { return m_raw; }

    /// num/den correctly rounded; den must not be 0.
    static constexpr Wide FromRatio(int64_t num, int64_t den) noexcept {
        return FromRaw(detail::DivShiftRound64(num, den, kFractionBits, "Wide::FromRatio"));
    }

    /// Narrows to Q16.16, rounding to nearest (ties away from zero) and saturating.
    [[gnu::always_inline]] constexpr Fixed ToFixed() const noexcept {
        // Fast path: raws in [-kFitRaw, kFitRaw] round to a Q16.16 value inside +-kMaxRaw, and
        // the clamp below leaves them alone (|raw| < 2^48), so the result is the same rounding
        // with no saturation; the single range test replaces the clamp and the narrow test.
        constexpr int64_t kFitRaw = (int64_t{Fixed::kMaxRaw} << 16) + (int64_t{1} << 15) - 1;
        if (m_raw >= -kFitRaw && m_raw <= kFitRaw) [[likely]] {
            return Fixed::FromRaw(static_cast<int32_t>(detail::ShiftRound(m_raw, 16)));
        }
        constexpr int64_t kBiasRoom = int64_t{1} << 62;  // beyond it the result saturates anyway
        const int64_t r = m_raw >= kBiasRoom ? kBiasRoom : m_raw <= -kBiasRoom ? -kBiasRoom : m_raw;
        return Fixed::FromRaw(detail::NarrowRaw(detail::ShiftRound(r, 16), "Wide::ToFixed", m_raw, 0));
    }

    /// Parses decimal text exactly. Returns false and leaves `out` unchanged on error.
    static constexpr bool Parse(std::string_view text, Wide& out, const char** error = nullptr) noexcept {
        const detail::DecimalResult r = detail::ParseDecimal(text, kFractionBits, kMaxRaw);
        if (r.error != detail::DecimalError::None) {
            if (error) *error = detail::DecimalErrorMessage(r.error);
            return false;
        }
        out = FromRaw(r.raw);
        return true;
    }

    /// For display only.
    constexpr double ToDouble() const noexcept { return static_cast<double>(m_raw) / static_cast<double>(kOneRaw); }

    /// Compares the raw values: the order and equality of the numbers they represent.
    ///@{
    constexpr auto operator<=>(const Wide&) const noexcept = default;
    constexpr bool operator==(const Wide&) const noexcept = default;
    ///@}

    /// Unary plus returns the value; unary minus negates it exactly (the raw INT64_MIN, which
    /// arithmetic never produces, saturates to kMaxRaw).
    ///@{
    constexpr Wide operator+() const noexcept { return *this; }
    constexpr Wide operator-() const noexcept {
        if (m_raw == std::numeric_limits<int64_t>::min()) [[unlikely]] {
            detail::OnOverflow("Wide::operator- (negate)", m_raw, 0);
            return FromRaw(kMaxRaw);
        }
        return FromRaw(-m_raw);
    }
    ///@}
    // The two tests of + and - are separate branches to the same saturation: GCC then
    // branches on the overflow flag directly instead of materialising it (same results).
    /// Arithmetic on two Wide values. + and - are exact unless the result leaves the range; * and /
    /// round the exact 128-bit result to the nearest multiple of 2^-32, ties away from zero.
    /// Out-of-range results and division by zero saturate to +-kMaxRaw (or trap in checked builds).
    ///@{
    [[gnu::always_inline]] friend constexpr Wide operator+(Wide a, Wide b) noexcept {
        int64_t r = 0;
        if (__builtin_add_overflow(a.m_raw, b.m_raw, &r)) [[unlikely]]
            return SaturateAdd(a, b);
        if (r == std::numeric_limits<int64_t>::min()) [[unlikely]]
            return SaturateAdd(a, b);
        return FromRaw(r);
    }
    [[gnu::always_inline]] friend constexpr Wide operator-(Wide a, Wide b) noexcept {
        int64_t r = 0;
        if (__builtin_sub_overflow(a.m_raw, b.m_raw, &r)) [[unlikely]]
            return SaturateSub(a, b);
        if (r == std::numeric_limits<int64_t>::min()) [[unlikely]]
            return SaturateSub(a, b);
        return FromRaw(r);
    }
    [[gnu::always_inline]] friend constexpr Wide operator*(Wide a, Wide b) noexcept {
        return FromRaw(detail::MulShiftRound64(a.m_raw, b.m_raw, kFractionBits, "Wide::operator*"));
    }
    friend constexpr Wide operator/(Wide a, Wide b) noexcept {
        return FromRaw(detail::DivShiftRound64(a.m_raw, b.m_raw, kFractionBits, "Wide::operator/"));
    }
    ///@}
    /// Compound assignment: `a op= b` is `a = a op b`, with the same rounding and saturation.
    ///@{
    constexpr Wide& operator+=(Wide b) noexcept { return *this = *this + b; }
    constexpr Wide& operator-=(Wide b) noexcept { return *this = *this - b; }
    constexpr Wide& operator*=(Wide b) noexcept { return *this = *this * b; }
    constexpr Wide& operator/=(Wide b) noexcept { return *this = *this / b; }
    ///@}

private:
    static Wide SaturateAdd(Wide a, Wide b) noexcept {
        detail::OnOverflow("Wide::operator+", a.m_raw, b.m_raw);
        return FromRaw(a.m_raw > 0 ? kMaxRaw : -kMaxRaw);
    }
    static Wide SaturateSub(Wide a, Wide b) noexcept {
        detail::OnOverflow("Wide::operator-", a.m_raw, b.m_raw);
        return FromRaw(a.m_raw >= 0 ? kMaxRaw : -kMaxRaw);
    }

    template <FixedIntegral I>
    static constexpr int64_t FromInteger(I v) noexcept {
        constexpr int64_t kLimit = kMaxRaw >> kFractionBits;
        if constexpr (std::is_signed_v<I>) {
            if (static_cast<int64_t>(v) > kLimit || static_cast<int64_t>(v) < -kLimit) [[unlikely]] {
                detail::OnOverflow("Wide(integer)", static_cast<int64_t>(v), 0);
                return v > 0 ? kMaxRaw : -kMaxRaw;
            }
        } else {
            if (static_cast<uint64_t>(v) > static_cast<uint64_t>(kLimit)) [[unlikely]] {
                detail::OnOverflow("Wide(integer)", kLimit, 0);
                return kMaxRaw;
            }
        }
        return static_cast<int64_t>(v) * kOneRaw;
    }

    int64_t m_raw = 0;
};

/// Exact product of two Q16.16 values as Q32.32 (no rounding at all).
constexpr Wide MulWide(Fixed a, Fixed b) noexcept { return Wide::FromRaw(int64_t{a.Raw()} * b.Raw()); }

/// Wide * Fixed -> Wide, one rounding.
///
/// Only for operands that are exactly a Wide and a Fixed (hence the templates): an integer or a
/// literal converts to both types, so as plain overloads these would compete with Fixed * Fixed
/// and Wide * Wide and make `2 * x` or `0.5 * w` ambiguous. With them constrained, a number
/// mixed with a Fixed is a Fixed, and mixed with a Wide is a Wide.
template <std::same_as<Wide> W, std::same_as<Fixed> F>
[[gnu::always_inline]] constexpr Wide operator*(W a, F b) noexcept {
    return Wide::FromRaw(detail::MulShiftRound64(a.Raw(), b.Raw(), Fixed::kFractionBits, "Wide*Fixed"));
}
/// Fixed * Wide -> Wide, one rounding (the same product as Wide * Fixed).
template <std::same_as<Fixed> F, std::same_as<Wide> W>
[[gnu::always_inline]] constexpr Wide operator*(F a, W b) noexcept {
    return b * a;
}

/// Wide * Fixed rounded straight to Fixed (one rounding): impulse * inverse mass -> velocity.
[[gnu::always_inline]] constexpr Fixed MulToFixed(Wide a, Fixed b) noexcept {
    const int64_t r = detail::MulShiftRound64(a.Raw(), b.Raw(), Wide::kFractionBits, "MulToFixed");
    return Fixed::FromRaw(detail::NarrowRaw(r, "MulToFixed", a.Raw(), b.Raw()));
}
/// Wide * Wide rounded straight to Fixed (one rounding).
[[gnu::always_inline]] constexpr Fixed MulToFixed(Wide a, Wide b) noexcept {
    const int64_t r = detail::MulShiftRound64(a.Raw(), b.Raw(), Wide::kFractionBits + 16, "MulToFixed");
    return Fixed::FromRaw(detail::NarrowRaw(r, "MulToFixed", a.Raw(), b.Raw()));
}
/// Fixed / Wide rounded to Fixed: round(a.raw * 2^32 / b.raw).
constexpr Fixed DivToFixed(Fixed a, Wide b) noexcept {
    const int64_t r = detail::DivShiftRound64(a.Raw(), b.Raw(), Wide::kFractionBits, "DivToFixed");
    return Fixed::FromRaw(detail::NarrowRaw(r, "DivToFixed", a.Raw(), b.Raw()));
}

namespace math {
/// |a|; |min raw| saturates.
constexpr Wide Abs(Wide a) noexcept { return a < Wide() ? -a : a; }
/// The smaller of a and b.
constexpr Wide Min(Wide a, Wide b) noexcept { return b < a ? b : a; }
/// The larger of a and b.
constexpr Wide Max(Wide a, Wide b) noexcept { return a < b ? b : a; }
/// Clamps a into [lo, hi]; lo must not exceed hi.
constexpr Wide Clamp(Wide a, Wide lo, Wide hi) noexcept { return Max(lo, Min(a, hi)); }
}  // namespace math

}  // namespace lockbox
