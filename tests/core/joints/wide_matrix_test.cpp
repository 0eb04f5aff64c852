// The joints' exact matrix division (WideMatrix.h) at the edge of its 128-bit range: a
// numerator of 127 or 128 bits (found by the snapshot-restore fuzzer through a prismatic joint
// between bodies with extreme restored values) must divide correctly instead of shifting by a
// negative count.
#include <gtest/gtest.h>

#include "lockbox/dynamics/joints/WideMatrix.h"

namespace lockbox {
namespace {

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

}  // namespace
}  // namespace lockbox
