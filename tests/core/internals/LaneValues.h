#pragma once
// Random raws for the lane tests: mostly of a game's magnitudes, sometimes anywhere in their
// type's range (where the scalar rows saturate and the lanes must hand the row back), at the
// edges of the lanes' bounds, or coarse (whole multiples of a power of two, as FromRatio's often
// are), which reach the roundings' ties.

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Overflow.h"
#include "lockbox/fixed/Wide.h"

namespace lockbox::test {

// The rows saturate on purpose: a checked build, which traps on overflow, is told to go on with
// the saturated result (and still counts it) while this is alive.
struct QuietTraps {
    OverflowTrapHandler previous = SetOverflowTrapHandler([](const char*, int64_t, int64_t) {});
    ~QuietTraps() { SetOverflowTrapHandler(previous); }
};

class LaneValues {
public:
    explicit LaneValues(uint64_t seed) : m_rng(seed) {}

    int Pick(int n) { return static_cast<int>(m_rng() % static_cast<uint64_t>(n)); }
    double Uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(m_rng); }

    // A Q32.32 raw of about `typical` in magnitude, or one of the other kinds above.
    int64_t WideRaw(double typical) {
        const int kind = Pick(20);
        if (kind == 0) return static_cast<int64_t>(m_rng());  // anywhere
        if (kind == 1) {  // near the top, either sign (~x is -x - 1: no overflow at 2^63)
            const uint64_t bits = m_rng() >> Pick(8);
            return Pick(2) == 0 ? static_cast<int64_t>(bits) : static_cast<int64_t>(~bits);
        }
        if (kind == 2) return 0;
        const auto raw = static_cast<int64_t>(Uniform(-typical, typical) * 4294967296.0);
        if (kind == 3) return raw & ~((int64_t{1} << (12 + Pick(20))) - 1);
        return raw;
    }
    Wide WideValue(double typical) { return Wide::FromRaw(WideRaw(typical)); }
    // A positive Q32.32 value in [lo, hi).
    Wide Positive(double lo, double hi) { return Wide::FromRaw(static_cast<int64_t>(Uniform(lo, hi) * 4294967296.0)); }
    // A Q16.16 value of about `typical` in magnitude, at the edges of the type and of the lanes'
    // arms (2^30 raw), or coarse.
    Fixed FixedValue(double typical) {
        const int kind = Pick(25);
        if (kind == 0) return Fixed::FromRaw(static_cast<int32_t>(m_rng()));
        if (kind <= 2) {
            constexpr int32_t kEdges[] = {INT32_MIN, INT32_MAX, -(int32_t{1} << 30), (int32_t{1} << 30) - 1};
            return Fixed::FromRaw(kEdges[Pick(4)]);
        }
        const auto raw = static_cast<int32_t>(Uniform(-typical, typical) * 65536.0);
        if (kind == 3) return Fixed::FromRaw(raw & ~((int32_t{1} << (4 + Pick(10))) - 1));
        return Fixed::FromRaw(raw);
    }

    // Places that cut a colour of `count` rows into ranges, as workers' blocks cut it: random,
    // most not on a multiple of four.
    std::vector<int32_t> Cuts(int32_t count) {
        std::vector<int32_t> cuts;
        for (int32_t at = Pick(9) + 1; at < count; at += Pick(61) + 1) cuts.push_back(at);
        return cuts;
    }

private:
    std::mt19937_64 m_rng;
};

// Whether two solves left every body with the same velocity (the first body that differs, if not).
inline ::testing::AssertionResult SameVelocities(const std::vector<b2Velocity>& a, const std::vector<b2Velocity>& b) {
    if (a.size() != b.size()) return ::testing::AssertionFailure() << "body counts " << a.size() << ", " << b.size();
    for (size_t i = 0; i < a.size(); ++i) {
        if (a[i].v.x != b[i].v.x || a[i].v.y != b[i].v.y || a[i].w != b[i].w)
            return ::testing::AssertionFailure() << "body " << i;
    }
    return ::testing::AssertionSuccess();
}

}  // namespace lockbox::test
