// The JavaScript number conversion (web/src/NumberConversion.h) against Fixed::Parse: every
// binary64 value has a finite decimal expansion, and converting the value must give exactly
// what parsing that expansion gives (both refused, or the same raw value), for Q16.16 and
// Q32.32 alike.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "NumberConversion.h"
#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/detail/Decimal.h"

namespace lockbox::web {
namespace LOCKBOX_TEST_FILE {

uint64_t Bits(double d) { return std::bit_cast<uint64_t>(d); }

// The exact decimal expansion of the binary64 value with bit pattern `bits` (finite), built
// with integer arithmetic on a digit string: significand * 2^e is significand * 5^-e / 10^-e
// for a negative e.
std::string ExactDecimal(uint64_t bits) {
    const bool negative = (bits >> 63) != 0;
    const int biased = static_cast<int>((bits >> 52) & 0x7FF);
    const uint64_t fraction = bits & ((uint64_t{1} << 52) - 1);
    uint64_t significand = biased == 0 ? fraction : fraction | (uint64_t{1} << 52);
    int exponent = (biased == 0 ? 1 : biased) - 1075;
    for (; significand != 0 && (significand & 1) == 0 && exponent < 0; significand >>= 1) ++exponent;
    std::vector<int> digits;  // least significant first
    for (; significand; significand /= 10) digits.push_back(static_cast<int>(significand % 10));
    if (digits.empty()) digits.push_back(0);
    auto multiply = [&digits](int factor) {
        int carry = 0;
        for (int& d : digits) {
            const int v = d * factor + carry;
            d = v % 10;
            carry = v / 10;
        }
        for (; carry; carry /= 10) digits.push_back(carry % 10);
    };
    int fractionDigits = 0;
    for (; exponent > 0; --exponent) multiply(2);
    for (; exponent < 0; ++exponent, ++fractionDigits) multiply(5);
    while (static_cast<int>(digits.size()) <= fractionDigits) digits.push_back(0);
    std::string s = negative ? "-" : "";
    for (int i = static_cast<int>(digits.size()) - 1; i >= 0; --i) {
        s += static_cast<char>('0' + digits[static_cast<size_t>(i)]);
        if (i == fractionDigits && i > 0) s += '.';
    }
    return s;
}

// Converts `bits` both ways for one format and expects the same answer.
void ExpectAgrees(uint64_t bits, int fracBits, int64_t maxRaw) {
    const RawNumber got = DoubleBitsToRaw(bits, fracBits, maxRaw);
    const std::string text = ExactDecimal(bits);
    const detail::DecimalResult want = detail::ParseDecimal(text, fracBits, maxRaw);
    const bool refused = want.error != detail::DecimalError::None;
    ASSERT_EQ(got.error != NumberError::none, refused) << text << " (bits 0x" << std::hex << bits << ")";
    if (!refused) {
        ASSERT_EQ(got.raw, want.raw) << text;
    }
}

TEST(NumberConversion, ExactDecimalIsExact) {
    EXPECT_EQ(ExactDecimal(Bits(0.5)), "0.5");
    EXPECT_EQ(ExactDecimal(Bits(-3.0)), "-3");
    EXPECT_EQ(ExactDecimal(Bits(0.1)), "0.1000000000000000055511151231257827021181583404541015625");
    EXPECT_EQ(ExactDecimal(Bits(1024.0)), "1024");
}

TEST(NumberConversion, DecimalStringsAsJavaScriptReadsThem) {
    // A decimal string becomes the nearest double in JavaScript (Number('0.1')), which the C++
    // compiler reproduces for these literals; the conversion of that double must equal
    // Fixed::Parse of the string whenever the double's expansion rounds as the string does,
    // which holds for every string here (none lies within 2^-53 of a Q16.16 tie).
    struct Case {
        const char* text;
        double value;
    };
    const Case cases[] = {{"0", 0.0},
                          {"0.1", 0.1},
                          {"-0.1", -0.1},
                          {"1.5", 1.5},
                          {"-10", -10.0},
                          {"0.7", 0.7},
                          {"3.14159265358979", 3.14159265358979},
                          {"-2.5e-3", -2.5e-3},
                          {"12345.6789", 12345.6789},
                          {"32767.99998", 32767.99998},
                          {"-32767.99998", -32767.99998},
                          {"0.016666666666666666", 1.0 / 60.0}};
    for (const Case& c : cases) {
        Fixed parsed;
        ASSERT_TRUE(Fixed::Parse(c.text, parsed)) << c.text;
        const RawNumber got = DoubleBitsToFixedRaw(Bits(c.value));
        ASSERT_EQ(got.error, NumberError::none) << c.text;
        EXPECT_EQ(got.raw, parsed.Raw()) << c.text;
    }
}

TEST(NumberConversion, HalvesRoundAwayFromZero) {
    // k + 1/2 units (2^-17 steps) are exact doubles: ties go away from zero, both signs.
    const double unit = 1.0 / 65536.0;
    for (int k = 0; k < 2000; ++k) {
        const double tie = (k + 0.5) * unit;
        EXPECT_EQ(DoubleBitsToFixedRaw(Bits(tie)).raw, k + 1) << k;
        EXPECT_EQ(DoubleBitsToFixedRaw(Bits(-tie)).raw, -(k + 1)) << k;
        // Just below and above the tie.
        EXPECT_EQ(DoubleBitsToFixedRaw(Bits(std::nextafter(tie, 0.0))).raw, k) << k;
        EXPECT_EQ(DoubleBitsToFixedRaw(Bits(std::nextafter(tie, 1.0))).raw, k + 1) << k;
    }
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(12.5 + 0.5 / 65536)).raw, 12 * 65536 + 32769);
}

TEST(NumberConversion, RangeLimits) {
    const int64_t max = std::numeric_limits<int32_t>::max();
    // The largest value, exactly.
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(max / 65536.0)).raw, max);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(-max / 65536.0)).raw, -max);
    // Its tie with 2^31 rounds away, out of range; just below the tie stays in.
    const double tie = (max + 0.5) / 65536.0;
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(tie)).error, NumberError::outOfRange);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(std::nextafter(tie, 0.0))).raw, max);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(-32768.0)).error, NumberError::outOfRange);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(32768.0)).error, NumberError::outOfRange);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(1e300)).error, NumberError::outOfRange);
    Fixed parsed;
    EXPECT_FALSE(Fixed::Parse("32767.9999923706054688", parsed));  // the tie, as text
    // Q32.32: 2^31 - 2^-32 fits, 2^31 does not.
    EXPECT_EQ(DoubleBitsToWideRaw(Bits(2147483647.0)).raw, int64_t{2147483647} << 32);
    EXPECT_EQ(DoubleBitsToWideRaw(Bits(2147483648.0)).error, NumberError::outOfRange);
    EXPECT_EQ(DoubleBitsToWideRaw(Bits(0.1)).raw, 429496730);
}

TEST(NumberConversion, RefusesWhatIsNotANumber) {
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(std::numeric_limits<double>::quiet_NaN())).error, NumberError::notFinite);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(std::numeric_limits<double>::infinity())).error, NumberError::notFinite);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(-std::numeric_limits<double>::infinity())).error, NumberError::notFinite);
    EXPECT_EQ(DoubleBitsToWideRaw(Bits(std::numeric_limits<double>::quiet_NaN())).error, NumberError::notFinite);
    EXPECT_EQ(DoubleBitsToFixedRaw(0x7FF0000000000001ull).error, NumberError::notFinite);  // signalling NaN
}

TEST(NumberConversion, ZeroesAndTinyValues) {
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(0.0)).raw, 0);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(-0.0)).raw, 0);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(std::numeric_limits<double>::denorm_min())).raw, 0);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(-std::numeric_limits<double>::min())).raw, 0);
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(1.0 / 131072)).raw, 1);  // half a unit: away from zero
    EXPECT_EQ(DoubleBitsToFixedRaw(Bits(std::nextafter(1.0 / 131072, 0.0))).raw, 0);
}

TEST(NumberConversion, AgreesWithParseOnExactExpansions) {
    // Every exponent from the subnormals to beyond the range, with pseudo-random significands
    // (SplitMix64), both signs, for both formats.
    uint64_t state = 0x243F6A8885A308D3ull;
    auto next = [&state] {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    };
    const int64_t fixedMax = std::numeric_limits<int32_t>::max();
    const int64_t wideMax = std::numeric_limits<int64_t>::max();
    // Below 2^-63 both formats round to zero: a few samples suffice there (their exact
    // expansions are long, so they are the slow part).
    for (int biased = 0; biased <= 1100; biased += biased < 960 ? 61 : 1) {
        for (int i = 0; i < (biased < 960 ? 2 : 24); ++i) {
            const uint64_t r = next();
            const uint64_t bits =
                (r & 0x8000000000000000ull) | (uint64_t(biased) << 52) | (r & ((uint64_t{1} << 52) - 1));
            ExpectAgrees(bits, 16, fixedMax);
            ExpectAgrees(bits, 32, wideMax);
        }
    }
    // Values with few significant bits, where ties are common.
    for (int i = 0; i < 4000; ++i) {
        const uint64_t r = next();
        const int exponentBits = 1023 - 24 + static_cast<int>(r % 44);  // 2^-24 .. 2^19
        const uint64_t bits =
            (r & 0x8000000000000000ull) | (uint64_t(exponentBits) << 52) | ((r >> 11) & (0xFFull << 40));
        ExpectAgrees(bits, 16, fixedMax);
        ExpectAgrees(bits, 32, wideMax);
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::web
