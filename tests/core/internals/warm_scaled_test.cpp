// Warm starts scale last step's impulses by dtRatio and skip the product when the ratio is
// exactly 1. The skip must give the very bits (and saturation reports) of the product: for every
// raw but INT64_MIN, which no operation produces, and for every other ratio the product itself.
#include <bit>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "dynamics/TimeStep.h"
#include "lockbox/fixed/Overflow.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;

constexpr int64_t kEdges[] = {0,
                              1,
                              -1,
                              2,
                              -2,
                              (int64_t{1} << 31) - 1,
                              int64_t{1} << 32,
                              -(int64_t{1} << 32),
                              (int64_t{1} << 47) + 3,
                              int64_t{1} << 62,
                              std::numeric_limits<int64_t>::max(),
                              std::numeric_limits<int64_t>::min() + 1};

// Whether raw * ratio may saturate: |raw| < 2^b and |ratio| < 2^w give a product below
// 2^(b + w - 16) + 1. Checked builds trap on saturation instead of counting it, so they compare
// only products that cannot saturate.
bool MaySaturate(int64_t raw, Fixed ratio) {
    const auto magnitude = [](int64_t v) { return v < 0 ? ~static_cast<uint64_t>(v) + 1 : static_cast<uint64_t>(v); };
    const int b = std::bit_width(magnitude(raw));
    const int w = std::bit_width(magnitude(ratio.Raw()));
    return b + w - Fixed::kFractionBits >= 62;
}

void ExpectLikeProduct(int64_t raw, Fixed ratio) {
    if (kOverflowTraps && MaySaturate(raw, ratio)) return;
    const Wide x = Wide::FromRaw(raw);
    ResetSaturationCount();
    const Wide product = x * ratio;
    const uint64_t productReports = SaturationCount();
    ResetSaturationCount();
    const Wide scaled = WarmScaled(x, ratio);
    ASSERT_EQ(scaled.Raw(), product.Raw()) << raw << " * " << ratio.Raw();
    ASSERT_EQ(SaturationCount(), productReports) << raw << " * " << ratio.Raw();
    ResetSaturationCount();
}

TEST(WarmScaled, IsTheProductByTheRatio) {
    std::mt19937_64 random(0x3a12);
    const Fixed ratios[] = {Fixed(1),
                            Fixed::FromRaw(65535),
                            Fixed::FromRaw(65537),
                            Fixed(2),
                            Fixed::FromRaw(32768),
                            Fixed::FromRaw(-65536),
                            Fixed(),
                            Fixed::FromRaw(std::numeric_limits<int32_t>::max())};
    for (const Fixed ratio : ratios) {
        for (const int64_t raw : kEdges) {
            ExpectLikeProduct(raw, ratio);
            ExpectLikeProduct(-raw, ratio);
        }
        for (int i = 0; i < 20000; ++i) {
            // Every bit length, both signs.
            const int bits = static_cast<int>(random() % 64);
            const int64_t raw = static_cast<int64_t>(random() >> (63 - bits)) * ((random() & 1) != 0 ? -1 : 1);
            ExpectLikeProduct(raw, ratio);
        }
    }
}

TEST(WarmScaled, VectorsScaleEachComponent) {
    const b2WideVec2 v{Wide::FromRaw(123456789012), Wide::FromRaw(-98765432109)};
    for (const Fixed ratio : {Fixed(1), Fixed::FromRaw(70000), Fixed::FromRaw(-3)}) {
        const b2WideVec2 scaled = WarmScaled(v, ratio);
        const b2WideVec2 product = ratio * v;
        EXPECT_EQ(scaled.x.Raw(), product.x.Raw());
        EXPECT_EQ(scaled.y.Raw(), product.y.Raw());
    }
}

}  // namespace LOCKBOX_TEST_FILE
