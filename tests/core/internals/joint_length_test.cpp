// The joints' position test without a square root (LengthWithin) against the rounded length it
// stands for: exhaustively around the linear slop, where the iterations decide, and on random
// vectors and limits over the whole Q16.16 range.
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "dynamics/joints/JointMath.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using jointmath::LengthWithin;

TEST(JointLength, AgreesWithTheRoundedLengthAroundTheSlop) {
    const int32_t slop = b2_linearSlop.Raw();
    const int32_t reach = slop + 80;
    int within = 0;
    for (int32_t x = -reach; x <= reach; ++x) {
        for (int32_t y = -reach; y <= reach; ++y) {
            const b2Vec2 v(Fixed::FromRaw(x), Fixed::FromRaw(y));
            for (const int32_t limit : {slop - 1, slop, slop + 1}) {
                const Fixed l = Fixed::FromRaw(limit);
                ASSERT_EQ(LengthWithin(v, l), v.Length() <= l) << x << " " << y << " " << limit;
            }
            within += LengthWithin(v, b2_linearSlop) ? 1 : 0;
        }
    }
    // About pi slop^2 of the square's points: the test is neither always true nor always false.
    EXPECT_GT(within, 3 * slop * slop);
    EXPECT_LT(within, 4 * slop * slop);
}

TEST(JointLength, AgreesWithTheRoundedLengthOverTheRange) {
    std::mt19937_64 rng(20261129);
    for (int i = 0; i < 400000; ++i) {
        auto raw = [&](int bits) {
            const auto v = static_cast<int32_t>(rng() & ((uint64_t{1} << bits) - 1));
            return (rng() & 1) != 0 ? -v : v;
        };
        // Up to 30 bits a component: the squared length stays below 2^61, with no saturation.
        const int bits = 1 + static_cast<int>(rng() % 30);
        const b2Vec2 v(Fixed::FromRaw(raw(bits)), Fixed::FromRaw(raw(bits)));
        // Limits near the vector's length, and anywhere in range.
        const int32_t length = v.Length().Raw();
        const int32_t near = length + static_cast<int32_t>(rng() % 5) - 2;
        const int32_t limit = i % 2 == 0 ? (near < 0 ? 0 : near) : static_cast<int32_t>(rng() % Fixed::kMaxRaw);
        const Fixed l = Fixed::FromRaw(limit);
        ASSERT_EQ(LengthWithin(v, l), v.Length() <= l) << v.x.Raw() << " " << v.y.Raw() << " " << limit;
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
