// b2Vec2: exact dot/cross, correctly rounded Length, precise Normalize over 0.001 m .. 30,000 m
// (NUMERICS Table 9).
#include "lockbox/fixed/Vec2.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "FixedPrint.h"

using lockbox::b2Vec2;
using lockbox::Fixed;

namespace LOCKBOX_TEST_FILE {
long double ExactLength(const b2Vec2& v) {
    const long double x = v.x.Raw(), y = v.y.Raw();
    return std::sqrt(x * x + y * y);  // in raw units
}

TEST(Vec2, DotAndCrossAreExactThenRoundedOnce) {
    std::mt19937 rng(11);
    for (int i = 0; i < 100000; ++i) {
        const b2Vec2 a(Fixed::FromRaw(static_cast<int32_t>(rng()) / 4),
                       Fixed::FromRaw(static_cast<int32_t>(rng()) / 4));
        const b2Vec2 b(Fixed::FromRaw(static_cast<int32_t>(rng()) / 4),
                       Fixed::FromRaw(static_cast<int32_t>(rng()) / 4));
        const int64_t dot = int64_t{a.x.Raw()} * b.x.Raw() + int64_t{a.y.Raw()} * b.y.Raw();
        const int64_t cross = int64_t{a.x.Raw()} * b.y.Raw() - int64_t{a.y.Raw()} * b.x.Raw();
        ASSERT_EQ(lockbox::b2DotWide(a, b).Raw(), dot);
        ASSERT_EQ(lockbox::b2CrossWide(a, b).Raw(), cross);
        // Rounded once: within half an ULP of the exact value (unless saturated).
        const long double d = static_cast<long double>(dot) / 65536.0L;
        if (std::fabs(d) < 2.1e9L) {
            ASSERT_LE(std::fabs(lockbox::b2Dot(a, b).Raw() - d), 0.5L);
        }
    }
}

TEST(Vec2, LengthIsCorrectlyRoundedEverywhere) {
    std::mt19937_64 rng(12);
    for (int i = 0; i < 200000; ++i) {
        const int bits = static_cast<int>(rng() % 31);
        const int32_t x = static_cast<int32_t>(rng() % (uint64_t{1} << bits)) * ((rng() & 1) ? 1 : -1);
        const int32_t y = static_cast<int32_t>(rng() % (uint64_t{1} << bits)) * ((rng() & 1) ? 1 : -1);
        const b2Vec2 v(Fixed::FromRaw(x), Fixed::FromRaw(y));
        const long double exact = ExactLength(v);
        if (exact > 2147483647.0L) continue;
        ASSERT_LE(std::fabs(v.Length().Raw() - exact), 0.5L) << x << "," << y;
    }
    // 200 m: beyond where Q16.16 squared lengths overflow (181 m), still exact.
    EXPECT_EQ(b2Vec2(Fixed(200), Fixed(0)).Length(), Fixed(200));
    EXPECT_EQ(b2Vec2(Fixed(30000), Fixed(0)).Length(), Fixed(30000));
    EXPECT_EQ(b2Vec2(Fixed(3), Fixed(4)).Length(), Fixed(5));
    EXPECT_EQ(b2Vec2().Length(), Fixed());
}

TEST(Vec2, NormalizeKeepsDirectionFromAMillimetreTo30km) {
    // Targets (NUMERICS Table 9): |n| - 1 within 2e-3 at 0.005 m and within 2 ULP at >= 1 m.
    std::mt19937_64 rng(13);
    const double lengths[] = {0.001, 0.005, 0.01, 0.05, 1.0, 10.0, 100.0, 1000.0, 30000.0};
    for (double L : lengths) {
        long double worstUnit = 0, worstAngle = 0;
        for (int i = 0; i < 20000; ++i) {
            const double angle = static_cast<double>(rng() % 1000000) * 6.283185307179586 / 1e6;
            b2Vec2 v(Fixed::FromDoubleNondeterministic(L * std::cos(angle)),
                     Fixed::FromDoubleNondeterministic(L * std::sin(angle)));
            if (v.x == Fixed() && v.y == Fixed()) continue;
            const long double ex = v.x.Raw(), ey = v.y.Raw(), el = std::sqrt(ex * ex + ey * ey);
            b2Vec2 n = v;
            const Fixed len = n.Normalize();
            EXPECT_LE(std::fabs(len.Raw() - el), 0.5L);
            // Each component is within half an ULP (plus the tiny error of the scaled root).
            const long double nx = ex / el * 65536.0L, ny = ey / el * 65536.0L;
            worstAngle = std::max(worstAngle, std::max(std::fabs(n.x.Raw() - nx), std::fabs(n.y.Raw() - ny)));
            const long double unit = std::sqrt(static_cast<long double>(n.x.Raw()) * n.x.Raw() +
                                               static_cast<long double>(n.y.Raw()) * n.y.Raw()) /
                                     65536.0L;
            worstUnit = std::max(worstUnit, std::fabs(unit - 1.0L));
        }
        EXPECT_LE(worstAngle, 0.51L) << "L = " << L;
        EXPECT_LE(worstUnit, 2.0L / 65536.0L) << "L = " << L;
    }
}

TEST(Vec2, NormalizeOfZeroAndTinyVectors) {
    b2Vec2 zero;
    EXPECT_EQ(zero.Normalize(), Fixed());
    EXPECT_EQ(zero, b2Vec2());
    b2Vec2 ulp(Fixed::FromRaw(1), Fixed());
    EXPECT_EQ(ulp.Normalize(), Fixed::FromRaw(1));
    EXPECT_EQ(ulp, b2Vec2(Fixed(1), Fixed()));
    b2Vec2 diag(Fixed::FromRaw(-1), Fixed::FromRaw(1));
    diag.Normalize();
    EXPECT_EQ(diag.x.Raw(), -46341);  // 65536 / sqrt(2) = 46340.95
    EXPECT_EQ(diag.y.Raw(), 46341);
}

// Normalize's general steps (a scaled exact root and one reciprocal), which an axis vector skips:
// on an axis they must give what the shortcut gives, the unit axis and the magnitude.
std::pair<b2Vec2, Fixed> NormalizeByTheRoot(b2Vec2 v) {
    const uint64_t sum = static_cast<uint64_t>(v.LengthSquaredWide().Raw());
    const uint64_t root = detail::IsqrtRound64(sum);
    const Fixed length = Fixed::FromRaw(static_cast<int32_t>(std::min<uint64_t>(root, Fixed::kMaxRaw)));
    const int k = (std::countl_zero(sum) - 2) / 2;
    const uint64_t rootScaled = detail::IsqrtRound64(sum << (2 * k));
    const int64_t recip = static_cast<int64_t>((uint64_t{1} << 62) / rootScaled);
    const auto scale = [&](Fixed c) {
        const int64_t cs = int64_t{c.Raw()} * (int64_t{1} << k);
        return Fixed::FromRaw(static_cast<int32_t>(detail::ShiftRound(cs * recip, 46)));
    };
    return {b2Vec2(scale(v.x), scale(v.y)), length};
}

TEST(Vec2, NormalizeOnAnAxisIsTheUnitAxisAndTheMagnitude) {
    std::mt19937_64 rng(0xa515);
    std::vector<int32_t> magnitudes;
    for (int32_t m = 1; m <= (1 << 20); ++m) magnitudes.push_back(m);
    for (int i = 0; i < 200000; ++i) magnitudes.push_back(static_cast<int32_t>(1 + rng() % Fixed::kMaxRaw));
    for (int b = 20; b < 31; ++b) {
        for (const int32_t d : {-1, 0, 1}) magnitudes.push_back((int32_t{1} << b) + d);
    }
    magnitudes.push_back(Fixed::kMaxRaw);
    for (const int32_t m : magnitudes) {
        for (const b2Vec2 v : {b2Vec2(Fixed::FromRaw(m), Fixed()), b2Vec2(Fixed::FromRaw(-m), Fixed()),
                               b2Vec2(Fixed(), Fixed::FromRaw(m)), b2Vec2(Fixed(), Fixed::FromRaw(-m))}) {
            const auto [expected, expectedLength] = NormalizeByTheRoot(v);
            b2Vec2 n = v;
            const Fixed length = n.Normalize();
            ASSERT_EQ(n, expected) << v.x.Raw() << "," << v.y.Raw();
            ASSERT_EQ(length, expectedLength) << v.x.Raw() << "," << v.y.Raw();
            ASSERT_EQ(length.Raw(), m);
            ASSERT_EQ(b2Abs(n.x).Raw() + b2Abs(n.y).Raw(), Fixed::kOneRaw);
        }
    }
}

TEST(Vec2, HelpersMatchTheManual) {
    const b2Vec2 a(Fixed(1), Fixed(-2)), b(Fixed(-3), Fixed(4));
    EXPECT_EQ(a + b, b2Vec2(Fixed(-2), Fixed(2)));
    EXPECT_EQ(a - b, b2Vec2(Fixed(4), Fixed(-6)));
    EXPECT_EQ(Fixed(2) * a, b2Vec2(Fixed(2), Fixed(-4)));
    EXPECT_EQ(-a, b2Vec2(Fixed(-1), Fixed(2)));
    EXPECT_EQ(lockbox::b2Cross(a, Fixed(2)), b2Vec2(Fixed(-4), Fixed(-2)));
    EXPECT_EQ(lockbox::b2Cross(Fixed(2), a), b2Vec2(Fixed(4), Fixed(2)));
    EXPECT_EQ(lockbox::b2Abs(a), b2Vec2(Fixed(1), Fixed(2)));
    EXPECT_EQ(lockbox::b2Min(a, b), b2Vec2(Fixed(-3), Fixed(-2)));
    EXPECT_EQ(lockbox::b2Max(a, b), b2Vec2(Fixed(1), Fixed(4)));
    EXPECT_EQ(lockbox::b2Clamp(b, a, a), a);
    EXPECT_EQ(lockbox::b2Distance(b2Vec2(), b2Vec2(Fixed(3), Fixed(4))), Fixed(5));
    EXPECT_EQ(lockbox::b2DistanceSquared(b2Vec2(), b2Vec2(Fixed(3), Fixed(4))), Fixed(25));
    EXPECT_EQ(lockbox::b2DistanceSquaredWide(b2Vec2(), b2Vec2(Fixed(300), Fixed(400))).ToDouble(), 250000.0);
    EXPECT_EQ(a.Skew(), b2Vec2(Fixed(2), Fixed(1)));
    EXPECT_EQ(a(0), Fixed(1));
    EXPECT_EQ(a(1), Fixed(-2));
    b2Vec2 c = a;
    c += b;
    c -= a;
    c *= Fixed(0.5);
    EXPECT_EQ(c, b2Vec2(Fixed(-1.5), Fixed(2)));
    EXPECT_TRUE(c.IsValid());
}

}  // namespace LOCKBOX_TEST_FILE
