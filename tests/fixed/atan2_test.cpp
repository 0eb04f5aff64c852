// Atan2Raw / Atan2: defined and correctly rounded on the axes and diagonals, no overflow for
// extreme int32 inputs, <= 1 ULP on bounded random and circle sweeps, exact odd symmetry.
// The large sweeps (circles r = 1e-3 .. 2e4 m with 2^20 angles, 1e7 random pairs) are in
// heavy/atan2_exhaustive_test.cpp.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/fixed/Functions.h"
#include "lockbox/fixed/detail/Trig.h"

using lockbox::Fixed;
using lockbox::detail::Atan2Raw;

namespace LOCKBOX_TEST_FILE {

constexpr int32_t kMin = std::numeric_limits<int32_t>::min();
constexpr int32_t kMax = std::numeric_limits<int32_t>::max();

long double ErrUlp(int32_t y, int32_t x) {
    const long double ref =
        (y == 0 && x == 0) ? 0.0L : std::atan2(static_cast<long double>(y), static_cast<long double>(x)) * 65536.0L;
    return std::fabs(static_cast<long double>(Atan2Raw(y, x)) - ref);
}

// Log-uniform magnitude in [1, 2^31] with a random sign (clamped to the int32 range).
int32_t LogUniformRaw(std::mt19937_64& rng) {
    const int bits = static_cast<int>(rng() % 32);  // 0..31
    int64_t v = static_cast<int64_t>((rng() >> (64 - bits - 1)) | (uint64_t{1} << bits));
    if (v > kMax) v = kMax;
    return (rng() & 1) ? static_cast<int32_t>(-v) : static_cast<int32_t>(v);
}

TEST(Atan2, AxesAndOrigin) {
    EXPECT_EQ(Atan2Raw(0, 0), 0);
    for (int32_t m : {1, 7, 65536, 123456789, kMax}) {
        EXPECT_EQ(Atan2Raw(0, m), 0);
        EXPECT_EQ(Atan2Raw(0, -m), 205887);  // +pi, as C's atan2(+0, x < 0)
        EXPECT_EQ(Atan2Raw(m, 0), 102944);   // +pi/2
        EXPECT_EQ(Atan2Raw(-m, 0), -102944);
    }
    EXPECT_EQ(Atan2Raw(0, kMin), 205887);
    EXPECT_EQ(Atan2Raw(kMin, 0), -102944);
}

TEST(Atan2, DiagonalsAreCorrectlyRounded) {
    for (int32_t m : {1, 3, 65536, 1 << 30, kMax}) {
        EXPECT_EQ(Atan2Raw(m, m), 51472);  // pi/4 = 51471.85
        EXPECT_EQ(Atan2Raw(-m, m), -51472);
        EXPECT_EQ(Atan2Raw(m, -m), 154416);  // 3pi/4 = 154415.56
        EXPECT_EQ(Atan2Raw(-m, -m), -154416);
    }
    EXPECT_EQ(Atan2Raw(kMin, kMin), -154416);
}

TEST(Atan2, ExtremeInputsNoOverflow) {
    const int32_t extremes[] = {kMin, kMin + 1, -65536, -2, -1, 0, 1, 2, 65536, kMax - 1, kMax};
    for (int32_t y : extremes) {
        for (int32_t x : extremes) {
            const int32_t r = Atan2Raw(y, x);
            EXPECT_GE(r, -205887);
            EXPECT_LE(r, 205887);
            EXPECT_LE(ErrUlp(y, x), 1.0L) << "y=" << y << " x=" << x;
        }
    }
    // Extreme ratios: 1 / (2^31 - 1) and its inverse.
    EXPECT_EQ(Atan2Raw(1, kMax), 0);  // 4.66e-10 rad
    EXPECT_EQ(Atan2Raw(kMax, 1), 102944);
    EXPECT_EQ(Atan2Raw(-1, kMin), -205887);  // -pi + 4.66e-10 rounds to -205887
    EXPECT_EQ(Atan2Raw(1, kMin), 205887);
}

TEST(Atan2, RandomLogUniformPairs) {
    std::mt19937_64 rng(99);
    long double max_err = 0;
    long long not_cr = 0;
    for (int i = 0; i < 300000; ++i) {
        const int32_t y = LogUniformRaw(rng);
        const int32_t x = LogUniformRaw(rng);
        const long double e = ErrUlp(y, x);
        if (e > max_err) max_err = e;
        if (e > 0.5L) ++not_cr;
    }
    EXPECT_LE(max_err, 1.0L);
    EXPECT_LE(not_cr, 10);  // measured: ~1 in 200k pairs is a near-tie off by 1e-5 ULP
}

TEST(Atan2, CirclesAtSeveralRadii) {
    const long double pi = 3.14159265358979323846264338327950288L;
    long double max_err = 0;
    for (long double radius : {1e-3L, 1.0L, 300.0L, 2e4L}) {
        for (int i = 0; i < 8192; ++i) {
            const long double th = (i + 0.5L) / 8192 * 2 * pi - pi;
            const int32_t y = static_cast<int32_t>(std::llround(radius * std::sin(th) * 65536.0L));
            const int32_t x = static_cast<int32_t>(std::llround(radius * std::cos(th) * 65536.0L));
            const long double e = ErrUlp(y, x);
            if (e > max_err) max_err = e;
        }
    }
    EXPECT_LE(max_err, 1.0L);
}

TEST(Atan2, OddSymmetryAndRange) {
    std::mt19937 rng(17);
    for (int i = 0; i < 200000; ++i) {
        int32_t y = static_cast<int32_t>(rng());
        const int32_t x = static_cast<int32_t>(rng());
        if (y == kMin || y == 0) y = 1;
        const int32_t r = Atan2Raw(y, x);
        ASSERT_EQ(Atan2Raw(-y, x), -r);
        ASSERT_GE(r, -205887);
        ASSERT_LE(r, 205887);
        // Same ratio at another scale gives the same angle (only the ratio matters).
        if (y > -(1 << 29) && y < (1 << 29) && x > -(1 << 29) && x < (1 << 29)) {
            ASSERT_EQ(Atan2Raw(4 * y, 4 * x), r);
        }
    }
}

TEST(Atan2, PublicWrapper) {
    EXPECT_EQ(lockbox::math::Atan2(Fixed(1), Fixed(1)).Raw(), 51472);
    EXPECT_EQ(lockbox::math::Atan2(Fixed(0), Fixed(-1)), lockbox::math::kPi);
    EXPECT_EQ(lockbox::math::Atan2(Fixed(0), Fixed(0)), Fixed(0));
    EXPECT_EQ(lockbox::math::Atan2(Fixed(-5), Fixed(0)), -lockbox::math::kHalfPi);
}

}  // namespace LOCKBOX_TEST_FILE
