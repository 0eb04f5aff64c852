// b2Rot, b2Transform and b2Sweep: identities, inverse round trips, interpolation end points,
// and that normalising a sweep keeps the relative angle exactly.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/fixed/Math.h"

using namespace lockbox;

TEST(Rot, IdentityAndAxes) {
    const b2Rot q;
    EXPECT_EQ(q.s, Fixed());
    EXPECT_EQ(q.c, Fixed(1));
    EXPECT_EQ(q.GetAngle(), Fixed());
    const b2Rot r(math::kHalfPi);
    EXPECT_EQ(r.s, Fixed(1));
    EXPECT_LE(std::abs(r.c.Raw()), 1);
    EXPECT_EQ(r.GetXAxis(), b2Vec2(r.c, r.s));
    EXPECT_EQ(r.GetYAxis(), b2Vec2(-r.s, r.c));
    EXPECT_EQ(r.GetAngle(), math::kHalfPi);
}

TEST(Rot, MulAndMulTRoundTrip) {
    std::mt19937 rng(31);
    for (int i = 0; i < 20000; ++i) {
        const b2Rot q(Fixed::FromRaw(static_cast<int32_t>(rng() % 411775) - 205887));
        const b2Vec2 v(Fixed::FromRaw(static_cast<int32_t>(rng() % 2000000) - 1000000),
                       Fixed::FromRaw(static_cast<int32_t>(rng() % 2000000) - 1000000));
        const b2Vec2 back = b2MulT(q, b2Mul(q, v));
        // Two roundings plus |q|^2 - 1, which is up to ~1.5 ULP relative (s and c are each
        // within 1 ULP): 2 ULP absolute plus 3 ULP per metre of |v|.
        const double bound = 2.0 + v.Length().Raw() * 3.0 / 65536.0;
        EXPECT_LE(std::abs(back.x.Raw() - v.x.Raw()), bound);
        EXPECT_LE(std::abs(back.y.Raw() - v.y.Raw()), bound);
        // Angle composition: q * q^T is the identity to within an ULP.
        const b2Rot id = b2MulT(q, q);
        EXPECT_LE(std::abs(id.s.Raw()), 1);
        EXPECT_LE(std::abs(id.c.Raw() - 65536), 2);
    }
}

TEST(Transform, MulTInvertsMul) {
    b2Transform xf;
    xf.Set(b2Vec2(Fixed(10), Fixed(-5)), Fixed(0.5));
    const b2Vec2 local(Fixed(1.25), Fixed(-0.75));
    const b2Vec2 world = b2Mul(xf, local);
    const b2Vec2 back = b2MulT(xf, world);
    EXPECT_LE(std::abs(back.x.Raw() - local.x.Raw()), 2);
    EXPECT_LE(std::abs(back.y.Raw() - local.y.Raw()), 2);
    const b2Transform id = b2MulT(xf, xf);
    EXPECT_EQ(id.p, b2Vec2());
    b2Transform t2;
    t2.Set(b2Vec2(Fixed(1), Fixed(2)), Fixed(-0.25));
    const b2Transform ab = b2Mul(xf, t2);
    const b2Vec2 p = b2Mul(ab, local), q = b2Mul(xf, b2Mul(t2, local));
    EXPECT_LE(std::abs(p.x.Raw() - q.x.Raw()), 3);
    EXPECT_LE(std::abs(p.y.Raw() - q.y.Raw()), 3);
    b2Transform identity;
    EXPECT_EQ(b2Mul(identity, local), local);
}

TEST(Transform, WholeMetreTranslationIsExact) {
    // Moving a frame by whole metres moves every transformed point by exactly that much.
    b2Transform xf;
    xf.Set(b2Vec2(Fixed(1.5), Fixed(2.25)), Fixed(0.3));
    const b2Vec2 local(Fixed(0.37), Fixed(-0.11));
    const b2Vec2 base = b2Mul(xf, local);
    for (int offset : {-15000, -1000, -1, 1, 7, 15000}) {
        b2Transform moved = xf;
        moved.p += b2Vec2(Fixed(offset), Fixed(-offset));
        const b2Vec2 w = b2Mul(moved, local);
        EXPECT_EQ(w - b2Vec2(Fixed(offset), Fixed(-offset)), base) << offset;
        EXPECT_EQ(b2MulT(moved, w), b2MulT(xf, base)) << offset;
    }
}

TEST(Sweep, EndpointsAreExactAndAdvanceMovesTheStart) {
    b2Sweep sweep;
    sweep.localCenter = b2Vec2(Fixed(0.5), Fixed(0));
    sweep.c0 = b2Vec2(Fixed(0), Fixed(0));
    sweep.c = b2Vec2(Fixed(2), Fixed(1));
    sweep.a0 = Fixed(0);
    sweep.a = Fixed(1);
    b2Transform xf0, xf1, xfHalf;
    sweep.GetTransform(&xf0, Fixed(0));
    sweep.GetTransform(&xf1, Fixed(1));
    sweep.GetTransform(&xfHalf, Fixed(0.5));
    EXPECT_EQ(xf0.p + b2Mul(xf0.q, sweep.localCenter), sweep.c0);
    EXPECT_LE(std::abs((xf1.p + b2Mul(xf1.q, sweep.localCenter) - sweep.c).x.Raw()), 1);
    EXPECT_EQ(xfHalf.q.GetAngle(), Fixed(0.5));
    sweep.Advance(Fixed(0.5));
    EXPECT_EQ(sweep.c0, b2Vec2(Fixed(1), Fixed(0.5)));
    EXPECT_EQ(sweep.a0, Fixed(0.5));
    EXPECT_EQ(sweep.alpha0, Fixed(0.5));
}

TEST(Sweep, NormalizeKeepsTheRelativeAngle) {
    for (int32_t a0raw : {-2000000, -411775, -1, 0, 411774, 411775, 9000000, -2147483000, 2147470000}) {
        b2Sweep s;
        s.a0 = Fixed::FromRaw(a0raw);
        s.a = Fixed::FromRaw(a0raw + 12345);
        s.Normalize();
        EXPECT_GE(s.a0.Raw(), 0);
        EXPECT_LT(s.a0.Raw(), 411775);
        EXPECT_EQ(s.a.Raw() - s.a0.Raw(), 12345);
        EXPECT_EQ((int64_t{a0raw} - s.a0.Raw()) % 411775, 0);
    }
}

// Near the ends of the range the whole turns below a0 pass the int32 range (-5216 turns of
// raw 411775 for a0 = INT32_MIN): the shift is computed in 64 bits (no overflow, no UB), a0
// still lands in [0, 2*pi), and an end angle pushed past the range saturates like any Fixed
// subtraction. Found by the restore fuzzer (an accepted image with such an angle, then a TOI).
TEST(Sweep, NormalizeAtTheEndsOfTheRange) {
    // Saturations are expected here: checked builds report them to a handler that returns.
    const lockbox::OverflowTrapHandler previous = lockbox::SetOverflowTrapHandler([](const char*, int64_t, int64_t) {});
    const int32_t lowest = std::numeric_limits<int32_t>::min();
    const int32_t highest = std::numeric_limits<int32_t>::max();
    for (int32_t a0raw : {lowest, lowest + 1, lowest + 411775, highest, highest - 1}) {
        for (int32_t araw : {a0raw, lowest, highest, 0}) {
            b2Sweep s;
            s.a0 = Fixed::FromRaw(a0raw);
            s.a = Fixed::FromRaw(araw);
            s.Normalize();
            ASSERT_GE(s.a0.Raw(), 0) << a0raw;
            ASSERT_LT(s.a0.Raw(), 411775) << a0raw;
            const int64_t shift = int64_t{a0raw} - s.a0.Raw();
            EXPECT_EQ(shift % 411775, 0) << a0raw;
            const int64_t exact = int64_t{araw} - shift;
            const int64_t expected = exact > highest ? highest : exact < -int64_t{highest} ? -int64_t{highest} : exact;
            EXPECT_EQ(s.a.Raw(), expected) << a0raw << " " << araw;
        }
    }
    lockbox::SetOverflowTrapHandler(previous);
}
