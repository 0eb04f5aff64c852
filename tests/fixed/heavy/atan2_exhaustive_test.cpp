// Atan2Raw against long double atan2l: circles of radius 1e-3 .. 2e4 m with 2^20 angles each,
// and 1e7 log-uniform random (y, x) pairs with random signs (fixed mt19937_64 seeds).
// Gate: max error <= 1 ULP. The correctly rounded share is printed.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/fixed/detail/Trig.h"

namespace LOCKBOX_TEST_FILE {

constexpr long double kPiL = 3.14159265358979323846264338327950288L;

struct Stats {
    long double max_err = 0, sum = 0;
    uint64_t count = 0, not_cr = 0;
    int32_t worst_y = 0, worst_x = 0;
    void Add(int32_t y, int32_t x) {
        const long double ref =
            (y == 0 && x == 0) ? 0.0L : std::atan2(static_cast<long double>(y), static_cast<long double>(x)) * 65536.0L;
        const long double e = std::fabs(static_cast<long double>(lockbox::detail::Atan2Raw(y, x)) - ref);
        if (e > max_err) {
            max_err = e;
            worst_y = y;
            worst_x = x;
        }
        sum += e;
        ++count;
        not_cr += e > 0.5L ? 1 : 0;
    }
    void Merge(const Stats& o) {
        if (o.max_err > max_err) {
            max_err = o.max_err;
            worst_y = o.worst_y;
            worst_x = o.worst_x;
        }
        sum += o.sum;
        count += o.count;
        not_cr += o.not_cr;
    }
};

void Report(const char* name, const Stats& st) {
    std::printf("%s: %llu pairs, max %.6Lf ULP (y=%d x=%d), mean %.4Lf, CR %.6f%% (%llu not CR)\n", name,
                static_cast<unsigned long long>(st.count), st.max_err, st.worst_y, st.worst_x, st.sum / st.count,
                100.0 * static_cast<double>(st.count - st.not_cr) / static_cast<double>(st.count),
                static_cast<unsigned long long>(st.not_cr));
    ::testing::Test::RecordProperty(std::string(name) + "_not_cr", std::to_string(st.not_cr));
}

template <typename Body>
Stats RunOnTwoThreads(Body body) {
    std::vector<Stats> parts(2);
    std::thread other([&] { body(1, parts[1]); });
    body(0, parts[0]);
    other.join();
    parts[0].Merge(parts[1]);
    return parts[0];
}

TEST(Atan2Exhaustive, CirclesFromOneMillimetreToTwentyKilometres) {
    const long double radii[] = {1e-3L, 3e-3L, 1e-2L, 0.1L, 1.0L, 10.0L, 100.0L, 1000.0L, 2e4L};
    constexpr int kAngles = 1 << 20;
    const Stats st = RunOnTwoThreads([&](int t, Stats& out) {
        for (long double radius : radii) {
            for (int i = t; i < kAngles; i += 2) {
                const long double th = (i + 0.5L) / kAngles * 2 * kPiL - kPiL;
                const int32_t y = static_cast<int32_t>(std::llround(radius * std::sin(th) * 65536.0L));
                const int32_t x = static_cast<int32_t>(std::llround(radius * std::cos(th) * 65536.0L));
                out.Add(y, x);
            }
        }
    });
    Report("circles", st);
    EXPECT_EQ(st.count, static_cast<uint64_t>(9) * kAngles);
    EXPECT_LE(st.max_err, 1.0L);
}

TEST(Atan2Exhaustive, TenMillionLogUniformPairs) {
    constexpr int kPairs = 10000000;
    const Stats st = RunOnTwoThreads([&](int t, Stats& out) {
        std::mt19937_64 rng(0x10CCB0C5ull + static_cast<uint64_t>(t));
        auto draw = [&rng]() -> int32_t {
            const int bits = static_cast<int>(rng() % 32);  // magnitude in [2^bits, 2^(bits+1))
            int64_t v = static_cast<int64_t>((rng() >> (63 - bits)) | (uint64_t{1} << bits));
            if (v > 2147483647) v = 2147483647;
            const bool neg = (rng() & 1) != 0;
            if (neg && bits == 31) return -2147483647 - 1;  // include INT32_MIN
            return neg ? static_cast<int32_t>(-v) : static_cast<int32_t>(v);
        };
        for (int i = 0; i < kPairs / 2; ++i) {
            const int32_t y = draw();
            const int32_t x = draw();
            out.Add(y, x);
        }
    });
    Report("random_pairs", st);
    EXPECT_EQ(st.count, static_cast<uint64_t>(kPairs));
    EXPECT_LE(st.max_err, 1.0L);
}

}  // namespace LOCKBOX_TEST_FILE
