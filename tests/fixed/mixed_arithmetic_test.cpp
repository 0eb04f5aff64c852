// Mixed arithmetic: a plain number (an integer, or a float or double literal) next to a Fixed,
// a Wide or a vector compiles, has the type of the lockbox operand, and gives the bits of the
// explicit form (the number converted first). A number that converts to both Fixed and Wide
// once made `0.25f * b2_pi`, `b2_pi * 2`, `n * x` and `2.0f * v` ambiguous; these are the
// manual's own forms, so each is checked here exactly as written.
#include <cstdint>
#include <type_traits>

#include <gtest/gtest.h>

#include "lockbox/fixed/Math.h"
#include "lockbox/fixed/WideMatrix.h"
#include "lockbox/fixed/WideVec.h"

using namespace lockbox;

namespace LOCKBOX_TEST_FILE {

// Run-time integers: the products below must not depend on the compiler folding them.
int32_t g_three = 3;
int64_t g_seven = 7;
uint8_t g_five = 5;

Fixed RuntimeFixed(int32_t raw) { return Fixed::FromRaw(raw); }

// Everything compared as raw integers, so "equal" means the same bits.
struct Bits {
    int64_t v[4] = {};
    bool operator==(const Bits&) const = default;
};
Bits BitsOf(Fixed f) { return {{f.Raw()}}; }
Bits BitsOf(Wide w) { return {{w.Raw()}}; }
Bits BitsOf(const b2Vec2& v) { return {{v.x.Raw(), v.y.Raw()}}; }
Bits BitsOf(const b2Vec3& v) { return {{v.x.Raw(), v.y.Raw(), v.z.Raw()}}; }
Bits BitsOf(const b2WideVec2& v) { return {{v.x.Raw(), v.y.Raw()}}; }
Bits BitsOf(const b2Mat22& m) { return {{m.ex.x.Raw(), m.ex.y.Raw(), m.ey.x.Raw(), m.ey.y.Raw()}}; }
Bits BitsOf(bool b) { return {{b ? 1 : 0}}; }
Bits BitsOf(int32_t i) { return {{i}}; }

// The mixed form and the explicit form have the same type and the same bits.
#define EXPECT_SAME(mixed, explicitForm)                                                                     \
    do {                                                                                                     \
        static_assert(std::is_same_v<std::remove_cvref_t<decltype(mixed)>, decltype(explicitForm)>, #mixed); \
        EXPECT_EQ(BitsOf(mixed), BitsOf(explicitForm)) << #mixed << " vs " #explicitForm;                    \
    } while (0)

TEST(MixedArithmetic, TheManualsFormsCompileAndMeanTheExplicitForm) {
    const int32_t n = g_three;
    const Fixed x = RuntimeFixed(98765);  // 1.507...
    const b2Vec2 v(RuntimeFixed(-70000), RuntimeFixed(123457));
    EXPECT_SAME(0.25f * b2_pi, Fixed(0.25f) * b2_pi);
    EXPECT_SAME(b2_pi * 2, b2_pi * Fixed(2));
    EXPECT_SAME(n * x, Fixed(n) * x);
    EXPECT_SAME(2.0f * v, Fixed(2.0f) * v);
    // From the manual's joint sections: limits and a gear ratio.
    EXPECT_SAME(-0.5f * b2_pi, Fixed(-0.5f) * b2_pi);
    EXPECT_SAME(2.0f * b2_pi / x, Fixed(2.0f) * b2_pi / x);
    EXPECT_EQ((0.25f * b2_pi).Raw(), 51472);  // pi/4 from the rounded pi: 205887 / 4 rounded
}

TEST(MixedArithmetic, FixedWithIntegers) {
    const int32_t n = g_three;
    const int64_t m = g_seven;
    const uint8_t u = g_five;
    const Fixed x = RuntimeFixed(-98765);
    EXPECT_SAME(x * n, x * Fixed(n));
    EXPECT_SAME(m * x, Fixed(m) * x);
    EXPECT_SAME(x * u, x * Fixed(u));
    EXPECT_SAME(x + 1, x + Fixed(1));
    EXPECT_SAME(1 + x, Fixed(1) + x);
    EXPECT_SAME(x - n, x - Fixed(n));
    EXPECT_SAME(n - x, Fixed(n) - x);
    EXPECT_SAME(x / 3, x / Fixed(3));
    EXPECT_SAME(3 / x, Fixed(3) / x);
    EXPECT_SAME(x < n, x < Fixed(n));
    EXPECT_SAME(n <= x, Fixed(n) <= x);
    EXPECT_SAME(x == -2, x == Fixed(-2));
    EXPECT_SAME(2 != x, Fixed(2) != x);
    Fixed y = x;
    y *= 2;
    EXPECT_SAME(y, x * Fixed(2));
    y = x;
    y /= n;
    EXPECT_SAME(y, x / Fixed(n));
    y = x;
    y += 1;
    y -= n;
    EXPECT_SAME(y, x + Fixed(1) - Fixed(n));
}

TEST(MixedArithmetic, FixedWithLiterals) {
    const Fixed x = RuntimeFixed(98765);
    EXPECT_SAME(x * 0.5, x * Fixed(0.5));
    EXPECT_SAME(0.1f * x, Fixed(0.1f) * x);
    EXPECT_SAME(x + 0.25f, x + Fixed(0.25f));
    EXPECT_SAME(1.5 - x, Fixed(1.5) - x);
    EXPECT_SAME(x / 0.75f, x / Fixed(0.75f));
    EXPECT_SAME(2.0 / x, Fixed(2.0) / x);
    EXPECT_SAME(x < -0.5f, x < Fixed(-0.5f));
    EXPECT_SAME(1.0f < x, Fixed(1.0f) < x);
    EXPECT_SAME(x >= 1.5, x >= Fixed(1.5));
    EXPECT_SAME(x == 0.25, x == Fixed(0.25));
    Fixed y = x;
    y *= 0.5f;
    y += 0.125;
    EXPECT_SAME(y, x * Fixed(0.5f) + Fixed(0.125));
}

TEST(MixedArithmetic, WideWithNumbersStaysWide) {
    const int32_t n = g_three;
    const Wide w = Wide::FromRaw(-12345678901);
    EXPECT_SAME(w * 2, w * Wide(2));
    EXPECT_SAME(2 * w, Wide(2) * w);
    EXPECT_SAME(n * w, Wide(n) * w);
    EXPECT_SAME(w * 0.5, w * Wide(0.5));
    EXPECT_SAME(0.5f * w, Wide(0.5f) * w);
    EXPECT_SAME(w + 1, w + Wide(1));
    EXPECT_SAME(1.5 - w, Wide(1.5) - w);
    EXPECT_SAME(w / 4, w / Wide(4));
    EXPECT_SAME(4 / w, Wide(4) / w);
    EXPECT_SAME(w > 0, w > Wide(0));
    EXPECT_SAME(-3 < w, Wide(-3) < w);
    EXPECT_SAME(w == 1.5, w == Wide(1.5));
    Wide y = w;
    y *= 2;
    y -= 0.25;
    EXPECT_SAME(y, w * Wide(2) - Wide(0.25));
}

TEST(MixedArithmetic, WideTimesFixedIsTheOneRoundingProduct) {
    const Fixed x = RuntimeFixed(-98765);
    const Wide w = Wide::FromRaw(12345678901);
    EXPECT_SAME(w * x, Wide::FromRaw(detail::MulShiftRound64(w.Raw(), x.Raw(), 16, "test")));
    EXPECT_SAME(x * w, w * x);
}

TEST(MixedArithmetic, VectorsWithNumbers) {
    const int32_t n = g_three;
    const Fixed x = RuntimeFixed(40000);
    const b2Vec2 v(RuntimeFixed(-70000), RuntimeFixed(123457));
    EXPECT_SAME(2 * v, Fixed(2) * v);
    EXPECT_SAME(n * v, Fixed(n) * v);
    EXPECT_SAME(0.5 * v, Fixed(0.5) * v);
    EXPECT_SAME(b2_pi * v, b2Vec2(b2_pi * v.x, b2_pi * v.y));
    EXPECT_SAME(b2Vec2(2.0f, 3), b2Vec2(Fixed(2.0f), Fixed(3)));
    EXPECT_SAME(v + b2Vec2(1, 0.5f), v + b2Vec2(Fixed(1), Fixed(0.5f)));
    EXPECT_SAME(v - b2Vec2(0.25, -1), v - b2Vec2(Fixed(0.25), Fixed(-1)));
    EXPECT_SAME(b2Cross(v, 2.0f), b2Cross(v, Fixed(2.0f)));
    EXPECT_SAME(b2Cross(n, v), b2Cross(Fixed(n), v));
    EXPECT_SAME(b2Dot(v, v) > 1.0f, b2Dot(v, v) > Fixed(1.0f));
    EXPECT_SAME(v.y < -0.5f, v.y < Fixed(-0.5f));
    b2Vec2 u = v;
    u *= 2;
    u *= 0.5f;
    EXPECT_SAME(u, Fixed(0.5f) * (Fixed(2) * v));
    u.Set(2.0f, n);
    EXPECT_SAME(u, b2Vec2(Fixed(2.0f), Fixed(n)));
    EXPECT_SAME(x * v, b2Vec2(x * v.x, x * v.y));

    const b2Vec3 a(RuntimeFixed(65536), RuntimeFixed(-3), RuntimeFixed(99999));
    EXPECT_SAME(2.0f * a, Fixed(2.0f) * a);
    EXPECT_SAME(n * a, Fixed(n) * a);
    EXPECT_SAME(b2Vec3(1, 2.0f, 0.5) + a, b2Vec3(Fixed(1), Fixed(2.0f), Fixed(0.5)) + a);
    b2Vec3 b = a;
    b *= 2;
    EXPECT_SAME(b, Fixed(2) * a);

    const b2Mat22 A(1, 2.0f, 0.5, n);
    EXPECT_SAME(A, b2Mat22(Fixed(1), Fixed(2.0f), Fixed(0.5), Fixed(n)));
    EXPECT_SAME(A + A, b2Mat22(A.ex + A.ex, A.ey + A.ey));
    EXPECT_SAME(b2Mul(A, 2.0f * v), b2Mul(A, Fixed(2.0f) * v));
}

TEST(MixedArithmetic, WideVectorsTakeWideScalars) {
    const int32_t n = g_three;
    const Fixed x = RuntimeFixed(-40000);
    const Wide w = Wide::FromRaw(-9876543210);
    const b2Vec2 d(RuntimeFixed(-70000), RuntimeFixed(123457));
    const b2WideVec2 p(Wide::FromRaw(123456789012), Wide::FromRaw(-5));
    EXPECT_SAME(2 * p, Wide(2) * p);
    EXPECT_SAME(n * p, Wide(n) * p);
    EXPECT_SAME(0.5 * p, Wide(0.5) * p);
    EXPECT_SAME(x * p, b2WideVec2(p.x * x, p.y * x));
    EXPECT_SAME(w * p, b2WideVec2(w * p.x, w * p.y));
    EXPECT_SAME(w * d, b2WideVec2(w * d.x, w * d.y));
}

TEST(MixedArithmetic, ManualScalarFunctionsTakeNumbers) {
    const int32_t n = g_three;
    const Fixed x = RuntimeFixed(-98765);
    const Wide w = Wide::FromRaw(-9876543210);
    EXPECT_SAME(b2Max(x, 0.0f), math::Max(x, Fixed(0.0f)));
    EXPECT_SAME(b2Min(2, x), math::Min(Fixed(2), x));
    EXPECT_SAME(b2Clamp(x, -1, 1), math::Clamp(x, Fixed(-1), Fixed(1)));
    EXPECT_SAME(b2Abs(-0.5f * b2_pi), math::Abs(Fixed(-0.5f) * b2_pi));
    EXPECT_SAME(b2Max(w, 0), math::Max(w, Wide(0)));
    EXPECT_SAME(b2Abs(w), math::Abs(w));
    EXPECT_SAME(b2Sqrt(2), math::Sqrt(Fixed(2)));
    EXPECT_SAME(b2Atan2(1, -1), math::Atan2(Fixed(1), Fixed(-1)));
    // Integers stay integers, as with Box2D's templates.
    EXPECT_SAME(b2Max(n, 4), 4);
    EXPECT_SAME(b2Min(n, -4), -4);
    EXPECT_SAME(b2Abs(-n), 3);
    EXPECT_SAME(b2Clamp(n, 0, 2), 2);
}

}  // namespace LOCKBOX_TEST_FILE
