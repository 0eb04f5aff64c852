// Conversions: integers (exact), compile-time literals (correctly rounded), decimal text (exact),
// ratios, and the named display / tool conversions.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Wide.h"

using lockbox::Fixed;
using lockbox::Wide;
using namespace lockbox::literals;

TEST(FixedConversion, IntegersAreExact) {
    for (int i = -32767; i <= 32767; i += 7) EXPECT_EQ(Fixed(i).Raw(), i * 65536);
    EXPECT_EQ(Fixed(int64_t{-5}).Raw(), -5 * 65536);
    EXPECT_EQ(Fixed(uint8_t{200}).Raw(), 200 * 65536);
}

TEST(FixedConversion, CompileTimeLiteralsAreCorrectlyRounded) {
    static_assert(Fixed(1.0 / 60.0).Raw() == 1092);  // NUMERICS Table 3
    static_assert(Fixed(0.005).Raw() == 328);
    static_assert(Fixed(0.01).Raw() == 655);
    static_assert(Fixed(0.2f).Raw() == 13107);
    static_assert(Fixed(-0.5).Raw() == -32768);
    // Ties away from zero: 2^-17 is half an ULP.
    static_assert(Fixed(1.0 / 131072.0).Raw() == 1);
    static_assert(Fixed(-1.0 / 131072.0).Raw() == -1);
    static_assert(Fixed(3.0 / 131072.0).Raw() == 2);
    // The x87 trap from NUMERICS section 3: 128 + 2^-16 is exactly representable.
    static_assert(Fixed(128.0 + 1.0 / 65536.0).Raw() == 8388609);
    SUCCEED();
}

TEST(FixedConversion, DecimalLiteralsAreExact) {
    static_assert((12.375_fx).Raw() == 811008);
    static_assert((1e-3_fx).Raw() == 66);   // 65.536 -> 66
    static_assert((0.1_fx).Raw() == 6554);  // 6553.6 -> 6554
    static_assert((32767.99998_fx).Raw() == INT32_MAX);
    static_assert((0.0000076293945_fx).Raw() == 0);      // just below 0.5 ULP (7.62939453125e-6)
    static_assert((0.00000762939453125_fx).Raw() == 1);  // exactly 0.5 ULP: tie rounds away
    SUCCEED();
}

TEST(FixedConversion, ParseMatchesExactReference) {
    struct Case {
        const char* text;
        int32_t raw;
    };
    const Case cases[] = {
        {"0", 0},
        {"-0", 0},
        {"1", 65536},
        {"-12.375", -811008},
        {"+2.5", 163840},
        {"0.5", 32768},
        {".5", 32768},
        {"5.", 327680},
        {"1e3", 65536000},
        {"1.5E-1", 9830},
        {"-1e-5", -1},
        {"007.25", 475136},
        {"0.000", 0},
        {"32767", 2147418112},
        {"1.5f", 98304},
        {"0.00000762939453125", 1},
        {"-0.00000762939453125", -1},
        {"0.0000076293945312", 0},
        {"0.1000000000000000000000000000000000000000000000000000000000000000000000001", 6554},
    };
    for (const Case& c : cases) {
        Fixed f = Fixed(99);
        ASSERT_TRUE(Fixed::Parse(c.text, f)) << c.text;
        EXPECT_EQ(f.Raw(), c.raw) << c.text;
    }
}

TEST(FixedConversion, ParseRejectsBadText) {
    const char* bad[] = {"", "-", ".", "1.2.3", "abc", "1e", "1e+", "1x", "40000", "-32768.5", "1e20", "--1", " 1"};
    for (const char* text : bad) {
        Fixed f = Fixed(7);
        const char* error = nullptr;
        EXPECT_FALSE(Fixed::Parse(text, f, &error)) << text;
        EXPECT_EQ(f, Fixed(7)) << "unchanged on error: " << text;
        EXPECT_NE(error, nullptr);
    }
}

TEST(FixedConversion, ParseRoundTripsPrintedValues) {
    // Every raw printed with enough digits parses back to itself.
    std::mt19937 rng(5);
    for (int i = 0; i < 20000; ++i) {
        const int32_t raw = static_cast<int32_t>(rng());
        if (raw == INT32_MIN) continue;
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.10f", static_cast<double>(raw) / 65536.0);
        Fixed f;
        ASSERT_TRUE(Fixed::Parse(buf, f)) << buf;
        ASSERT_EQ(f.Raw(), raw) << buf;
    }
}

TEST(FixedConversion, RatioIsCorrectlyRounded) {
    EXPECT_EQ(Fixed::FromRatio(1, 60).Raw(), 1092);
    EXPECT_EQ(Fixed::FromRatio(-1, 3).Raw(), -21845);
    EXPECT_EQ(Fixed::FromRatio(1, 131072).Raw(), 1);  // tie away
    EXPECT_EQ(Fixed::FromRatio(-1, 131072).Raw(), -1);
    EXPECT_EQ(Fixed::FromRatio(INT64_MAX / 2, INT64_MAX).Raw(), 32768);
}

TEST(FixedConversion, DisplayAndToolConversions) {
    EXPECT_DOUBLE_EQ(Fixed(1.5).ToDouble(), 1.5);
    EXPECT_FLOAT_EQ(Fixed(-0.25).ToFloat(), -0.25f);
    EXPECT_EQ(Fixed::FromDoubleNondeterministic(0.5).Raw(), 32768);
    EXPECT_EQ(Fixed::FromDoubleNondeterministic(-1.0 / 131072.0).Raw(), -1);
    EXPECT_EQ(Fixed::FromDoubleNondeterministic(1e9).Raw(), INT32_MAX);
    EXPECT_EQ(Fixed::FromDoubleNondeterministic(std::nan("")).Raw(), 0);
}

TEST(WideConversion, WidenAndNarrow) {
    EXPECT_EQ(Wide(Fixed(1.5)).Raw(), int64_t{3} << 31);
    EXPECT_EQ(Wide::FromRaw(int64_t{1} << 15).ToFixed().Raw(), 1);  // tie away from zero
    EXPECT_EQ(Wide::FromRaw(-(int64_t{1} << 15)).ToFixed().Raw(), -1);
    EXPECT_EQ(Wide::FromRaw((int64_t{1} << 15) - 1).ToFixed().Raw(), 0);
    EXPECT_EQ(Wide::FromRaw(-((int64_t{1} << 15) - 1)).ToFixed().Raw(), 0);
    static_assert(Wide(0.25).Raw() == int64_t{1} << 30);
    Wide w;
    ASSERT_TRUE(Wide::Parse("1000000.5", w));
    EXPECT_EQ(w.Raw(), (int64_t{2000001} << 31));
}
