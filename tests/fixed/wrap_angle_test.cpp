// WrapAngleRaw / WrapAngleTurnsRaw / WrapAngle: result in [-pi, pi) with whole turns of the
// exact 2 pi removed (then rounded once), idempotent, consistent turn counts.
#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/fixed/Functions.h"
#include "lockbox/fixed/detail/Trig.h"

using lockbox::Fixed;
using lockbox::detail::WrapAngleRaw;
using lockbox::detail::WrapAngleTurnsRaw;

namespace LOCKBOX_TEST_FILE {

constexpr int32_t kMin = std::numeric_limits<int32_t>::min();
constexpr int32_t kMax = std::numeric_limits<int32_t>::max();
constexpr long double kPiL = 3.14159265358979323846264338327950288L;

// The reference semantics with long double: the exact a - n 2pi must be in [-pi, pi), and the
// result is its nearest raw value. No int32 input lies within 2^-16 raw of a decision boundary,
// so a long double (even a 53-bit one) decides exactly.
::testing::AssertionResult MatchesExactSemantics(int32_t a) {
    int32_t turns = 0;
    const int32_t w = WrapAngleTurnsRaw(a, &turns);
    const long double v = static_cast<long double>(a) - turns * (2 * kPiL * 65536.0L);
    const long double pi_raw = kPiL * 65536.0L;
    if (!(v >= -pi_raw && v < pi_raw)) {
        return ::testing::AssertionFailure() << "a=" << a << " turns=" << turns << " exact rest out of range";
    }
    if (w != static_cast<int32_t>(std::llround(v))) {
        return ::testing::AssertionFailure() << "a=" << a << " w=" << w << " want " << std::llround(v);
    }
    if (WrapAngleRaw(a) != w) return ::testing::AssertionFailure() << "a=" << a << " WrapAngleRaw differs";
    return ::testing::AssertionSuccess();
}

TEST(WrapAngle, IdempotentOnTheWholeOutputRange) {
    // Every raw value of [-pi, pi) is returned unchanged with zero turns.
    for (int32_t a = -205887; a <= 205887; ++a) {
        int32_t turns = 99;
        ASSERT_EQ(WrapAngleTurnsRaw(a, &turns), a);
        ASSERT_EQ(turns, 0);
    }
}

TEST(WrapAngle, BoundaryAroundPi) {
    // pi * 2^16 = 205887.416: raw 205887 is below pi (kept), 205888 is above (wrapped).
    EXPECT_EQ(WrapAngleRaw(205887), 205887);
    EXPECT_EQ(WrapAngleRaw(205888), -205887);  // 205888 - 411774.83 = -205886.83
    EXPECT_EQ(WrapAngleRaw(-205887), -205887);
    EXPECT_EQ(WrapAngleRaw(-205888), 205887);  // -205888 + 411774.83 = 205886.83
    EXPECT_EQ(WrapAngleRaw(411775), 0);        // 2pi rounded: 0.17 raw above 2pi
    EXPECT_EQ(WrapAngleRaw(-411775), 0);
    int32_t turns = 0;
    EXPECT_EQ(WrapAngleTurnsRaw(205888, &turns), -205887);
    EXPECT_EQ(turns, 1);
    EXPECT_EQ(WrapAngleTurnsRaw(-205888, &turns), 205887);
    EXPECT_EQ(turns, -1);
}

TEST(WrapAngle, ExtremesOfInt32) {
    int32_t turns = 0;
    const int32_t w_max = WrapAngleTurnsRaw(kMax, &turns);
    EXPECT_EQ(turns, 5215);
    EXPECT_TRUE(MatchesExactSemantics(kMax));
    const int32_t w_min = WrapAngleTurnsRaw(kMin, &turns);
    EXPECT_EQ(turns, -5215);
    EXPECT_TRUE(MatchesExactSemantics(kMin));
    EXPECT_GE(w_max, -205887);
    EXPECT_LE(w_max, 205887);
    EXPECT_GE(w_min, -205887);
    EXPECT_LE(w_min, 205887);
}

TEST(WrapAngle, StridedFullRangeMatchesExactSemantics) {
    for (int64_t a = kMin; a <= kMax; a += 4099) {
        ASSERT_TRUE(MatchesExactSemantics(static_cast<int32_t>(a)));
    }
    // Every multiple of the turn, +-1 raw and +-pi around it (the decision points).
    for (int n = -5215; n <= 5215; ++n) {
        const long double center = n * 2 * kPiL * 65536.0L;
        for (long double off : {-kPiL * 65536.0L, 0.0L, kPiL * 65536.0L}) {
            const long long base = std::llround(center + off);
            for (long long d = -2; d <= 2; ++d) {
                const long long a = base + d;
                if (a < kMin || a > kMax) continue;
                ASSERT_TRUE(MatchesExactSemantics(static_cast<int32_t>(a)));
            }
        }
    }
}

TEST(WrapAngle, NoDriftWhenSpinning) {
    // A wheel at 94 rad/s for 10 simulated minutes (36000 steps of raw dt 1092): accumulate the
    // wrapped angle and the turn count; the exact total is steps * omega * dt.
    const int32_t step = 94 * 1092;  // 94 rad/s times dt = 1092 raw: 1.566 rad per step, exact
    int32_t angle = 0;
    int64_t total_turns = 0;
    for (int i = 0; i < 36000; ++i) {
        int32_t turns = 0;
        angle = WrapAngleTurnsRaw(angle + step, &turns);
        total_turns += turns;
        ASSERT_GE(angle, -205887);
        ASSERT_LE(angle, 205887);
    }
    // Each wrap rounds once (<= 0.5 raw); the drift against the exact total is bounded by the
    // number of wraps times 0.5 raw.
    const long double exact = 36000.0L * step;
    const long double got = angle + total_turns * 2 * kPiL * 65536.0L;
    EXPECT_LE(std::fabs(got - exact), 0.5L * static_cast<long double>(total_turns) + 0.5L);
}

TEST(WrapAngle, PublicWrappers) {
    EXPECT_EQ(lockbox::math::WrapAngle(lockbox::math::kPi), lockbox::math::kPi);
    EXPECT_EQ(lockbox::math::WrapAngle(-lockbox::math::kPi), -lockbox::math::kPi);
    EXPECT_EQ(lockbox::math::WrapAngle(lockbox::math::kTwoPi), Fixed(0));
    int32_t turns = 0;
    EXPECT_EQ(lockbox::math::WrapAngle(Fixed(100), turns).Raw(), WrapAngleRaw(100 * 65536));
    EXPECT_EQ(turns, 16);  // 100 rad = 15.9 turns -> 16 turns removed, rest -0.53 rad
}

}  // namespace LOCKBOX_TEST_FILE
