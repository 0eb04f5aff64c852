// SinCosRaw / SinCos: exact special values, exact symmetry, <= 1 ULP (and nearly always
// correctly rounded) on bounded dense and strided sweeps, Pythagorean identity within 2 ULP.
// The exhaustive |x| <= 4 pi sweep and the full-range stride-61 sweep are in
// heavy/trig_exhaustive_test.cpp.
#include "lockbox/fixed/detail/Trig.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/fixed/Functions.h"

using lockbox::Fixed;
using lockbox::detail::SinCosRaw;

namespace LOCKBOX_TEST_FILE {

constexpr long double kRawPerUnit = 65536.0L;

struct ErrStats {
    long double max_ulp = 0;
    long long count = 0;
    long long not_cr = 0;
    void Add(long double err) {
        err = std::fabs(err);
        if (err > max_ulp) max_ulp = err;
        ++count;
        if (err > 0.5L) ++not_cr;
    }
};

// Errors in ULP of sin and cos at raw angle x against long double sinl/cosl. The argument is
// exact in long double; glibc's sinl/cosl reduce it exactly.
void Measure(int32_t x, ErrStats& s_stats, ErrStats& c_stats) {
    int32_t s = 0;
    int32_t c = 0;
    SinCosRaw(x, &s, &c);
    const long double a = static_cast<long double>(x) / kRawPerUnit;
    s_stats.Add(static_cast<long double>(s) - std::sin(a) * kRawPerUnit);
    c_stats.Add(static_cast<long double>(c) - std::cos(a) * kRawPerUnit);
}

TEST(SinCos, ExactSpecialValues) {
    struct Case {
        int32_t x, s, c;
    };
    // Correctly rounded values (300-bit reference): 0, the rounded pi/4, pi/2, pi, 3pi/2, 2pi,
    // 1 ULP, 1 rad, and the two ends of the int32 range.
    const Case cases[] = {
        {0, 0, 65536},
        {51472, 46341, 46341},
        {102944, 65536, 0},
        {205887, 0, -65536},
        {308831, -65536, 0},
        {411775, 0, 65536},
        {1, 1, 65536},
        {-1, -1, 65536},
        {65536, 55147, 35409},
        {std::numeric_limits<int32_t>::max(), 60808, 24442},
        {std::numeric_limits<int32_t>::min(), -60808, 24441},
    };
    for (const Case& k : cases) {
        int32_t s = 12345;
        int32_t c = 12345;
        SinCosRaw(k.x, &s, &c);
        EXPECT_EQ(s, k.s) << "x=" << k.x;
        EXPECT_EQ(c, k.c) << "x=" << k.x;
    }
}

TEST(SinCos, ExactOddEvenSymmetry) {
    std::mt19937 rng(3);
    for (int i = 0; i < 200000; ++i) {
        int32_t x = static_cast<int32_t>(rng());
        if (x == std::numeric_limits<int32_t>::min()) x = 0;
        int32_t s1 = 0, c1 = 0, s2 = 0, c2 = 0;
        SinCosRaw(x, &s1, &c1);
        SinCosRaw(-x, &s2, &c2);
        ASSERT_EQ(s1, -s2) << "x=" << x;
        ASSERT_EQ(c1, c2) << "x=" << x;
    }
}

TEST(SinCos, DenseSweepWithinTwoPi) {
    // Every 3rd raw value in [-2pi, 2pi] (~275k angles).
    ErrStats s_stats, c_stats;
    for (int32_t x = -411775; x <= 411775; x += 3) Measure(x, s_stats, c_stats);
    EXPECT_LE(s_stats.max_ulp, 0.5001L);
    EXPECT_LE(c_stats.max_ulp, 0.5001L);
    EXPECT_EQ(s_stats.not_cr, 0);
    EXPECT_EQ(c_stats.not_cr, 0);
}

TEST(SinCos, StridedFullInt32Range) {
    // ~1M angles over the whole int32 range (|x| up to 32768 rad), stride 4093 (prime).
    ErrStats s_stats, c_stats;
    for (int64_t x = std::numeric_limits<int32_t>::min(); x <= std::numeric_limits<int32_t>::max(); x += 4093) {
        Measure(static_cast<int32_t>(x), s_stats, c_stats);
    }
    Measure(std::numeric_limits<int32_t>::max(), s_stats, c_stats);
    EXPECT_LE(s_stats.max_ulp, 1.0L);
    EXPECT_LE(c_stats.max_ulp, 1.0L);
    // Correctly rounded except for rare near-ties (measured ~1 in 4 million).
    EXPECT_LE(s_stats.not_cr, 5);
    EXPECT_LE(c_stats.not_cr, 5);
}

TEST(SinCos, PythagoreanIdentityWithinTwoUlp) {
    std::mt19937 rng(5);
    for (int i = 0; i < 300000; ++i) {
        const int32_t x = static_cast<int32_t>(rng());
        int32_t s = 0, c = 0;
        SinCosRaw(x, &s, &c);
        ASSERT_LE(s, 65536);
        ASSERT_GE(s, -65536);
        ASSERT_LE(c, 65536);
        ASSERT_GE(c, -65536);
        // s^2 + c^2 - 1 in Q32; 2 ULP of Q16.16 is 2 * 2^16 there.
        const int64_t dev = int64_t{s} * s + int64_t{c} * c - (int64_t{1} << 32);
        ASSERT_LE(dev < 0 ? -dev : dev, int64_t{2} << 16) << "x=" << x;
    }
}

TEST(SinCos, PublicWrappersAgreeWithKernel) {
    for (int32_t x = -2000000; x <= 2000000; x += 997) {
        int32_t s = 0, c = 0;
        SinCosRaw(x, &s, &c);
        Fixed fs, fc;
        lockbox::math::SinCos(Fixed::FromRaw(x), fs, fc);
        const lockbox::math::SinCosResult r = lockbox::math::SinCos(Fixed::FromRaw(x));
        ASSERT_EQ(fs.Raw(), s);
        ASSERT_EQ(fc.Raw(), c);
        ASSERT_EQ(r.sin.Raw(), s);
        ASSERT_EQ(r.cos.Raw(), c);
        ASSERT_EQ(lockbox::math::Sin(Fixed::FromRaw(x)).Raw(), s);
        ASSERT_EQ(lockbox::math::Cos(Fixed::FromRaw(x)).Raw(), c);
    }
    EXPECT_EQ(lockbox::math::Sin(Fixed(0)), Fixed(0));
    EXPECT_EQ(lockbox::math::Cos(Fixed(0)), Fixed(1));
}

TEST(AngleConstants, AreCorrectlyRounded) {
    EXPECT_EQ(lockbox::math::kPi.Raw(), 205887);
    EXPECT_EQ(lockbox::math::kTwoPi.Raw(), 411775);
    EXPECT_EQ(lockbox::math::kHalfPi.Raw(), 102944);
    EXPECT_EQ(lockbox::detail::kQuarterPiRaw, 51472);
    EXPECT_EQ(lockbox::detail::kTwoPiQ48, 2 * lockbox::detail::kPiQ48);
    // Against long double pi (64-bit mantissa is ample for 17 + 32 bits).
    const long double pi = 3.14159265358979323846264338327950288L;
    EXPECT_LT(std::fabs(lockbox::math::kPi.Raw() - pi * 65536.0L), 0.5L);
    EXPECT_LT(std::fabs(lockbox::math::kTwoPi.Raw() - 2 * pi * 65536.0L), 0.5L);
    EXPECT_LT(std::fabs(lockbox::math::kHalfPi.Raw() - pi / 2 * 65536.0L), 0.5L);
}

}  // namespace LOCKBOX_TEST_FILE
