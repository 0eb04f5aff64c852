// The native 128-bit division (detail::DivModNative: the processor's 128-by-64 division, a
// quotient estimate and one correction) against the compiler's general division, on divisors
// and dividends of every width, both sides of each branch, and the edges of each.
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "lockbox/fixed/detail/Int128.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

#ifdef LOCKBOX_NATIVE_INT128
using detail::NativeU128;

NativeU128 Make(uint64_t hi, uint64_t lo) { return (NativeU128{hi} << 64) | lo; }

// A value of exactly `width` bits (0 to 128), its low bits random.
NativeU128 OfWidth(std::mt19937_64& rng, int width) {
    if (width == 0) return 0;
    NativeU128 v = Make(rng(), rng());
    if (width < 128) v &= (NativeU128{1} << width) - 1;
    return v | (NativeU128{1} << (width - 1));
}

::testing::AssertionResult Divides(NativeU128 n, NativeU128 d) {
    const detail::NativeDivMod r = detail::DivModNative(n, d);
    if (r.quot == n / d && r.rem == n % d) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "n " << static_cast<uint64_t>(n >> 64) << ":" << static_cast<uint64_t>(n)
                                         << " d " << static_cast<uint64_t>(d >> 64) << ":" << static_cast<uint64_t>(d);
}
#endif

TEST(Int128Division, NativeDivisionIsTheQuotientAndRemainder) {
#ifndef LOCKBOX_NATIVE_INT128
    GTEST_SKIP() << "no native 128-bit integer";
#else
    std::mt19937_64 rng(128);
    // Every pair of widths, many times over: divisors below and above 2^64, quotients below and
    // above 2^64, dividends below the divisor.
    for (int dw = 1; dw <= 128; ++dw) {
        for (int nw = 0; nw <= 128; ++nw) {
            for (int i = 0; i < 40; ++i) ASSERT_TRUE(Divides(OfWidth(rng, nw), OfWidth(rng, dw)));
        }
    }
    // Quotients next to a whole number: n = q d + r for r near 0 and near d, where an estimate
    // one off shows.
    for (int i = 0; i < 200000; ++i) {
        const NativeU128 d = OfWidth(rng, static_cast<int>(rng() % 128) + 1);
        const int qw = static_cast<int>(rng() % 65);
        const NativeU128 q = OfWidth(rng, qw);
        if (q != 0 && d > ~NativeU128{0} / q) continue;
        const NativeU128 base = q * d;
        for (const NativeU128 r : {NativeU128{0}, NativeU128{1}, d - 1}) {
            if (base > ~NativeU128{0} - r) continue;
            ASSERT_TRUE(Divides(base + r, d));
        }
    }
    // The edges: the smallest and largest divisors of each branch, the largest dividends.
    const NativeU128 top = ~NativeU128{0};
    const NativeU128 edges[] = {1,
                                2,
                                3,
                                Make(0, ~uint64_t{0}),
                                Make(1, 0),
                                Make(1, 1),
                                Make(1, ~uint64_t{0}),
                                Make(uint64_t{1} << 63, 0),
                                Make(~uint64_t{0}, 0),
                                top - 1,
                                top};
    for (const NativeU128 d : edges) {
        for (const NativeU128 n : edges) ASSERT_TRUE(Divides(n, d));
        ASSERT_TRUE(Divides(0, d));
        ASSERT_TRUE(Divides(d - 1, d));
        ASSERT_TRUE(Divides(d, d));
    }
#endif
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
