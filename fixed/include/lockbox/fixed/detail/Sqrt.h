// Integer square roots for the Q16.16 / Q32.32 layer.
//
// All kernels are integer-only (uint64 at most, no __int128, no floating point), constexpr and
// free of undefined behaviour, so they give the same bits on every compiler, optimisation level
// and architecture.
//
// Algorithm (division-free):
//   1. Normalise n by an even left shift 2h so that m = n << 2h lies in [2^62, 2^64).
//   2. Seed y0 ~ 1/sqrt(a), a = m / 2^64 in [1/4, 1), from a 384-entry table indexed by the top
//      9 bits of m (relative error <= 2^-9).
//   3. One Newton step for the reciprocal square root: y1 = y0 (3 - a y0^2) / 2 (error ~2^-17).
//   4. s1 = a y1 approximates sqrt(m); one coupled correction s2 = s1 + y1 (m - s1^2) / 2 brings
//      it within +-1 of floor(sqrt(m)) (the residual m - s1^2 is computed exactly).
//   5. r = s2 >> h is within +-1 of floor(sqrt(n)); one exact step on the remainder n - r^2
//      makes it exact, and rounding is decided exactly from the same remainder.
// Correctness is verified exhaustively for every Q16.16 input (tests/fixed/heavy) and on random
// and adversarial (k^2 - 1, k^2 + k, ...) 64-bit inputs over the whole uint64 range.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

namespace lockbox::detail {

namespace sqrt_impl {

// Bit-by-bit floor square root. Slow; used only at compile time to build the seed table.
constexpr uint64_t SlowIsqrt(uint64_t n) noexcept {
    uint64_t root = 0;
    uint64_t bit = uint64_t{1} << 62;
    while (bit > n) bit >>= 2;
    while (bit != 0) {
        if (n >= root + bit) {
            n -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return root;
}

inline constexpr int kSeedBits = 9;
inline constexpr uint32_t kSeedFirst = 1u << (kSeedBits - 2);           // 128: top 9 bits of m are >= 128
inline constexpr uint32_t kSeedCount = (1u << kSeedBits) - kSeedFirst;  // 384 entries

// Entry i - 128 holds round(2^15 / sqrt(a_mid)) with a_mid = (i + 1/2) / 512 the centre of the
// bucket, i.e. 2^20 / sqrt(2i + 1) (Q15; max 65408 for i = 128, so it fits uint16).
constexpr std::array<uint16_t, kSeedCount> MakeRsqrtSeed() noexcept {
    std::array<uint16_t, kSeedCount> table{};
    for (uint32_t i = kSeedFirst; i < (1u << kSeedBits); ++i) {
        // round(sqrt(q)) for q = 2^40 / (2i + 1): floor root, then round up when q - r^2 > r.
        const uint64_t q = (uint64_t{1} << 40) / (2 * uint64_t{i} + 1);
        uint64_t r = SlowIsqrt(q);
        if (q - r * r > r) ++r;
        table[i - kSeedFirst] = static_cast<uint16_t>(r);
    }
    return table;
}

inline constexpr std::array<uint16_t, kSeedCount> kRsqrtSeed = MakeRsqrtSeed();

/// Floor square root with its remainder: root = floor(sqrt(n)), rem = n - root^2 (0 <= rem <= 2
/// root).
struct IsqrtRem {
    uint32_t root;
    uint64_t rem;
};

/// Exact floor square root and remainder for every uint64 n (see the algorithm at the top).
constexpr IsqrtRem IsqrtFloorRem64(uint64_t n) noexcept {
    if (n == 0) return {0, 0};
    const int half_shift = std::countl_zero(n) >> 1;  // h; n << 2h has its top bit at 62 or 63
    const uint64_t m = n << (2 * half_shift);
    const uint32_t a = static_cast<uint32_t>(m >> 32);                     // a / 2^32 in [1/4, 1)
    const uint64_t y0 = kRsqrtSeed[(a >> (32 - kSeedBits)) - kSeedFirst];  // Q15 ~ 1/sqrt(a)

    // Newton step for 1/sqrt(a): y1 = y0 (3 - a y0^2) / 2. y0^2 < 2^32 (Q30), a*y0^2 < 2^64.
    const uint64_t ay2 = (uint64_t{a} * (y0 * y0)) >> 32;          // Q30, close to 2^30
    const uint64_t y1 = (y0 * ((uint64_t{3} << 30) - ay2)) >> 16;  // Q30, <= ~2^31

    // s1 ~ sqrt(m) = 2^32 sqrt(a); a*y1 < 2^63. s1 may exceed 2^32 by a unit or two, so the
    // residual m - s1^2 is formed modulo 2^64: its true value is below 2^48 in magnitude, so the
    // int64 reinterpretation is exact.
    const uint64_t s1 = (uint64_t{a} * y1) >> 30;
    const int64_t d = static_cast<int64_t>(m - s1 * s1);
    // s2 = s1 + d / (2 sqrt(m)) = s1 + d * y1 / 2^63. |d >> 16| < 2^32 and y1 <= 2^31.
    const int64_t corr = ((d >> 16) * static_cast<int64_t>(y1)) >> 47;
    const uint64_t s2 = s1 + static_cast<uint64_t>(corr);  // modular add of a small signed value

    // Back to n's scale: r is within +-1 of floor(sqrt(n)). Fix it exactly from the remainder,
    // again formed modulo 2^64 (its true magnitude is below 2^35).
    uint64_t r = s2 >> half_shift;
    int64_t rem = static_cast<int64_t>(n - r * r);
    if (rem < 0) {
        --r;
        rem += static_cast<int64_t>(2 * r + 1);
    } else if (rem > static_cast<int64_t>(2 * r)) {
        rem -= static_cast<int64_t>(2 * r + 1);
        ++r;
    }
    return {static_cast<uint32_t>(r), static_cast<uint64_t>(rem)};
}

}  // namespace sqrt_impl

/// floor(sqrt(n)) for every n in [0, 2^64 - 1]; the result is in [0, 2^32 - 1]. Exact.
constexpr uint32_t IsqrtFloor64(uint64_t n) noexcept { return sqrt_impl::IsqrtFloorRem64(n).root; }

/// round(sqrt(n)) (to nearest; ties cannot occur for integer n) for every n in [0, 2^64 - 1].
/// The result is in [0, 2^32]: it equals 2^32 for n >= 2^64 - 2^32 + 1, hence the uint64_t
/// return type. For n < 2^63 (e.g. an exact int64 sum of squared Q16.16 raws, as used by
/// Vec2::Length) the result is <= 3037000500, which fits uint32_t but NOT int32_t. Exact.
constexpr uint64_t IsqrtRound64(uint64_t n) noexcept {
    const sqrt_impl::IsqrtRem fr = sqrt_impl::IsqrtFloorRem64(n);
    // sqrt(n) >= r + 1/2  <=>  n >= r^2 + r + 1/4  <=>  rem > r (integers).
    return uint64_t{fr.root} + (fr.rem > fr.root ? 1u : 0u);
}

/// Q16.16 square root, correctly rounded: returns round(sqrt(x * 2^16)) for raw x >= 0, i.e. the
/// Q16.16 value nearest to sqrt(x / 2^16) (error <= 0.5 ULP = 2^-17, verified exhaustively).
/// Result range [0, 11863283] (sqrt(32768) ~ 181.02). For x < 0 it returns 0 (domain error; the
/// public Fixed wrapper reports it).
constexpr int32_t SqrtRaw(int32_t x) noexcept {
    if (x <= 0) return 0;
    return static_cast<int32_t>(IsqrtRound64(static_cast<uint64_t>(x) << 16));
}

}  // namespace lockbox::detail
