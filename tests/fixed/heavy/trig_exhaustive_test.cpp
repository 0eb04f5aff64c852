// SinCosRaw against long double sinl/cosl: every raw input with |x| <= 4 pi (1.65 M angles)
// and the whole int32 range at a stride of 61 (70.4 M angles, |x| up to 32768 rad).
// Gate: max error <= 1 ULP (2^-16). The share of correctly rounded results is printed and
// recorded as a test property. The reference is glibc's sinl/cosl on x86-64 (64-bit
// mantissa, exact argument reduction); on other platforms the long double reference may be
// less precise for huge arguments, which only loosens the CR share, not the 1 ULP gate.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/fixed/detail/Trig.h"

namespace LOCKBOX_TEST_FILE {

struct Stats {
    long double max_sin = 0, max_cos = 0;
    long double sum_sin = 0, sum_cos = 0;
    uint64_t count = 0, not_cr_sin = 0, not_cr_cos = 0;
    void Merge(const Stats& o) {
        if (o.max_sin > max_sin) max_sin = o.max_sin;
        if (o.max_cos > max_cos) max_cos = o.max_cos;
        sum_sin += o.sum_sin;
        sum_cos += o.sum_cos;
        count += o.count;
        not_cr_sin += o.not_cr_sin;
        not_cr_cos += o.not_cr_cos;
    }
};

void MeasureOne(int32_t x, Stats& st) {
    int32_t s = 0, c = 0;
    lockbox::detail::SinCosRaw(x, &s, &c);
    const long double a = static_cast<long double>(x) / 65536.0L;
    const long double es = std::fabs(static_cast<long double>(s) - std::sin(a) * 65536.0L);
    const long double ec = std::fabs(static_cast<long double>(c) - std::cos(a) * 65536.0L);
    if (es > st.max_sin) st.max_sin = es;
    if (ec > st.max_cos) st.max_cos = ec;
    st.sum_sin += es;
    st.sum_cos += ec;
    st.not_cr_sin += es > 0.5L ? 1 : 0;
    st.not_cr_cos += ec > 0.5L ? 1 : 0;
    ++st.count;
}

// Runs x = begin, begin + stride, ... <= last over 2 threads.
Stats Sweep(int64_t begin, int64_t last, int64_t stride) {
    constexpr int kThreads = 2;
    std::vector<Stats> parts(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([=, &parts] {
            Stats st;
            for (int64_t x = begin + t * stride; x <= last; x += kThreads * stride) {
                MeasureOne(static_cast<int32_t>(x), st);
            }
            parts[t] = st;
        });
    }
    for (std::thread& th : threads) th.join();
    Stats total;
    for (const Stats& p : parts) total.Merge(p);
    return total;
}

void Report(const char* name, const Stats& st) {
    const double cr_sin = 100.0 * static_cast<double>(st.count - st.not_cr_sin) / static_cast<double>(st.count);
    const double cr_cos = 100.0 * static_cast<double>(st.count - st.not_cr_cos) / static_cast<double>(st.count);
    std::printf(
        "%s: %llu angles; sin max %.6Lf ULP mean %.4Lf, CR %.6f%% (%llu not CR); "
        "cos max %.6Lf ULP mean %.4Lf, CR %.6f%% (%llu not CR)\n",
        name, static_cast<unsigned long long>(st.count), st.max_sin, st.sum_sin / st.count, cr_sin,
        static_cast<unsigned long long>(st.not_cr_sin), st.max_cos, st.sum_cos / st.count, cr_cos,
        static_cast<unsigned long long>(st.not_cr_cos));
    ::testing::Test::RecordProperty(std::string(name) + "_sin_not_cr", std::to_string(st.not_cr_sin));
    ::testing::Test::RecordProperty(std::string(name) + "_cos_not_cr", std::to_string(st.not_cr_cos));
}

TEST(TrigExhaustive, EveryRawInputWithinFourPi) {
    const int64_t four_pi = 823550;  // 4 pi * 2^16 = 823549.7
    const Stats st = Sweep(-four_pi, four_pi, 1);
    Report("abs_le_4pi", st);
    EXPECT_EQ(st.count, static_cast<uint64_t>(2 * four_pi + 1));
    EXPECT_LE(st.max_sin, 1.0L);
    EXPECT_LE(st.max_cos, 1.0L);
}

TEST(TrigExhaustive, WholeInt32RangeEvery61st) {
    const Stats st = Sweep(-2147483647 - 1, 2147483647, 61);
    Report("int32_stride61", st);
    EXPECT_LE(st.max_sin, 1.0L);
    EXPECT_LE(st.max_cos, 1.0L);
}

}  // namespace LOCKBOX_TEST_FILE
