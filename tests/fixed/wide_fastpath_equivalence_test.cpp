// The 64-bit fast paths of detail::MulShiftRound64 and detail::DivShiftRound64 (Wide.h) must
// give the same bits and the same overflow reports as the 128-bit computation they shortcut.
// The references below are the pre-fast-path formulas, written on the portable S128 helpers;
// they are compared on edge values and on random operands spread over every magnitude.
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/fixed/Wide.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox::detail;

// Overflow reports are counted by the per-thread saturation counter (both builds); checked
// builds get a handler that returns, so the saturated value that follows can be compared.
void ReturningHandler(const char*, int64_t, int64_t) {}

struct Outcome {
    int64_t value;
    int reports;
    bool operator==(const Outcome&) const = default;
};

constexpr int64_t kMax = std::numeric_limits<int64_t>::max();

// round(a*b / 2^shift), ties away from zero, saturating to +-INT64_MAX: 128-bit reference.
Outcome RefMulShiftRound64(int64_t a, int64_t b, int shift) {
    const S128 p = MulS64(a, b);
    // Ties away from zero on the magnitude equals (p + half - (p < 0)) >> shift on the value.
    const S128 r = ShrRoundS128(p, shift);
    int reports = 0;
    int64_t v = 0;
    if (r.mag.hi != 0 || r.mag.lo > static_cast<uint64_t>(kMax)) {
        ++reports;
        v = r.negative ? -kMax : kMax;
    } else {
        v = r.negative ? -static_cast<int64_t>(r.mag.lo) : static_cast<int64_t>(r.mag.lo);
    }
    return {v, reports};
}

#ifdef __SIZEOF_INT128__
// The former native formula, verbatim in meaning: floor((p + half - (p < 0)) / 2^shift) on the
// signed 128-bit product, saturating to +-INT64_MAX by the sign of the result.
Outcome RefNativeMulShiftRound64(int64_t a, int64_t b, int shift) {
    __extension__ typedef __int128 I128;
    const I128 p = static_cast<I128>(a) * b;
    const I128 half = static_cast<I128>(1) << (shift - 1);
    const I128 r = (p + half - (p < 0 ? 1 : 0)) >> shift;
    if (r > kMax || r < -kMax) return {r > 0 ? kMax : -kMax, 1};
    return {static_cast<int64_t>(r), 0};
}
#else
Outcome RefNativeMulShiftRound64(int64_t a, int64_t b, int shift) { return RefMulShiftRound64(a, b, shift); }
#endif

// round(a * 2^shift / b), ties away from zero, saturating; b == 0 reports and saturates.
Outcome RefDivShiftRound64(int64_t a, int64_t b, int shift) {
    if (b == 0) return {a == 0 ? 0 : (a > 0 ? kMax : -kMax), 1};
    S128 n{a < 0, ShlU128(U128{0, AbsU64(a)}, shift)};
    const S128 d{b < 0, U128{0, AbsU64(b)}};
    const S128 q = DivRoundS128(n, d);
    if (q.mag.hi != 0 || q.mag.lo > static_cast<uint64_t>(kMax)) return {q.negative ? -kMax : kMax, 1};
    return {q.negative ? -static_cast<int64_t>(q.mag.lo) : static_cast<int64_t>(q.mag.lo), 0};
}

Outcome RunMul(int64_t a, int64_t b, int shift) {
    const uint64_t before = lockbox::SaturationCount();
    const int64_t v = MulShiftRound64(a, b, shift, "test");
    return {v, static_cast<int>(lockbox::SaturationCount() - before)};
}

Outcome RunDiv(int64_t a, int64_t b, int shift) {
    const uint64_t before = lockbox::SaturationCount();
    const int64_t v = DivShiftRound64(a, b, shift, "test");
    return {v, static_cast<int>(lockbox::SaturationCount() - before)};
}

// Values of every bit length, both signs, plus the boundaries around powers of two.
std::vector<int64_t> EdgeValues() {
    std::vector<int64_t> v = {0, 1, -1, 2, -2, 3, -3, kMax, -kMax, std::numeric_limits<int64_t>::min()};
    for (int k = 1; k < 63; ++k) {
        const int64_t p = int64_t{1} << k;
        for (int64_t x : {p - 1, p, p + 1, p + p / 2}) {
            v.push_back(x);
            v.push_back(-x);
        }
    }
    return v;
}

// A random value with a uniformly chosen bit length, so small and huge magnitudes both occur.
int64_t RandomMagnitude(std::mt19937_64& rng) {
    const int bits = static_cast<int>(rng() % 64);
    const uint64_t raw = rng();
    const uint64_t mag = bits == 0 ? 0 : (raw >> (64 - bits));
    const int64_t value = static_cast<int64_t>(mag >> 1);  // keep below 2^63
    return (rng() & 1) ? -value : value;
}

class WideFastPath : public ::testing::Test {
protected:
    void SetUp() override { previous_ = lockbox::SetOverflowTrapHandler(&ReturningHandler); }
    void TearDown() override { lockbox::SetOverflowTrapHandler(previous_); }

private:
    lockbox::OverflowTrapHandler previous_ = nullptr;
};

constexpr int kShifts[] = {1, 16, 31, 32, 48};

TEST_F(WideFastPath, MulShiftRoundMatchesThe128BitFormulaOnEdges) {
    const std::vector<int64_t> values = EdgeValues();
    for (int shift : kShifts) {
        for (int64_t a : values) {
            for (int64_t b : values) {
                ASSERT_EQ(RunMul(a, b, shift), RefMulShiftRound64(a, b, shift))
                    << "a=" << a << " b=" << b << " shift=" << shift;
                ASSERT_EQ(RunMul(a, b, shift), RefNativeMulShiftRound64(a, b, shift))
                    << "a=" << a << " b=" << b << " shift=" << shift;
            }
        }
    }
}

TEST_F(WideFastPath, MulShiftRoundMatchesThe128BitFormulaOnRandomOperands) {
    std::mt19937_64 rng(0x5eed'0001);
    for (int i = 0; i < 2'000'000; ++i) {
        const int64_t a = RandomMagnitude(rng);
        const int64_t b = RandomMagnitude(rng);
        const int shift = kShifts[i % 5];
        ASSERT_EQ(RunMul(a, b, shift), RefMulShiftRound64(a, b, shift))
            << "a=" << a << " b=" << b << " shift=" << shift;
        ASSERT_EQ(RunMul(a, b, shift), RefNativeMulShiftRound64(a, b, shift))
            << "a=" << a << " b=" << b << " shift=" << shift;
    }
}

TEST_F(WideFastPath, MulShiftRoundTiesRoundAwayFromZero) {
    // Exact ties around the fast path's int64 limit, where the bias add is the deciding step.
    for (int shift : kShifts) {
        const int64_t half = int64_t{1} << (shift - 1);
        for (int64_t p : {half, 3 * half, kMax - half, kMax - half + 1, kMax - 2 * half + 1}) {
            for (int64_t sign : {1, -1}) {
                ASSERT_EQ(RunMul(sign * p, 1, shift), RefMulShiftRound64(sign * p, 1, shift)) << p;
            }
        }
    }
}

TEST_F(WideFastPath, DivShiftRoundMatchesThe128BitFormulaOnEdges) {
    const std::vector<int64_t> values = EdgeValues();
    for (int shift : kShifts) {
        for (int64_t a : values) {
            for (int64_t b : values) {
                ASSERT_EQ(RunDiv(a, b, shift), RefDivShiftRound64(a, b, shift))
                    << "a=" << a << " b=" << b << " shift=" << shift;
            }
        }
    }
}

TEST_F(WideFastPath, DivShiftRoundMatchesThe128BitFormulaOnRandomOperands) {
    std::mt19937_64 rng(0x5eed'0002);
    for (int i = 0; i < 2'000'000; ++i) {
        const int64_t a = RandomMagnitude(rng);
        const int64_t b = RandomMagnitude(rng);
        const int shift = kShifts[i % 5];
        ASSERT_EQ(RunDiv(a, b, shift), RefDivShiftRound64(a, b, shift))
            << "a=" << a << " b=" << b << " shift=" << shift;
    }
}

TEST_F(WideFastPath, DivShiftRoundExactHalvesRoundAwayFromZero) {
    // d odd and num = d * k + (d - 1) / 2 or (d + 1) / 2: just below and at a tie.
    std::mt19937_64 rng(0x5eed'0003);
    for (int i = 0; i < 200'000; ++i) {
        const int64_t b = static_cast<int64_t>(rng() >> 34) | 1;  // odd, < 2^30
        const int64_t a = static_cast<int64_t>(rng() >> 33);
        for (int shift : {16, 32}) {
            for (int64_t sa : {a, -a}) {
                for (int64_t sb : {b, -b, 2 * b}) {
                    ASSERT_EQ(RunDiv(sa, sb, shift), RefDivShiftRound64(sa, sb, shift))
                        << "a=" << sa << " b=" << sb << " shift=" << shift;
                }
            }
        }
    }
}

// Wide::ToFixed before its fast path: clamp to +-2^62, round, narrow with saturation.
Outcome RefToFixed(int64_t raw) {
    constexpr int64_t kBiasRoom = int64_t{1} << 62;
    const int64_t r = raw >= kBiasRoom ? kBiasRoom : raw <= -kBiasRoom ? -kBiasRoom : raw;
    const int64_t v = ShiftRound(r, 16);
    constexpr int64_t kMax32 = std::numeric_limits<int32_t>::max();
    if (v > kMax32 || v < -kMax32) return {v > 0 ? kMax32 : -kMax32, 1};
    return {v, 0};
}

Outcome RunToFixed(int64_t raw) {
    const uint64_t before = lockbox::SaturationCount();
    const int64_t v = lockbox::Wide::FromRaw(raw).ToFixed().Raw();
    return {v, static_cast<int>(lockbox::SaturationCount() - before)};
}

TEST_F(WideFastPath, ToFixedMatchesTheClampedFormula) {
    const int64_t fit = (int64_t{std::numeric_limits<int32_t>::max()} << 16) + (int64_t{1} << 15) - 1;
    std::vector<int64_t> values = EdgeValues();
    for (int64_t d = -3; d <= 3; ++d) {
        values.push_back(fit + d);
        values.push_back(-fit + d);
        values.push_back((int64_t{1} << 62) + d);
        values.push_back(-(int64_t{1} << 62) + d);
    }
    for (int64_t raw : values) ASSERT_EQ(RunToFixed(raw), RefToFixed(raw)) << raw;
    std::mt19937_64 rng(0x5eed'0004);
    for (int i = 0; i < 2'000'000; ++i) {
        const int64_t raw = RandomMagnitude(rng);
        ASSERT_EQ(RunToFixed(raw), RefToFixed(raw)) << raw;
    }
}

// Wide + and - before the branch split: saturate when the exact sum leaves +-INT64_MAX.
Outcome RefAddSub(int64_t a, int64_t b, bool subtract) {
    const S128 sum = subtract ? SubS128(MulS64(a, 1), MulS64(b, 1)) : AddS128(MulS64(a, 1), MulS64(b, 1));
    if (sum.mag.hi != 0 || sum.mag.lo > static_cast<uint64_t>(kMax)) {
        const bool positive = subtract ? a >= 0 : a > 0;
        return {positive ? kMax : -kMax, 1};
    }
    return {sum.negative ? -static_cast<int64_t>(sum.mag.lo) : static_cast<int64_t>(sum.mag.lo), 0};
}

Outcome RunAddSub(int64_t a, int64_t b, bool subtract) {
    const uint64_t before = lockbox::SaturationCount();
    const lockbox::Wide x = lockbox::Wide::FromRaw(a), y = lockbox::Wide::FromRaw(b);
    const int64_t v = (subtract ? x - y : x + y).Raw();
    return {v, static_cast<int>(lockbox::SaturationCount() - before)};
}

TEST_F(WideFastPath, AddAndSubtractSaturateExactlyAsBefore) {
    const std::vector<int64_t> values = EdgeValues();
    for (int64_t a : values) {
        for (int64_t b : values) {
            ASSERT_EQ(RunAddSub(a, b, false), RefAddSub(a, b, false)) << a << " + " << b;
            ASSERT_EQ(RunAddSub(a, b, true), RefAddSub(a, b, true)) << a << " - " << b;
        }
    }
}

}  // namespace LOCKBOX_TEST_FILE
