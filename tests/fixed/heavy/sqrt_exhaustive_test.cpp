// Exhaustive SqrtRaw: every non-negative raw Q16.16 input (2^31 values), checked with integer
// arithmetic only: r = round(sqrt(v)), v = x * 2^16, iff (2r - 1)^2 <= 4v < (2r + 1)^2.
// Split over 2 threads (about 15-30 s in Release).
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/fixed/detail/Sqrt.h"

namespace LOCKBOX_TEST_FILE {

struct Result {
    uint64_t failures = 0;
    int64_t first_bad = -1;
};

Result CheckRange(int64_t begin, int64_t end) {
    Result res;
    for (int64_t x = begin; x < end; ++x) {
        const int32_t r = lockbox::detail::SqrtRaw(static_cast<int32_t>(x));
        const uint64_t v4 = static_cast<uint64_t>(x) << 18;  // 4v < 2^49
        const uint64_t rr = static_cast<uint64_t>(r);
        const uint64_t lo = rr == 0 ? 0 : (2 * rr - 1) * (2 * rr - 1);
        const uint64_t hi = (2 * rr + 1) * (2 * rr + 1);
        if (r < 0 || lo > v4 || v4 >= hi) {
            if (res.failures++ == 0) res.first_bad = x;
        }
    }
    return res;
}

TEST(SqrtExhaustive, AllNonNegativeRawInputsAreCorrectlyRounded) {
    constexpr int64_t kEnd = int64_t{1} << 31;
    constexpr int kThreads = 2;
    std::vector<Result> results(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([t, &results] {
            // Interleaved 2^20-sized chunks balance the two halves.
            Result total;
            for (int64_t chunk = t; chunk < (kEnd >> 20); chunk += kThreads) {
                const Result r = CheckRange(chunk << 20, (chunk + 1) << 20);
                if (r.failures != 0 && total.first_bad < 0) total.first_bad = r.first_bad;
                total.failures += r.failures;
            }
            results[t] = total;
        });
    }
    for (std::thread& th : threads) th.join();
    uint64_t failures = 0;
    for (const Result& r : results) {
        failures += r.failures;
        if (r.failures != 0) ADD_FAILURE() << "first bad input " << r.first_bad;
    }
    EXPECT_EQ(failures, 0u);
    // Negative inputs are a domain error and return 0.
    EXPECT_EQ(lockbox::detail::SqrtRaw(-1), 0);
    EXPECT_EQ(lockbox::detail::SqrtRaw(-2147483647 - 1), 0);
}

}  // namespace LOCKBOX_TEST_FILE
