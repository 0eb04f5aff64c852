// Checked builds (LOCKBOX_CHECKED) stop on every overflow with the operation named; the
// default build saturates instead (fixed_arith_test). One death test per trap site.
#include <gtest/gtest.h>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Vec2.h"
#include "lockbox/fixed/Wide.h"

using lockbox::Fixed;
using lockbox::Wide;

namespace LOCKBOX_TEST_FILE {
// Values opaque to the optimiser, so every trap happens at run time.
Fixed Opaque(Fixed f) {
    volatile int32_t raw = f.Raw();
    return Fixed::FromRaw(raw);
}
[[maybe_unused]] Wide OpaqueWide(int64_t raw) {
    volatile int64_t r = raw;
    return Wide::FromRaw(r);
}

#ifdef LOCKBOX_CHECKED
TEST(FixedTrapDeathTest, EveryOverflowStopsWithTheOperationNamed) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const Fixed big = Opaque(Fixed::FromRaw(INT32_MAX));
    EXPECT_DEATH((void)(big + Fixed(1)), "Fixed::operator\\+");
    EXPECT_DEATH((void)(-big - Fixed(2)), "Fixed::operator-");
    EXPECT_DEATH((void)(big * Fixed(2)), "Fixed::operator\\*");
    EXPECT_DEATH((void)(Fixed(1) / Opaque(Fixed())), "Fixed::operator/");
    EXPECT_DEATH((void)(big / Fixed(0.5)), "Fixed::operator/");
    EXPECT_DEATH((void)(-Opaque(Fixed::FromRaw(INT32_MIN))), "negate");
    volatile int big_int = 40000;
    EXPECT_DEATH((void)Fixed(static_cast<int>(big_int)), "Fixed\\(integer\\)");
    EXPECT_DEATH((void)Fixed::FromRatio(1, 0), "FromRatio");
    EXPECT_DEATH((void)OpaqueWide(INT64_MAX / 2 + 1).ToFixed(), "Wide::ToFixed");
    EXPECT_DEATH((void)(OpaqueWide(INT64_MAX) + Wide(1)), "Wide::operator\\+");
    EXPECT_DEATH((void)(OpaqueWide(INT64_MIN + 1) - Wide(1)), "Wide::operator-");
    EXPECT_DEATH((void)(OpaqueWide(int64_t{1} << 62) * Wide(4)), "Wide::operator\\*");
    EXPECT_DEATH((void)(Wide(1) / OpaqueWide(0)), "Wide::operator/");
    EXPECT_DEATH((void)lockbox::MulToFixed(OpaqueWide(int64_t{1} << 50), Fixed(1)), "MulToFixed");
    const lockbox::b2Vec2 far(big, big);
    EXPECT_DEATH((void)far.LengthSquared(), "Wide::ToFixed");
}

TEST(FixedTrapDeathTest, HandlerIsReplaceable) {
    static int calls = 0;
    auto previous = lockbox::SetOverflowTrapHandler([](const char*, int64_t, int64_t) { ++calls; });
    const Fixed r = Opaque(Fixed::FromRaw(INT32_MAX)) + Fixed(1);
    lockbox::SetOverflowTrapHandler(previous);
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(r.Raw(), INT32_MAX);  // a handler that returns gets the saturated value
}
#else
TEST(FixedTrapDeathTest, DefaultBuildSaturatesInsteadOfTrapping) {
    EXPECT_FALSE(lockbox::kOverflowTraps);
    EXPECT_EQ((Opaque(Fixed::FromRaw(INT32_MAX)) + Fixed(1)).Raw(), INT32_MAX);
}
#endif

}  // namespace LOCKBOX_TEST_FILE
