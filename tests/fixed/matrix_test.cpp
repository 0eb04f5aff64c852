// b2Mat22/b2Mat33 solves and inverses against long double references over the magnitudes the
// joints meet (NUMERICS Table 1), and the portable 128-bit helpers against native __int128.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/fixed/Mat22.h"
#include "lockbox/fixed/Mat33.h"

using lockbox::b2Mat22;
using lockbox::b2Mat33;
using lockbox::b2Vec2;
using lockbox::b2Vec3;
using lockbox::Fixed;

namespace LOCKBOX_TEST_FILE {
long double D(Fixed f) { return static_cast<long double>(f.Raw()) / 65536.0L; }

Fixed RandomFixed(std::mt19937_64& rng, double lo, double hi) {
    // Log-uniform magnitude in [lo, hi], random sign.
    const double u = static_cast<double>(rng() % 1000000) / 1e6;
    const double mag = lo * std::pow(hi / lo, u);
    return Fixed::FromDoubleNondeterministic((rng() & 1) ? mag : -mag);
}

TEST(Mat22, SolveMatchesReferenceWithinHalfUlpOfTheRoundedInputs) {
    std::mt19937_64 rng(21);
    int checked = 0;
    for (int i = 0; i < 50000; ++i) {
        const b2Mat22 A(RandomFixed(rng, 1e-3, 1e3), RandomFixed(rng, 1e-3, 1e3), RandomFixed(rng, 1e-3, 1e3),
                        RandomFixed(rng, 1e-3, 1e3));
        const b2Vec2 b(RandomFixed(rng, 1e-3, 1e2), RandomFixed(rng, 1e-3, 1e2));
        const long double a11 = D(A.ex.x), a12 = D(A.ey.x), a21 = D(A.ex.y), a22 = D(A.ey.y);
        const long double det = a11 * a22 - a12 * a21;
        if (det == 0) continue;
        const long double x = (a22 * D(b.x) - a12 * D(b.y)) / det;
        const long double y = (a11 * D(b.y) - a21 * D(b.x)) / det;
        if (std::fabs(x) > 30000 || std::fabs(y) > 30000) continue;
        ++checked;
        const b2Vec2 s = A.Solve(b);
        // Exact integers in, one rounding out: within half an ULP of the exact quotient.
        ASSERT_LE(std::fabs(D(s.x) - x) * 65536.0L, 0.5L + 1e-6L);
        ASSERT_LE(std::fabs(D(s.y) - y) * 65536.0L, 0.5L + 1e-6L);
    }
    EXPECT_GT(checked, 30000);
}

TEST(Mat22, InverseAndSingular) {
    const b2Mat22 A(Fixed(2), Fixed(0), Fixed(0), Fixed(4));
    const b2Mat22 inv = A.GetInverse();
    EXPECT_EQ(inv.ex.x, Fixed(0.5));
    EXPECT_EQ(inv.ey.y, Fixed(0.25));
    EXPECT_EQ(inv.ey.x, Fixed());
    const b2Mat22 singular(Fixed(1), Fixed(2), Fixed(2), Fixed(4));
    EXPECT_EQ(singular.Solve(b2Vec2(Fixed(1), Fixed(1))), b2Vec2());
    const b2Mat22 zi = singular.GetInverse();
    EXPECT_EQ(zi.ex, b2Vec2());
    EXPECT_EQ(zi.ey, b2Vec2());
    b2Mat22 I;
    I.SetIdentity();
    EXPECT_EQ(lockbox::b2Mul(I, b2Vec2(Fixed(3), Fixed(-7))), b2Vec2(Fixed(3), Fixed(-7)));
    EXPECT_EQ(lockbox::b2MulT(A, b2Vec2(Fixed(1), Fixed(1))), b2Vec2(Fixed(2), Fixed(4)));
}

TEST(Mat33, Solve33AndSymInverseMatchReference) {
    std::mt19937_64 rng(22);
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
        // Symmetric positive-definite-ish matrices like the joints' K (diagonal dominant).
        const Fixed d1 = lockbox::math::Abs(RandomFixed(rng, 1e-2, 1e3)) + Fixed(0.01),
                    d2 = lockbox::math::Abs(RandomFixed(rng, 1e-2, 1e3)) + Fixed(0.01),
                    d3 = lockbox::math::Abs(RandomFixed(rng, 1e-2, 1e3)) + Fixed(0.01);
        const Fixed o12 = RandomFixed(rng, 1e-3, 1.0) * lockbox::math::Min(d1, d2),
                    o13 = RandomFixed(rng, 1e-3, 1.0) * lockbox::math::Min(d1, d3) * Fixed(0.5),
                    o23 = RandomFixed(rng, 1e-3, 1.0) * lockbox::math::Min(d2, d3) * Fixed(0.5);
        b2Mat33 K(b2Vec3(d1, o12, o13), b2Vec3(o12, d2, o23), b2Vec3(o13, o23, d3));
        const b2Vec3 b(RandomFixed(rng, 1e-3, 10), RandomFixed(rng, 1e-3, 10), RandomFixed(rng, 1e-3, 10));
        long double m[3][3] = {{D(d1), D(o12), D(o13)}, {D(o12), D(d2), D(o23)}, {D(o13), D(o23), D(d3)}};
        const long double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                                m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                                m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        if (det == 0) continue;
        const long double bx = D(b.x), by = D(b.y), bz = D(b.z);
        const long double x = (bx * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (by * m[2][2] - m[1][2] * bz) +
                               m[0][2] * (by * m[2][1] - m[1][1] * bz)) /
                              det;
        if (std::fabs(x) > 30000) continue;
        ++checked;
        const b2Vec3 s = K.Solve33(b);
        ASSERT_LE(std::fabs(D(s.x) - x) * 65536.0L, 0.5L + 1e-6L);
        b2Mat33 inv;
        K.GetSymInverse33(&inv);
        const long double inv11 = (m[1][1] * m[2][2] - m[1][2] * m[1][2]) / det;
        if (std::fabs(inv11) < 30000) {
            ASSERT_LE(std::fabs(D(inv.ex.x) - inv11) * 65536.0L, 0.5L + 1e-6L);
        }
        EXPECT_EQ(inv.ey.x, inv.ex.y);
        EXPECT_EQ(inv.ez.x, inv.ex.z);
        EXPECT_EQ(inv.ez.y, inv.ey.z);
    }
    EXPECT_GT(checked, 15000);
}

TEST(Mat33, Solve22AndInverse22) {
    b2Mat33 K(b2Vec3(Fixed(2), Fixed(0), Fixed(9)), b2Vec3(Fixed(0), Fixed(8), Fixed(9)),
              b2Vec3(Fixed(9), Fixed(9), Fixed(9)));
    EXPECT_EQ(K.Solve22(b2Vec2(Fixed(1), Fixed(1))), b2Vec2(Fixed(0.5), Fixed(0.125)));
    b2Mat33 inv;
    K.GetInverse22(&inv);
    EXPECT_EQ(inv.ex, b2Vec3(Fixed(0.5), Fixed(0), Fixed(0)));
    EXPECT_EQ(inv.ey, b2Vec3(Fixed(0), Fixed(0.125), Fixed(0)));
    EXPECT_EQ(inv.ez, b2Vec3());
    EXPECT_EQ(lockbox::b2Mul(K, b2Vec3(Fixed(1), Fixed(0), Fixed(0))), b2Vec3(Fixed(2), Fixed(0), Fixed(9)));
    EXPECT_EQ(lockbox::b2Dot(b2Vec3(Fixed(1), Fixed(2), Fixed(3)), b2Vec3(Fixed(4), Fixed(5), Fixed(6))), Fixed(32));
    EXPECT_EQ(lockbox::b2Cross(b2Vec3(Fixed(1), Fixed(0), Fixed(0)), b2Vec3(Fixed(0), Fixed(1), Fixed(0))),
              b2Vec3(Fixed(0), Fixed(0), Fixed(1)));
}

#if defined(__SIZEOF_INT128__)
TEST(Int128, PortableLimbsAgreeWithNative) {
    // The portable helpers are what i686 runs; check them against the compiler's __int128 here.
    namespace d = lockbox::detail;
    std::mt19937_64 rng(23);
    __extension__ typedef unsigned __int128 u128;
    for (int i = 0; i < 200000; ++i) {
        const uint64_t a = rng() >> (rng() % 64), b = rng() >> (rng() % 64);
        const u128 p = static_cast<u128>(a) * b;
        // Re-implement the limb product as the portable build does.
        const uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
        const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
        const uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
        const uint64_t lo = (mid << 32) | (p00 & 0xFFFFFFFFu);
        const uint64_t hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
        ASSERT_EQ(lo, static_cast<uint64_t>(p));
        ASSERT_EQ(hi, static_cast<uint64_t>(p >> 64));
        const d::U128 m = d::MulU64(a, b);
        ASSERT_EQ(m.lo, lo);
        ASSERT_EQ(m.hi, hi);
        if (b != 0) {
            const d::DivModU128Result qr = d::DivModU128(m, d::U128{0, b | 1});
            ASSERT_EQ(qr.quot.lo, static_cast<uint64_t>(p / (b | 1)));
            ASSERT_EQ(qr.quot.hi, static_cast<uint64_t>((p / (b | 1)) >> 64));
        }
    }
}
#endif

}  // namespace LOCKBOX_TEST_FILE
