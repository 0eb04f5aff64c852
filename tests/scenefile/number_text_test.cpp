// Scene-file numbers: decimal text follows Fixed::Parse's rule exactly, hexadecimal binary32
// values decode from their bits with round-to-nearest, ties away from zero, and the saved text
// is the shortest decimal that reads back to the same raw value.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/scenefile/NumberText.h"

namespace lockbox::scenefile {
namespace LOCKBOX_TEST_FILE {

Fixed ParsedFixed(const std::string& text) {
    Fixed v = Fixed::FromRaw(123456789);
    EXPECT_EQ(ParseFixed(text, v), NumberError::e_ok) << text;
    return v;
}

Fixed Hex(const char* bits) {
    Fixed v;
    EXPECT_EQ(HexFloatToFixed(bits, v), NumberError::e_ok) << bits;
    return v;
}

TEST(NumberText, DecimalMatchesFixedParse) {
    // The fast path and Fixed::Parse (detail::ParseDecimal) agree on every kind of JSON number.
    std::mt19937_64 rng(7);
    for (int i = 0; i < 100000; ++i) {
        std::string t;
        if (rng() & 1) t += '-';
        const int whole = static_cast<int>(rng() % 6);
        t += std::to_string(rng() % (whole == 0 ? 1 : (whole == 5 ? 32768 : 10000)));
        const int frac = static_cast<int>(rng() % 22);
        if (frac) {
            t += '.';
            for (int k = 0; k < frac; ++k) t += static_cast<char>('0' + rng() % 10);
        }
        if (rng() % 5 == 0) {
            t += 'e';
            t += std::to_string(static_cast<int>(rng() % 12) - 8);
        }
        Fixed want;
        const bool ok = Fixed::Parse(t, want);
        Fixed got;
        const NumberError e = ParseFixed(t, got);
        ASSERT_EQ(e == NumberError::e_ok, ok) << t;
        if (ok) {
            ASSERT_EQ(got, want) << t;
        }
    }
}

TEST(NumberText, DecimalExamples) {
    EXPECT_EQ(ParsedFixed("1"), Fixed(1));
    EXPECT_EQ(ParsedFixed("-0"), Fixed());
    EXPECT_EQ(ParsedFixed("0.1"), Fixed::FromRaw(6554));
    EXPECT_EQ(ParsedFixed("-0.1"), Fixed::FromRaw(-6554));
    EXPECT_EQ(ParsedFixed("1.25e3"), Fixed(1250));
    EXPECT_EQ(ParsedFixed("1e-300"), Fixed());
    EXPECT_EQ(ParsedFixed("32767.99998"), Fixed::FromRaw(Fixed::kMaxRaw));
    // A tie (1.5 raw units) goes away from zero.
    EXPECT_EQ(ParsedFixed("0.00002288818359375"), Fixed::FromRaw(2));
    EXPECT_EQ(ParsedFixed("-0.00002288818359375"), Fixed::FromRaw(-2));
    Fixed v;
    EXPECT_EQ(ParseFixed("32768", v), NumberError::e_outOfRange);
    EXPECT_EQ(ParseFixed("1e5", v), NumberError::e_outOfRange);
    EXPECT_EQ(ParseFixed("abc", v), NumberError::e_malformed);
    Wide w;
    EXPECT_EQ(ParseWide("0.5026394848", w), NumberError::e_ok);
    EXPECT_EQ(w, Wide::FromRaw(2158820149));  // 2158820148.894... raw units
    EXPECT_EQ(ParseWide("2147483648", w), NumberError::e_outOfRange);
}

TEST(NumberText, HexFloatsDecodeFromTheirBits) {
    EXPECT_EQ(Hex("3F800000"), Fixed(1));
    EXPECT_EQ(Hex("bf800000"), Fixed(-1));
    EXPECT_EQ(Hex("00000000"), Fixed());
    EXPECT_EQ(Hex("80000000"), Fixed());
    EXPECT_EQ(Hex("41200000"), Fixed(10));
    // 0.1f is 0.100000001490116...: 6553.6000977 raw units, nearest 6554.
    EXPECT_EQ(Hex("3DCCCCCD"), Fixed::FromRaw(6554));
    // Exact halves of a raw unit round away from zero: 2^-17 -> 1, 3 * 2^-17 -> 2.
    EXPECT_EQ(Hex("37000000"), Fixed::FromRaw(1));
    EXPECT_EQ(Hex("B7000000"), Fixed::FromRaw(-1));
    EXPECT_EQ(Hex("37C00000"), Fixed::FromRaw(2));
    // Just below half a unit rounds to zero; the smallest subnormal too.
    EXPECT_EQ(Hex("36FFFFFF"), Fixed());
    EXPECT_EQ(Hex("00000001"), Fixed());
    // The largest float below 32768.
    EXPECT_EQ(Hex("46FFFFFF"), Fixed::FromRaw(2147483520));
    Fixed v;
    EXPECT_EQ(HexFloatToFixed("47000000", v), NumberError::e_outOfRange);  // 32768
    EXPECT_EQ(HexFloatToFixed("7F800000", v), NumberError::e_notFinite);   // +inf
    EXPECT_EQ(HexFloatToFixed("7FC00000", v), NumberError::e_notFinite);   // NaN
    EXPECT_EQ(HexFloatToFixed("3F80000", v), NumberError::e_malformed);
    EXPECT_EQ(HexFloatToFixed("3F80000G", v), NumberError::e_malformed);
    Wide w;
    EXPECT_EQ(HexFloatToWide("3F000000", w), NumberError::e_ok);
    EXPECT_EQ(w, Wide::FromRaw(int64_t{1} << 31));
    EXPECT_EQ(HexFloatToWide("2F000000", w), NumberError::e_ok);  // 2^-33: half a unit, away from zero
    EXPECT_EQ(w, Wide::FromRaw(1));
    EXPECT_EQ(HexFloatToWide("4F000000", w), NumberError::e_outOfRange);  // 2^31
}

TEST(NumberText, EveryHexFloatInRangeMatchesExactRounding) {
    // Every binary32 of a sampled exponent range against the exact rational value.
    for (uint32_t bits = 0x30000000u; bits < 0x47000000u; bits += 4099) {
        char text[9];
        std::snprintf(text, sizeof text, "%08X", bits);
        Fixed v;
        ASSERT_EQ(HexFloatToFixed(text, v), NumberError::e_ok) << text;
        const int e = static_cast<int>((bits >> 23) & 0xFF) - 150 + 16;
        const uint64_t m = (bits & 0x7FFFFF) | 0x800000;
        int64_t want = 0;
        if (e >= 0) {
            want = static_cast<int64_t>(m << e);
        } else if (-e < 40) {
            const uint64_t half = uint64_t{1} << (-e - 1);
            want = static_cast<int64_t>((m + half) >> -e);
        }
        ASSERT_EQ(v.Raw(), want) << text;
    }
}

// True when no decimal with fewer fraction digits than `text` reads back as `raw`.
bool Shortest(const std::string& text, int32_t raw) {
    const size_t point = text.find('.');
    if (point == std::string::npos) return true;
    const int digits = static_cast<int>(text.size() - point - 1);
    const double x = static_cast<double>(raw) / 65536.0;  // a guide to the neighbours only
    for (int k = 0; k < digits; ++k) {
        double scale = 1;
        for (int i = 0; i < k; ++i) scale *= 10;
        for (double c : {std::floor(x * scale) / scale, std::ceil(x * scale) / scale}) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.*f", k, c);
            Fixed v;
            if (ParseFixed(buf, v) == NumberError::e_ok && v.Raw() == raw) return false;
        }
    }
    return true;
}

TEST(NumberText, FormatIsShortestAndReadsBack) {
    EXPECT_EQ(FormatFixed(Fixed()), "0");
    EXPECT_EQ(FormatFixed(Fixed(1)), "1");
    EXPECT_EQ(FormatFixed(Fixed(-12)), "-12");
    EXPECT_EQ(FormatFixed(Fixed::FromRaw(6554)), "0.1");
    EXPECT_EQ(FormatFixed(Fixed::FromRaw(-6554)), "-0.1");
    EXPECT_EQ(FormatFixed(Fixed::FromRaw(1)), "0.00002");
    EXPECT_EQ(FormatFixed(Fixed::FromRaw(32768)), "0.5");
    EXPECT_EQ(FormatFixed(Fixed::FromRaw(Fixed::kMaxRaw)), "32767.99998");
    EXPECT_EQ(FormatWide(Wide(1)), "1");
    EXPECT_EQ(FormatWide(Wide::FromRaw(1)), "0.0000000002");
    std::mt19937 rng(11);
    for (int i = 0; i < 150000; ++i) {
        const auto raw =
            static_cast<int32_t>(rng() % 2000001) - 1000000 + (i % 3 == 0 ? static_cast<int32_t>(rng()) / 2 : 0);
        const std::string t = FormatFixed(Fixed::FromRaw(raw));
        Fixed back;
        ASSERT_EQ(ParseFixed(t, back), NumberError::e_ok) << t;
        ASSERT_EQ(back.Raw(), raw) << t;
        if (i % 10 == 0) {
            ASSERT_TRUE(Shortest(t, raw)) << t;
        }
    }
    std::mt19937_64 rng64(5);
    for (int i = 0; i < 100000; ++i) {
        const auto raw = static_cast<int64_t>(rng64() >> (1 + rng64() % 40)) * ((i & 1) ? -1 : 1);
        const std::string t = FormatWide(Wide::FromRaw(raw));
        Wide back;
        ASSERT_EQ(ParseWide(t, back), NumberError::e_ok) << t;
        ASSERT_EQ(back.Raw(), raw) << t;
        ASSERT_LE(t.size() - (t.find('.') == std::string::npos ? t.size() : t.find('.')), 11u) << t;
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenefile
