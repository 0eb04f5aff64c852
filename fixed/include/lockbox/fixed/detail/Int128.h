#pragma once
/// 128-bit helpers for the wide (Q32.32) products and the 2x2/3x3 solves.
///
/// `__int128` exists only on 64-bit GCC/Clang targets. i686 has none, so a portable
/// struct of two 64-bit limbs gives the same bits. Define LOCKBOX_PORTABLE_INT128 to force
/// the portable path on 64-bit hosts too: CI builds it that way to prove both agree.

#include <bit>
#include <cstdint>
#include <type_traits>

#if defined(__SIZEOF_INT128__) && !defined(LOCKBOX_PORTABLE_INT128)
#define LOCKBOX_NATIVE_INT128 1
#endif

namespace lockbox::detail {

#ifdef LOCKBOX_NATIVE_INT128
__extension__ typedef __int128 NativeI128;           // NOLINT: -Wpedantic-clean alias
__extension__ typedef unsigned __int128 NativeU128;  // NOLINT
#endif

/// Unsigned 128-bit value as two limbs. Only the operations lockbox needs.
struct U128 {
    uint64_t hi = 0;
    uint64_t lo = 0;
};

/// Full 64x64 -> 128 unsigned product.
constexpr U128 MulU64(uint64_t a, uint64_t b) noexcept {
#ifdef LOCKBOX_NATIVE_INT128
    const NativeU128 p = static_cast<NativeU128>(a) * b;
    return {static_cast<uint64_t>(p >> 64), static_cast<uint64_t>(p)};
#else
    const uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32;
    const uint64_t b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
    const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    const uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
    U128 r;
    r.lo = (mid << 32) | (p00 & 0xFFFFFFFFu);
    r.hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    return r;
#endif
}

constexpr U128 AddU128(U128 a, U128 b) noexcept {
    U128 r;
    r.lo = a.lo + b.lo;
    r.hi = a.hi + b.hi + (r.lo < a.lo ? 1u : 0u);
    return r;
}

constexpr U128 AddU128(U128 a, uint64_t b) noexcept { return AddU128(a, U128{0, b}); }

constexpr U128 SubU128(U128 a, U128 b) noexcept {
    U128 r;
    r.lo = a.lo - b.lo;
    r.hi = a.hi - b.hi - (a.lo < b.lo ? 1u : 0u);
    return r;
}

constexpr bool LessU128(U128 a, U128 b) noexcept { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }

/// Logical right shift by 0..127.
constexpr U128 ShrU128(U128 a, int s) noexcept {
    if (s == 0) return a;
    if (s >= 64) return {0, a.hi >> (s - 64)};
    return {a.hi >> s, (a.lo >> s) | (a.hi << (64 - s))};
}

/// Left shift by 0..127 (bits shifted out are lost).
constexpr U128 ShlU128(U128 a, int s) noexcept {
    if (s == 0) return a;
    if (s >= 64) return {a.lo << (s - 64), 0};
    return {(a.hi << s) | (a.lo >> (64 - s)), a.lo << s};
}

/// Number of significant bits (0 for zero).
constexpr int BitWidthU128(U128 a) noexcept {
    // One count-leading-zeros instruction: the joint solves normalise by this twice per call.
    return a.hi != 0 ? 64 + static_cast<int>(std::bit_width(a.hi)) : static_cast<int>(std::bit_width(a.lo));
}

#ifdef LOCKBOX_NATIVE_INT128
/// Quotient and remainder of native values.
struct NativeDivMod {
    NativeU128 quot;
    NativeU128 rem;
};

/// (hi 2^64 + lo) / den and its remainder for hi < den, so that the quotient fits in 64 bits: one
/// 128-by-64 division instruction on x86-64, the compiler's 128-bit division elsewhere. Quotient
/// and remainder are unique, so both give the same bits.
[[gnu::always_inline]] inline uint64_t DivWordNative(uint64_t hi, uint64_t lo, uint64_t den, uint64_t* rem) noexcept {
#if defined(__x86_64__)
    uint64_t q = 0, r = 0;
    __asm__("divq %4" : "=a"(q), "=d"(r) : "a"(lo), "d"(hi), "rm"(den) : "cc");
    *rem = r;
    return q;
#else
    const NativeU128 n = (static_cast<NativeU128>(hi) << 64) | lo;
    *rem = static_cast<uint64_t>(n % den);
    return static_cast<uint64_t>(n / den);
#endif
}

/// n / d and n % d for d != 0. On x86-64 through the processor's 128-by-64 division, each step
/// arranged so that its quotient fits in 64 bits: a fraction of the instructions of the
/// compiler's general 128-bit routine, which the solvers' set-ups call in every step. Quotient
/// and remainder are unique, so every path has the same bits.
inline NativeDivMod DivModNative(NativeU128 n, NativeU128 d) noexcept {
#if defined(__x86_64__)
    const auto dHi = static_cast<uint64_t>(d >> 64), dLo = static_cast<uint64_t>(d);
    const auto nHi = static_cast<uint64_t>(n >> 64), nLo = static_cast<uint64_t>(n);
    if (dHi == 0) {
        uint64_t r = 0;
        if (nHi < dLo) {
            const uint64_t q = DivWordNative(nHi, nLo, dLo, &r);
            return {q, r};
        }
        // A quotient of more than 64 bits: its high half first, then the rest.
        uint64_t r1 = 0;
        const uint64_t q1 = DivWordNative(0, nHi, dLo, &r1);
        const uint64_t q0 = DivWordNative(r1, nLo, dLo, &r);
        return {(NativeU128{q1} << 64) | q0, r};
    }
    // d >= 2^64, so the quotient is below 2^64. Divide n / 2 by d's leading 64 bits (normalised,
    // so the step cannot overflow), undo both scalings, and correct the estimate, which is the
    // quotient or one above it, then one below it at most (Hacker's Delight, section 9-5).
    const int s = std::countl_zero(dHi);
    const auto v1 = static_cast<uint64_t>((d << s) >> 64);
    const NativeU128 u1 = n >> 1;
    uint64_t unused = 0;
    const uint64_t q1 = DivWordNative(static_cast<uint64_t>(u1 >> 64), static_cast<uint64_t>(u1), v1, &unused);
    auto q0 = static_cast<uint64_t>((NativeU128{q1} << s) >> 63);
    if (q0 != 0) --q0;
    NativeU128 rem = n - NativeU128{q0} * d;
    if (rem >= d) {
        ++q0;
        rem -= d;
    }
    return {q0, rem};
#else
    return {n / d, n % d};
#endif
}
#endif

/// Quotient and remainder of a 128-bit value by a non-zero 128-bit divisor.
struct DivModU128Result {
    U128 quot;
    U128 rem;
};
constexpr DivModU128Result DivModU128(U128 n, U128 d) noexcept {
#ifdef LOCKBOX_NATIVE_INT128
    using u128 = NativeU128;
    const u128 nn = (static_cast<u128>(n.hi) << 64) | n.lo;
    const u128 dd = (static_cast<u128>(d.hi) << 64) | d.lo;
    NativeDivMod qr{0, 0};
    if (std::is_constant_evaluated()) {
        qr = {nn / dd, nn % dd};
    } else {
        qr = DivModNative(nn, dd);
    }
    return {{static_cast<uint64_t>(qr.quot >> 64), static_cast<uint64_t>(qr.quot)},
            {static_cast<uint64_t>(qr.rem >> 64), static_cast<uint64_t>(qr.rem)}};
#else
    U128 q{}, r{};
    const int width = BitWidthU128(n);
    for (int i = width - 1; i >= 0; --i) {
        r = ShlU128(r, 1);
        r.lo |= (i >= 64 ? (n.hi >> (i - 64)) : (n.lo >> i)) & 1u;
        if (!LessU128(r, d)) {
            r = SubU128(r, d);
            if (i >= 64)
                q.hi |= uint64_t{1} << (i - 64);
            else
                q.lo |= uint64_t{1} << i;
        }
    }
    return {q, r};
#endif
}

/// Signed 128-bit value as sign and magnitude; enough for products of a few int32/int64.
struct S128 {
    bool negative = false;
    U128 mag;
};

constexpr uint64_t AbsU64(int64_t v) noexcept {
    return v < 0 ? uint64_t{0} - static_cast<uint64_t>(v) : static_cast<uint64_t>(v);
}

constexpr S128 MulS64(int64_t a, int64_t b) noexcept {
    S128 r;
    r.mag = MulU64(AbsU64(a), AbsU64(b));
    r.negative = ((a < 0) != (b < 0)) && (r.mag.hi | r.mag.lo) != 0;
    return r;
}

constexpr bool IsZero(const S128& a) noexcept { return (a.mag.hi | a.mag.lo) == 0; }

constexpr S128 Negate(S128 a) noexcept {
    if (!IsZero(a)) a.negative = !a.negative;
    return a;
}

constexpr S128 AddS128(S128 a, S128 b) noexcept {
    if (a.negative == b.negative) return {a.negative, AddU128(a.mag, b.mag)};
    if (LessU128(a.mag, b.mag)) return {b.negative, SubU128(b.mag, a.mag)};
    S128 r{a.negative, SubU128(a.mag, b.mag)};
    if (IsZero(r)) r.negative = false;
    return r;
}

constexpr S128 SubS128(S128 a, S128 b) noexcept { return AddS128(a, Negate(b)); }

/// Multiplies a signed 128-bit magnitude by a small signed 64-bit factor whose product must fit
/// in 128 bits (the caller guarantees it: the 3x3 determinants stay below 2^110).
constexpr S128 MulS128S64(S128 a, int64_t b) noexcept {
    const uint64_t m = AbsU64(b);
    const U128 lo = MulU64(a.mag.lo, m);
    const U128 hi = MulU64(a.mag.hi, m);
    S128 r;
    r.mag = {lo.hi + hi.lo, lo.lo};
    r.negative = (a.negative != (b < 0)) && (r.mag.hi | r.mag.lo) != 0;
    return r;
}

/// round(n / d) with ties away from zero, for d != 0. The caller checks the result range.
/// Returns the magnitude and sign separately so callers can saturate.
constexpr S128 DivRoundS128(S128 n, S128 d) noexcept {
    const DivModU128Result qr = DivModU128(n.mag, d.mag);
    // Round half away from zero on magnitudes: up iff 2*rem >= d.
    U128 q = qr.quot;
    const U128 twice = ShlU128(qr.rem, 1);
    const bool remTopBit = (qr.rem.hi >> 63) != 0;
    if (remTopBit || !LessU128(twice, d.mag)) q = AddU128(q, 1);
    S128 r{n.negative != d.negative, q};
    if (IsZero(r)) r.negative = false;
    return r;
}

/// Arithmetic right shift with round-half-away-from-zero on the magnitude.
constexpr S128 ShrRoundS128(S128 a, int s) noexcept {
    if (s == 0) return a;
    U128 half = ShlU128(U128{0, 1}, s - 1);
    S128 r{a.negative, ShrU128(AddU128(a.mag, half), s)};
    if (IsZero(r)) r.negative = false;
    return r;
}

/// True when the value fits in int64.
constexpr bool FitsS64(const S128& a) noexcept {
    if (a.mag.hi != 0) return false;
    return a.negative ? a.mag.lo <= (uint64_t{1} << 63) : a.mag.lo < (uint64_t{1} << 63);
}

/// Narrows to int64; the caller must have checked FitsS64.
constexpr int64_t ToS64(const S128& a) noexcept {
    if (a.negative) {
        return a.mag.lo == (uint64_t{1} << 63) ? INT64_MIN : -static_cast<int64_t>(a.mag.lo);
    }
    return static_cast<int64_t>(a.mag.lo);
}

}  // namespace lockbox::detail
