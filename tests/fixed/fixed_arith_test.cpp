// Q16.16 arithmetic: the rounding rule, exact add/sub, correctly rounded mul/div, saturation.
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/fixed/Fixed.h"

using lockbox::Fixed;

namespace LOCKBOX_TEST_FILE {

// Exact reference: round(n / d) with ties away from zero, on int64 with |n| < 2^62.
int64_t RoundDivRef(int64_t n, int64_t d) {
    const bool neg = (n < 0) != (d < 0);
    const uint64_t un = n < 0 ? static_cast<uint64_t>(-n) : static_cast<uint64_t>(n);
    const uint64_t ud = d < 0 ? static_cast<uint64_t>(-d) : static_cast<uint64_t>(d);
    uint64_t q = un / ud;
    if (2 * (un % ud) >= ud) ++q;
    return neg ? -static_cast<int64_t>(q) : static_cast<int64_t>(q);
}

int32_t RandomRaw(std::mt19937_64& rng) {
    // Log-uniform magnitudes so that small and large values are both well covered.
    const int bits = static_cast<int>(rng() % 31);
    const int64_t mag = static_cast<int64_t>(rng() & ((uint64_t{1} << bits) - 1)) | (int64_t{1} << bits) >> 1;
    return static_cast<int32_t>((rng() & 1) ? -mag : mag);
}

TEST(FixedArith, AddSubAreExactInRange) {
    std::mt19937_64 rng(1);
    for (int i = 0; i < 200000; ++i) {
        const int32_t a = static_cast<int32_t>(rng()) / 2, b = static_cast<int32_t>(rng()) / 2;
        EXPECT_EQ((Fixed::FromRaw(a) + Fixed::FromRaw(b)).Raw(), a + b);
        EXPECT_EQ((Fixed::FromRaw(a) - Fixed::FromRaw(b)).Raw(), a - b);
    }
}

TEST(FixedArith, MulIsCorrectlyRoundedTiesAwayFromZero) {
    std::mt19937_64 rng(2);
    int checked = 0;
    for (int i = 0; i < 1000000; ++i) {
        const int32_t a = RandomRaw(rng), b = RandomRaw(rng);
        const int64_t ref = RoundDivRef(int64_t{a} * b, 65536);
        if (ref > INT32_MAX || ref < -INT32_MAX) continue;
        ++checked;
        ASSERT_EQ((Fixed::FromRaw(a) * Fixed::FromRaw(b)).Raw(), ref) << a << " * " << b;
    }
    EXPECT_GT(checked, 900000);
}

TEST(FixedArith, MulTiesRoundAwayAndAreSymmetric) {
    // 0.5 ULP products: 1 raw * 0.5 -> exact tie.
    const Fixed half = Fixed::FromRaw(32768);
    EXPECT_EQ((Fixed::FromRaw(1) * half).Raw(), 1);
    EXPECT_EQ((Fixed::FromRaw(-1) * half).Raw(), -1);
    EXPECT_EQ((Fixed::FromRaw(3) * half).Raw(), 2);    // 1.5 -> 2
    EXPECT_EQ((Fixed::FromRaw(-3) * half).Raw(), -2);  // -1.5 -> -2
    // Just below a tie rounds toward zero on both sides.
    const Fixed belowHalf = Fixed::FromRaw(32767);
    EXPECT_EQ((Fixed::FromRaw(1) * belowHalf).Raw(), 0);
    EXPECT_EQ((Fixed::FromRaw(-1) * belowHalf).Raw(), 0);
    std::mt19937_64 rng(3);
    for (int i = 0; i < 100000; ++i) {
        // Magnitudes below 2^22 raw (64 m) keep the product in range: no saturation to hide a sign.
        const Fixed a = Fixed::FromRaw(RandomRaw(rng) / 512), b = Fixed::FromRaw(RandomRaw(rng) / 512);
        ASSERT_EQ(((-a) * b).Raw(), -(a * b).Raw());
    }
}

TEST(FixedArith, DivIsCorrectlyRounded) {
    std::mt19937_64 rng(4);
    int checked = 0;
    for (int i = 0; i < 1000000; ++i) {
        const int32_t a = RandomRaw(rng), b = RandomRaw(rng);
        if (b == 0) continue;
        const int64_t ref = RoundDivRef(int64_t{a} * 65536, b);
        if (ref > INT32_MAX || ref < -INT32_MAX) continue;
        ++checked;
        ASSERT_EQ((Fixed::FromRaw(a) / Fixed::FromRaw(b)).Raw(), ref) << a << " / " << b;
    }
    EXPECT_GT(checked, 500000);
}

TEST(FixedArith, NoDownwardCreepForSlowMotion) {
    // NUMERICS Table 4: floor rounding moves v = -2e-4 m/s but not +2e-4 m/s. Ours is symmetric.
    const Fixed dt = Fixed::FromRaw(1092);
    for (int32_t v = -40; v <= 40; ++v) {
        EXPECT_EQ((dt * Fixed::FromRaw(-v)).Raw(), -(dt * Fixed::FromRaw(v)).Raw());
    }
}

TEST(FixedArith, SaturatesAndCounts) {
    if (lockbox::kOverflowTraps) GTEST_SKIP() << "checked build traps instead (see fixed_trap_test)";
    lockbox::ResetSaturationCount();
    const Fixed big = Fixed::FromRaw(INT32_MAX);
    EXPECT_EQ((big + Fixed(1)).Raw(), INT32_MAX);
    EXPECT_EQ((-big - Fixed(1)).Raw(), -INT32_MAX);
    EXPECT_EQ((big * Fixed(2)).Raw(), INT32_MAX);
    EXPECT_EQ((big * Fixed(-2)).Raw(), -INT32_MAX);
    EXPECT_EQ((Fixed(1) / Fixed()).Raw(), INT32_MAX);
    EXPECT_EQ((Fixed(-1) / Fixed()).Raw(), -INT32_MAX);
    EXPECT_EQ((Fixed() / Fixed()).Raw(), 0);
    EXPECT_EQ((-Fixed::FromRaw(INT32_MIN)).Raw(), INT32_MAX);
    EXPECT_EQ(Fixed(40000).Raw(), INT32_MAX);
    EXPECT_EQ(lockbox::SaturationCount(), 9u);
    lockbox::ResetSaturationCount();
    EXPECT_EQ(lockbox::SaturationCount(), 0u);
}

TEST(FixedArith, HelpersAndLimits) {
    EXPECT_EQ(lockbox::math::Floor(Fixed(1.75)), Fixed(1));
    EXPECT_EQ(lockbox::math::Floor(Fixed(-1.25)), Fixed(-2));
    EXPECT_EQ(lockbox::math::Ceil(Fixed(1.25)), Fixed(2));
    EXPECT_EQ(lockbox::math::Ceil(Fixed(-1.75)), Fixed(-1));
    EXPECT_EQ(lockbox::math::Round(Fixed(2.5)), Fixed(3));
    EXPECT_EQ(lockbox::math::Round(Fixed(-2.5)), Fixed(-3));
    EXPECT_EQ(lockbox::math::Round(Fixed(-2.25)), Fixed(-2));
    EXPECT_EQ(lockbox::math::Abs(Fixed(-3)), Fixed(3));
    EXPECT_EQ(lockbox::math::Min(Fixed(1), Fixed(2)), Fixed(1));
    EXPECT_EQ(lockbox::math::Max(Fixed(1), Fixed(2)), Fixed(2));
    EXPECT_EQ(lockbox::math::Clamp(Fixed(5), Fixed(-1), Fixed(1)), Fixed(1));
    EXPECT_EQ(lockbox::math::Sign(Fixed(-0.5)), -1);
    EXPECT_EQ(std::numeric_limits<Fixed>::max().Raw(), INT32_MAX);
    EXPECT_EQ(std::numeric_limits<Fixed>::lowest().Raw(), -INT32_MAX);
    EXPECT_EQ(std::numeric_limits<Fixed>::epsilon().Raw(), 1);
    static_assert(std::numeric_limits<Fixed>::is_specialized);
}

TEST(FixedArith, ComparisonsFollowRaw) {
    EXPECT_LT(Fixed(-1), Fixed(0));
    EXPECT_GT(Fixed(0.5), Fixed(0.25));
    EXPECT_EQ(Fixed(0.5), Fixed::FromRaw(32768));
    EXPECT_NE(Fixed(0.5), Fixed::FromRaw(32767));
}

}  // namespace LOCKBOX_TEST_FILE
