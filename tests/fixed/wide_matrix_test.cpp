// The joints' exact matrix division (WideMatrix.h) at the edge of its 128-bit range: a
// numerator of 127 or 128 bits (found by the snapshot-restore fuzzer through a prismatic joint
// between bodies with extreme restored values) must divide correctly instead of shifting by a
// negative count. And the native 128-bit paths of the joint solvers' hot loops (b2Cross of an
// arm and an impulse, the prepared 2x2 solve, the shifted division) against the portable
// limbs: the same bits and the same overflow reports on random and extreme inputs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "lockbox/fixed/Overflow.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using detail::S128;
using detail::U128;

TEST(WideMatrixDivShift, NumeratorOf128BitsDividesWithoutANegativeShift) {
    // n = 2^127 + 2^126 (128 bits), d = 2^127: n / d = 1.5, times 2^32.
    const S128 n{false, U128{(uint64_t{1} << 63) | (uint64_t{1} << 62), 0}};
    const S128 d{false, U128{uint64_t{1} << 63, 0}};
    EXPECT_EQ(detail::DivShiftS128(n, d, 32, "test"), int64_t{3} << 31);
    const S128 negative{true, n.mag};
    EXPECT_EQ(detail::DivShiftS128(negative, d, 32, "test"), -(int64_t{3} << 31));
}

TEST(WideMatrixDivShift, NumeratorOf127BitsDividesWithoutANegativeShift) {
    // n = 2^126 + 2^124 (127 bits), d = 2^126: 1.25 * 2^20.
    const S128 n{false, U128{(uint64_t{1} << 62) | (uint64_t{1} << 60), 0}};
    const S128 d{false, U128{uint64_t{1} << 62, 0}};
    EXPECT_EQ(detail::DivShiftS128(n, d, 20, "test"), (int64_t{5} << 18));
}

TEST(WideMatrixDivShift, OrdinaryValuesAreUnchanged) {
    // 3 / 4 in Q32.32.
    const S128 n{false, U128{0, 3}};
    const S128 d{false, U128{0, 4}};
    EXPECT_EQ(detail::DivShiftS128(n, d, 32, "test"), int64_t{3} << 30);
}

// Counts overflow reports in both build kinds: the checked build calls the handler (which
// returns, accepting the saturation), the default build counts saturations.
int g_trapped = 0;
uint64_t Reports() { return SaturationCount() + static_cast<uint64_t>(g_trapped); }

class NativeWide : public ::testing::Test {
protected:
    void SetUp() override {
        previous_ = SetOverflowTrapHandler([](const char*, int64_t, int64_t) { ++g_trapped; });
    }
    void TearDown() override { SetOverflowTrapHandler(previous_); }

    // A raw of a random bit width (0..bits), random sign, now and then an extreme.
    int64_t Raw(int bits) {
        const uint64_t pick = rng_() % 64;
        if (pick == 0) return bits >= 63 ? INT64_MAX : (int64_t{1} << bits) - 1;
        if (pick == 1) return bits >= 63 ? -INT64_MAX : -((int64_t{1} << bits) - 1);
        if (pick == 2) return 0;
        const int width = static_cast<int>(rng_() % static_cast<uint64_t>(bits + 1));
        const uint64_t mask = width >= 63 ? static_cast<uint64_t>(INT64_MAX) : (uint64_t{1} << width) - 1;
        const auto v = static_cast<int64_t>(rng_() & mask);
        return (rng_() & 1) != 0 ? -v : v;
    }

    std::mt19937_64 rng_{20261125};
    OverflowTrapHandler previous_ = nullptr;
};

TEST_F(NativeWide, CrossOfArmAndImpulseMatchesThePortableLimbs) {
    for (int i = 0; i < 300000; ++i) {
        const b2Vec2 r(Fixed::FromRaw(static_cast<int32_t>(Raw(31))), Fixed::FromRaw(static_cast<int32_t>(Raw(31))));
        const b2WideVec2 p(Wide::FromRaw(Raw(63)), Wide::FromRaw(Raw(63)));
        const uint64_t before = Reports();
        const int64_t got = b2Cross(r, p).Raw();
        const uint64_t gotReports = Reports() - before;
        const int64_t want = detail::CrossArmImpulseRaw(r.x.Raw(), r.y.Raw(), p.x.Raw(), p.y.Raw(), "test");
        ASSERT_EQ(got, want) << r.x.Raw() << " " << r.y.Raw() << " " << p.x.Raw() << " " << p.y.Raw();
        ASSERT_EQ(gotReports, Reports() - before - gotReports);
    }
}

TEST_F(NativeWide, PreparedSolveMatchesThePortableLimbs) {
    int singular = 0;
    for (int i = 0; i < 300000; ++i) {
        const int bits = static_cast<int>(rng_() % 64);
        b2WideVec2 ex(Wide::FromRaw(Raw(bits)), Wide::FromRaw(Raw(bits)));
        b2WideVec2 ey(Wide::FromRaw(Raw(bits)), Wide::FromRaw(Raw(bits)));
        if (i % 50 == 0) ey = ex;  // singular: x = 0
        const b2WideSolver22 k(ex, ey);
        singular += detail::IsZero(k.det) ? 1 : 0;
        // The determinant the constructor computed equals the limbs' exact one.
        const detail::S128 limbDet = detail::SubS128(detail::MulS64(k.a11, k.a22), detail::MulS64(k.a12, k.a21));
        ASSERT_EQ(k.det.negative, limbDet.negative);
        ASSERT_EQ(k.det.mag.hi, limbDet.mag.hi);
        ASSERT_EQ(k.det.mag.lo, limbDet.mag.lo);
        const b2WideVec2 b(Wide::FromRaw(Raw(63)), Wide::FromRaw(Raw(63)));
        const uint64_t before = Reports();
        const b2WideVec2 got = k.Solve(b);
        const uint64_t gotReports = Reports() - before;
        const b2WideVec2 want = k.SolvePortable(b);
        ASSERT_EQ(got.x.Raw(), want.x.Raw()) << i;
        ASSERT_EQ(got.y.Raw(), want.y.Raw()) << i;
        ASSERT_EQ(gotReports, Reports() - before - gotReports) << i;
    }
    EXPECT_GT(singular, 6000);
}

TEST_F(NativeWide, Prepared3x3SolveMatchesThePortableLimbs) {
    int native = 0;
    for (int i = 0; i < 200000; ++i) {
        const int bits = static_cast<int>(rng_() % 64);
        auto col = [&]() {
            return b2WideVec3(Wide::FromRaw(Raw(bits)), Wide::FromRaw(Raw(bits)), Wide::FromRaw(Raw(bits)));
        };
        const b2WideVec3 ex = col(), ey = col();
        const b2WideVec3 ez = i % 50 == 0 ? ex : col();  // singular now and then
        const b2WideSolver33 k(ex, ey, ez);
        {
            // The determinant the constructor computed equals the limbs' exact c0 . (c1 x c2).
            using namespace detail;
            const int64_t* m = k.m;
            const S128 cx = SubS128(MulS64(m[4], m[8]), MulS64(m[5], m[7]));
            const S128 cy = SubS128(MulS64(m[5], m[6]), MulS64(m[3], m[8]));
            const S128 cz = SubS128(MulS64(m[3], m[7]), MulS64(m[4], m[6]));
            const S128 limbDet = AddS128(AddS128(MulS128S64(cx, m[0]), MulS128S64(cy, m[1])), MulS128S64(cz, m[2]));
            ASSERT_EQ(k.det.negative, limbDet.negative) << i;
            ASSERT_EQ(k.det.mag.hi, limbDet.mag.hi) << i;
            ASSERT_EQ(k.det.mag.lo, limbDet.mag.lo) << i;
        }
        // Mostly Q16.16-range right-hand sides (the native path), some beyond (the limbs).
        const int rhsBits = i % 10 == 0 ? 63 : 47;
        const b2WideVec3 b(Wide::FromRaw(Raw(rhsBits)), Wide::FromRaw(Raw(rhsBits)), Wide::FromRaw(Raw(rhsBits)));
        native += rhsBits == 47 ? 1 : 0;
        const uint64_t before = Reports();
        const b2WideVec3 got = k.Solve33(b);
        const uint64_t gotReports = Reports() - before;
        const b2WideVec3 want = k.Solve33Portable(b);
        ASSERT_EQ(got.x.Raw(), want.x.Raw()) << i;
        ASSERT_EQ(got.y.Raw(), want.y.Raw()) << i;
        ASSERT_EQ(got.z.Raw(), want.z.Raw()) << i;
        ASSERT_EQ(gotReports, Reports() - before - gotReports) << i;
    }
    EXPECT_GT(native, 150000);
}

// The inverse shares one division between the two off-diagonal entries of a symmetric K. It
// must give the bits and the overflow reports of two full solves, on symmetric and general
// matrices from tiny to extreme (where entries saturate), and SolveY those of Solve's y.
TEST_F(NativeWide, InverseMatchesTwoSolves) {
    int symmetric = 0, saturated = 0;
    for (int i = 0; i < 300000; ++i) {
        const int bits = static_cast<int>(rng_() % 64);
        const Wide a11 = Wide::FromRaw(Raw(bits)), a22 = Wide::FromRaw(Raw(bits));
        const Wide a21 = Wide::FromRaw(Raw(bits));
        const Wide a12 = i % 4 == 0 ? Wide::FromRaw(Raw(bits)) : a21;
        const b2WideSolver22 k({a11, a21}, {a12, a22});
        symmetric += k.a12 == k.a21 ? 1 : 0;

        uint64_t before = Reports();
        const b2WideMat22 got = math::Inverse(k);
        const uint64_t gotReports = Reports() - before;
        before = Reports();
        const b2WideVec2 ex = k.SolvePortable(b2WideVec2(Wide(1), Wide()));
        const b2WideVec2 ey = k.SolvePortable(b2WideVec2(Wide(), Wide(1)));
        const uint64_t wantReports = Reports() - before;
        ASSERT_EQ(got.ex.x.Raw(), ex.x.Raw()) << i;
        ASSERT_EQ(got.ex.y.Raw(), ex.y.Raw()) << i;
        ASSERT_EQ(got.ey.x.Raw(), ey.x.Raw()) << i;
        ASSERT_EQ(got.ey.y.Raw(), ey.y.Raw()) << i;
        ASSERT_EQ(gotReports, wantReports) << i;
        saturated += wantReports > 0 ? 1 : 0;

        const b2WideVec2 b(Wide::FromRaw(Raw(63)), Wide::FromRaw(Raw(63)));
        before = Reports();
        const Wide y = k.SolveY(b);
        const uint64_t yReports = Reports() - before;
        before = Reports();
        const b2WideVec2 full = k.SolvePortable(b);
        const uint64_t fullReports = Reports() - before;
        ASSERT_EQ(y.Raw(), full.y.Raw()) << i;
        // The full solve reports for x as well; SolveY never reports more than it.
        ASSERT_LE(yReports, fullReports) << i;
    }
    EXPECT_GT(symmetric, 200000);
    EXPECT_GT(saturated, 1000);
}

TEST_F(NativeWide, NormalisingScaleRoundsLikeThe128BitShift) {
    for (int i = 0; i < 300000; ++i) {
        const int64_t raw = i % 1000 == 0 ? (i % 2000 == 0 ? INT64_MAX : -INT64_MAX) : Raw(63);
        const int s = 1 + static_cast<int>(rng_() % 33);  // up to 64 - kNormBits22
        ASSERT_EQ(detail::ScaleRaw(raw, s), detail::ToS64(detail::ShrRoundS128(detail::MulS64(raw, 1), s)))
            << raw << " " << s;
    }
}

#ifdef LOCKBOX_NATIVE_INT128
TEST_F(NativeWide, ShiftedDivisionMatchesThePortableLimbs) {
    using detail::NativeI128;
    using detail::NativeU128;
    auto wide = [&](int bits) {
        // A value of up to `bits` (<= 127) magnitude bits.
        NativeU128 m = (static_cast<NativeU128>(rng_()) << 64) | rng_();
        m &= bits >= 128 ? ~NativeU128{0} : (NativeU128{1} << bits) - 1;
        if (bits == 127) m &= ~(NativeU128{1} << 127);
        const auto v = static_cast<NativeI128>(m);
        return (rng_() & 1) != 0 ? -v : v;
    };
    auto toS128 = [](NativeI128 v) {
        const NativeU128 m = detail::MagnitudeU128(v);
        return S128{v < 0, U128{static_cast<uint64_t>(m >> 64), static_cast<uint64_t>(m)}};
    };
    for (int i = 0; i < 300000; ++i) {
        const NativeI128 n = wide(static_cast<int>(rng_() % 128));
        const NativeI128 d = i % 97 == 0 ? NativeI128{0} : wide(static_cast<int>(rng_() % 128));
        const int shift = static_cast<int>(rng_() % 100);
        const uint64_t before = Reports();
        const int64_t got = detail::DivShiftNative(n, d, shift, "test");
        const uint64_t gotReports = Reports() - before;
        const int64_t want = detail::DivShiftS128(toS128(n), toS128(d), shift, "test");
        ASSERT_EQ(got, want) << i;
        ASSERT_EQ(gotReports, Reports() - before - gotReports) << i;
    }
}

// The 2x2 solves' one-division path must give the general path's bits at its edges: n << shift
// of 125, 126 and 127 bits, quotients just below and above 2^64, zero and extreme divisors.
TEST_F(NativeWide, SmallDivisorDivisionMatchesThePortableLimbs) {
    int fast = 0;
    for (int i = 0; i < 300000; ++i) {
        const int shift = static_cast<int>(rng_() % 70) - 3;
        // A divisor of 0..63 bits, or exactly 2^63 (the largest a normalised determinant reaches).
        const int dBits = static_cast<int>(rng_() % 65);
        uint64_t dMag = uint64_t{1} << 63;
        if (dBits < 64) dMag = dBits == 0 ? 0 : (rng_() >> (64 - dBits)) | (uint64_t{1} << (dBits - 1));
        const bool dNegative = (rng_() & 1) != 0;
        // Numerators near the 126-bit edge for this shift, or of any width below 2^95.
        const int width =
            i % 3 == 0 ? std::clamp(125 - shift + static_cast<int>(rng_() % 3), 0, 95) : static_cast<int>(rng_() % 96);
        detail::NativeU128 nm = 0;
        if (width > 0) {
            nm = (static_cast<detail::NativeU128>(rng_()) << 64 | rng_()) >> (128 - width);
            nm |= static_cast<detail::NativeU128>(1) << (width - 1);
        }
        const auto n = (rng_() & 1) != 0 ? -static_cast<detail::NativeI128>(nm) : static_cast<detail::NativeI128>(nm);
        const uint64_t before = Reports();
        const int64_t got = detail::DivShiftNative64(n, dMag, dNegative, shift, "test");
        const uint64_t gotReports = Reports() - before;
        const detail::S128 d{dNegative && dMag != 0, detail::U128{0, dMag}};
        const int64_t want = detail::DivShiftS128(detail::FromNative(n), d, shift, "test");
        ASSERT_EQ(got, want) << i << " shift " << shift << " width " << width << " d " << dMag;
        ASSERT_EQ(gotReports, Reports() - before - gotReports) << i;
        fast += shift >= 0 && shift <= 63 && width + shift <= 126 && dMag != 0 ? 1 : 0;
    }
    EXPECT_GT(fast, 100000);
}
#endif

// The inverse that the revolute, prismatic and weld point iterations multiply by: each entry
// must be K^-1's entry to the prepared solve's precision (K normalised to 36 significant bits,
// so a relative 1.5e-11 per entry, amplified by K's condition number), checked against double
// arithmetic (test-only) on effective-mass matrices from light to heavy bodies; a singular K
// must give zero, as the solve does.
TEST(WideMatrixInverse, EntriesAreTheInverseRounded) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> mass(0.01, 50.0), arm(-2.0, 2.0);
    for (int i = 0; i < 20000; ++i) {
        // K = m I + i [ry^2, -rx ry; -rx ry, rx^2] for a body pinned at r: symmetric, positive.
        const double m = mass(rng), inertia = mass(rng), rx = arm(rng), ry = arm(rng);
        const double k11 = m + inertia * ry * ry, k12 = -inertia * rx * ry, k22 = m + inertia * rx * rx;
        auto w = [](double v) { return Wide::FromRaw(static_cast<int64_t>(v * 4294967296.0)); };
        const b2WideMat22 K{{w(k11), w(k12)}, {w(k12), w(k22)}};
        const b2WideMat22 M = math::Inverse(K.Prepared());
        // The exact inverse of the matrix as rounded into Q32.32.
        const double a = K.ex.x.ToDouble(), b = K.ey.x.ToDouble(), c = K.ex.y.ToDouble(), d = K.ey.y.ToDouble();
        const double det = a * d - b * c;
        const double expect[4] = {d / det, -c / det, -b / det, a / det};
        const Wide got[4] = {M.ex.x, M.ex.y, M.ey.x, M.ey.y};
        const double norm = std::abs(a) + std::abs(b) + std::abs(c) + std::abs(d);
        const double condition = norm * norm / std::abs(det);
        // Normalising rounds each entry of K by up to 2^-kNormBits22 of the largest. A change dK
        // moves the inverse by K^-1 dK K^-1, so every entry's error is bounded by the inverse's
        // largest entry times the condition number times that rounding (and a small factor).
        const double entryError = 3.0 * std::ldexp(1.0, -detail::kNormBits22);
        double largest = 0;
        for (const double v : expect) largest = std::max(largest, std::abs(v));
        for (int e = 0; e < 4; ++e) {
            const double tolerance = 1.5 + largest * 4294967296.0 * entryError * condition;
            ASSERT_NEAR(static_cast<double>(got[e].Raw()), expect[e] * 4294967296.0, tolerance)
                << "case " << i << " entry " << e;
        }
        EXPECT_EQ(M.ex.y, M.ey.x) << "a symmetric K has a symmetric inverse, bit for bit";
    }
}

TEST(WideMatrixInverse, SingularMatrixGivesZero) {
    const b2WideMat22 K{{Wide(2), Wide(4)}, {Wide(1), Wide(2)}};  // columns parallel: det 0
    const b2WideMat22 M = math::Inverse(K.Prepared());
    EXPECT_EQ(M.ex.x, Wide());
    EXPECT_EQ(M.ex.y, Wide());
    EXPECT_EQ(M.ey.x, Wide());
    EXPECT_EQ(M.ey.y, Wide());
}

TEST(WideMatrixInverse, ProductAppliesTheInverse) {
    // K = diag(2, 4) (1/kg): its inverse halves and quarters, exactly.
    const b2WideMat22 K{{Wide(2), Wide()}, {Wide(), Wide(4)}};
    const b2WideMat22 M = math::Inverse(K.Prepared());
    const b2WideVec2 x = math::Mul(M, b2Vec2(Fixed(3), Fixed(-1)));
    EXPECT_EQ(x.x, Wide(1.5));
    EXPECT_EQ(x.y, Wide(-0.25));
    const b2WideVec2 y = math::Mul(M, b2WideVec2(Wide(-3), Wide(1)));
    EXPECT_EQ(y.x, Wide(-1.5));
    EXPECT_EQ(y.y, Wide(0.25));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
