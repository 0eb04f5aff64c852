// Integer square roots: IsqrtFloor64 / IsqrtRound64 over the whole uint64 range (random and
// adversarial inputs, integer-exact checks) and the Q16.16 SqrtRaw / Sqrt (dense sweeps; the
// exhaustive 2^31 sweep is in heavy/sqrt_exhaustive_test.cpp).
#include "lockbox/fixed/detail/Sqrt.h"

#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/fixed/Functions.h"

using lockbox::Fixed;
using lockbox::detail::IsqrtFloor64;
using lockbox::detail::IsqrtRound64;
using lockbox::detail::SqrtRaw;

namespace LOCKBOX_TEST_FILE {

// Integer-exact: r = floor(sqrt(n)) iff r^2 <= n and n - r^2 <= 2r ((r+1)^2 > n).
bool FloorIsExact(uint64_t n, uint64_t r) {
    if (r > 0xFFFFFFFFu) return false;
    const uint64_t sq = r * r;
    return sq <= n && n - sq <= 2 * r;
}

// Integer-exact: q = round(sqrt(n)) iff |q - sqrt(n)| < 1/2, i.e. with r = floor(sqrt(n)):
// q = r + 1 iff n - r^2 > r (n >= r^2 + r + 1 > (r + 1/2)^2). For n < 2^61 this is also
// checked directly as (2q - 1)^2 <= 4n < (2q + 1)^2.
bool RoundIsExact(uint64_t n, uint64_t q) {
    const uint64_t r = IsqrtFloor64(n);
    if (!FloorIsExact(n, r)) return false;
    const uint64_t want = r + ((n - r * r > r) ? 1 : 0);
    if (q != want) return false;
    if (n < (uint64_t{1} << 61)) {
        const uint64_t lo = q == 0 ? 0 : (2 * q - 1) * (2 * q - 1);
        const uint64_t hi = (2 * q + 1) * (2 * q + 1);
        return lo <= 4 * n && 4 * n < hi;
    }
    return true;
}

void CheckOne(uint64_t n) {
    const uint64_t r = IsqrtFloor64(n);
    const uint64_t q = IsqrtRound64(n);
    ASSERT_TRUE(FloorIsExact(n, r)) << "n=" << n << " floor=" << r;
    ASSERT_TRUE(RoundIsExact(n, q)) << "n=" << n << " round=" << q;
}

// Q16.16: r = round(sqrt(v)), v = x * 2^16 < 2^47, iff (2r - 1)^2 <= 4v < (2r + 1)^2.
bool SqrtRawIsExact(int32_t x, int32_t r) {
    if (x <= 0) return r == 0;
    const uint64_t v4 = static_cast<uint64_t>(x) << 18;
    const uint64_t rr = static_cast<uint64_t>(r);
    const uint64_t lo = rr == 0 ? 0 : (2 * rr - 1) * (2 * rr - 1);
    return r >= 0 && lo <= v4 && v4 < (2 * rr + 1) * (2 * rr + 1);
}

static_assert(IsqrtFloor64(0) == 0 && IsqrtFloor64(1) == 1 && IsqrtFloor64(3) == 1);
static_assert(IsqrtFloor64(4) == 2 && IsqrtFloor64(99) == 9 && IsqrtFloor64(100) == 10);
static_assert(IsqrtFloor64(~uint64_t{0}) == 0xFFFFFFFFu);
static_assert(IsqrtRound64(2) == 1 && IsqrtRound64(3) == 2 && IsqrtRound64(6) == 2 && IsqrtRound64(7) == 3);
static_assert(IsqrtRound64(~uint64_t{0}) == (uint64_t{1} << 32));
static_assert(SqrtRaw(0) == 0 && SqrtRaw(65536) == 65536 && SqrtRaw(4 * 65536) == 2 * 65536);
static_assert(SqrtRaw(-1) == 0 && SqrtRaw(std::numeric_limits<int32_t>::min()) == 0);

TEST(Isqrt64, SmallValuesExhaustive) {
    for (uint64_t n = 0; n < (uint64_t{1} << 20); ++n) CheckOne(n);
}

TEST(Isqrt64, AroundEverySquareBoundary) {
    // k^2 - 1, k^2, k^2 + k, k^2 + k + 1 (the floor and rounding boundaries) for random k of
    // every bit length, up to k = 2^32 - 1 (where k^2 + k + 1 wraps: skip those).
    std::mt19937_64 rng(20240601);
    for (int i = 0; i < 60000; ++i) {
        const int bits = 1 + static_cast<int>(rng() % 32);
        const uint64_t k = (rng() >> (64 - bits)) | (uint64_t{1} << (bits - 1));
        const uint64_t sq = k * k;
        CheckOne(sq);
        CheckOne(sq - 1);
        CheckOne(sq + 1);
        if (k < 0xFFFFFFFFu) {
            CheckOne(sq + k);
            CheckOne(sq + k + 1);
            CheckOne(sq + 2 * k);
        }
    }
    const uint64_t kMax = 0xFFFFFFFFu;
    CheckOne(kMax * kMax);
    CheckOne(kMax * kMax - 1);
    CheckOne(kMax * kMax + kMax);      // last value that rounds down to 2^32 - 1
    CheckOne(kMax * kMax + kMax + 1);  // first value that rounds to 2^32
    EXPECT_EQ(IsqrtRound64(kMax * kMax + kMax), kMax);
    EXPECT_EQ(IsqrtRound64(kMax * kMax + kMax + 1), uint64_t{1} << 32);
}

TEST(Isqrt64, RandomOverWholeRange) {
    std::mt19937_64 rng(7);
    for (int i = 0; i < 400000; ++i) {
        const uint64_t n = rng() >> (rng() % 64);
        CheckOne(n);
    }
}

TEST(Isqrt64, TopOfRangeAndPowersOfTwo) {
    for (uint64_t j = 0; j < 20000; ++j) CheckOne(~uint64_t{0} - j);
    for (int b = 0; b < 64; ++b) {
        const uint64_t p = uint64_t{1} << b;
        CheckOne(p);
        CheckOne(p - 1);
        CheckOne(p + 1);
    }
    // Int64 sums of two squared Q16.16 raws (what Vec2::Length feeds in) stay below 2^63, so
    // the rounded root fits uint32.
    const uint64_t max_sum = 2 * uint64_t{0x80000000u} * 0x80000000u - 1;  // 2^63 - 1
    EXPECT_LE(IsqrtRound64(max_sum), 0xFFFFFFFFu);
    EXPECT_EQ(IsqrtRound64(max_sum), 3037000500u);
}

TEST(SqrtRaw, DenseLowRangeAndStridedFullRange) {
    for (int32_t x = 0; x < (1 << 20); ++x) {
        const int32_t r = SqrtRaw(x);
        ASSERT_TRUE(SqrtRawIsExact(x, r)) << "x=" << x << " r=" << r;
    }
    for (int64_t x = 1 << 20; x <= std::numeric_limits<int32_t>::max(); x += 1021) {
        const int32_t r = SqrtRaw(static_cast<int32_t>(x));
        ASSERT_TRUE(SqrtRawIsExact(static_cast<int32_t>(x), r)) << "x=" << x << " r=" << r;
    }
    const int32_t top = std::numeric_limits<int32_t>::max();
    EXPECT_TRUE(SqrtRawIsExact(top, SqrtRaw(top)));
    EXPECT_EQ(SqrtRaw(top), 11863283);  // sqrt(32767.99998) = 181.019336
}

TEST(SqrtRaw, PerfectSquaresAreExact) {
    for (int32_t k = 0; k <= 181; ++k) {
        EXPECT_EQ(SqrtRaw(k * k * 65536), k * 65536) << k;
    }
    EXPECT_EQ(SqrtRaw(16384), 32768);  // sqrt(0.25) = 0.5
    EXPECT_EQ(SqrtRaw(1), 256);        // sqrt(2^-16) = 2^-8
}

TEST(SqrtRaw, NegativeIsDomainErrorReturningZero) {
    EXPECT_EQ(SqrtRaw(-1), 0);
    EXPECT_EQ(SqrtRaw(-65536), 0);
    EXPECT_EQ(SqrtRaw(std::numeric_limits<int32_t>::min()), 0);
}

TEST(FixedSqrt, WrapsTheKernel) {
    EXPECT_EQ(lockbox::math::Sqrt(Fixed(4)), Fixed(2));
    EXPECT_EQ(lockbox::math::Sqrt(Fixed(0)), Fixed(0));
    EXPECT_EQ(lockbox::math::Sqrt(Fixed::FromRaw(2 * 65536)).Raw(), 92682);  // sqrt(2) = 1.41421356
    for (int32_t x = 0; x < 100000; x += 7) {
        EXPECT_EQ(lockbox::math::Sqrt(Fixed::FromRaw(x)).Raw(), SqrtRaw(x));
    }
}

}  // namespace LOCKBOX_TEST_FILE
