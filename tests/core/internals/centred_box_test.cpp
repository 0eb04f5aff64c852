// A SetAsBox(hx, hy) polygon's shortcuts against the scans they stand for: which polygons count
// as centred boxes, and the support corner that the polygon collision's edge separation takes
// without visiting the corners (the first least exact dot product, as its scan keeps).
#include <random>

#include <gtest/gtest.h>

#include "collision/shapes/CentredBox.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using shape_detail::AsCentredBox;
using shape_detail::CentredBox;
using shape_detail::CentredBoxSupport;

// The scan of b2EdgeSeparation: the first corner of least exact dot product with n.
int32 ScannedSupport(const b2PolygonShape& box, const b2Vec2& n) {
    int32 index = 0;
    Wide minDot = Wide::FromRaw(Wide::kMaxRaw);
    for (int32 i = 0; i < box.GetVertexCount(); ++i) {
        const Wide dot = b2DotWide(box.GetVertex(i), n);
        if (dot < minDot) {
            minDot = dot;
            index = i;
        }
    }
    return index;
}

bool IsCentredBox(const b2PolygonShape& polygon) {
    CentredBox box;
    return AsCentredBox(&polygon.GetVertex(0), polygon.GetVertexCount(), &box);
}

TEST(CentredBox, OnlySetAsBoxWithoutCentreOrAngleCounts) {
    b2PolygonShape polygon;
    ASSERT_EQ(polygon.SetAsBox(Fixed(0.5), Fixed(2)), b2ShapeError::ok);
    CentredBox box;
    ASSERT_TRUE(AsCentredBox(&polygon.GetVertex(0), polygon.GetVertexCount(), &box));
    EXPECT_EQ(box.hx, Fixed(0.5).Raw());
    EXPECT_EQ(box.hy, Fixed(2).Raw());

    ASSERT_EQ(polygon.SetAsBox(Fixed(0.5), Fixed(2), b2Vec2(Fixed(1), Fixed(0)), Fixed(0)), b2ShapeError::ok);
    EXPECT_FALSE(IsCentredBox(polygon));
    ASSERT_EQ(polygon.SetAsBox(Fixed(0.5), Fixed(2), b2Vec2(), Fixed(0.25)), b2ShapeError::ok);
    EXPECT_FALSE(IsCentredBox(polygon));
    // A centred box given as points in another order is a polygon like any other.
    const b2Vec2 shifted[4] = {b2Vec2(Fixed(1), Fixed(-1)), b2Vec2(Fixed(1), Fixed(1)), b2Vec2(Fixed(-1), Fixed(1)),
                               b2Vec2(Fixed(-1), Fixed(-1))};
    ASSERT_EQ(polygon.Set(shifted, 4), b2ShapeError::ok);
    EXPECT_FALSE(IsCentredBox(polygon));
    const b2Vec2 triangle[3] = {b2Vec2(Fixed(-1), Fixed(-1)), b2Vec2(Fixed(1), Fixed(-1)), b2Vec2(Fixed(0), Fixed(1))};
    ASSERT_EQ(polygon.Set(triangle, 3), b2ShapeError::ok);
    EXPECT_FALSE(IsCentredBox(polygon));
    // Half-extents from 2^30 raw (16384 m) up are left to the scans.
    const b2Vec2 wide[4] = {b2Vec2(Fixed::FromRaw(-(1 << 30)), Fixed(-1)), b2Vec2(Fixed::FromRaw(1 << 30), Fixed(-1)),
                            b2Vec2(Fixed::FromRaw(1 << 30), Fixed(1)), b2Vec2(Fixed::FromRaw(-(1 << 30)), Fixed(1))};
    EXPECT_FALSE(AsCentredBox(wide, 4, &box));
}

TEST(CentredBox, SupportCornerIsTheScansFirstLeast) {
    std::mt19937_64 rng(3);
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(Fixed(0.5), Fixed(0.5)), b2ShapeError::ok);
    // Every direction on a fine circle, the exact axes and diagonals (ties), and zero.
    for (int32 k = 0; k < 20000; ++k) {
        const b2Rot q(Fixed::FromRaw(static_cast<int32>(rng() % 411775) - 205887));
        const b2Vec2 n(q.c, q.s);
        ASSERT_EQ(CentredBoxSupport(n), ScannedSupport(box, n)) << n.x.Raw() << "," << n.y.Raw();
    }
    for (const int32 x : {-65536, -1, 0, 1, 65536}) {
        for (const int32 y : {-65536, -1, 0, 1, 65536}) {
            const b2Vec2 n(Fixed::FromRaw(x), Fixed::FromRaw(y));
            EXPECT_EQ(CentredBoxSupport(n), ScannedSupport(box, n)) << x << "," << y;
        }
    }
    // Boxes of other proportions, and unit-range vectors that are not unit.
    for (int32 k = 0; k < 20000; ++k) {
        b2PolygonShape other;
        const auto extent = [&] { return Fixed::FromRaw(static_cast<int32>(1000 + rng() % (1u << 22))); };
        if (other.SetAsBox(extent(), extent()) != b2ShapeError::ok) continue;
        const auto component = [&] { return Fixed::FromRaw(static_cast<int32>(rng() % (1u << 18)) - (1 << 17)); };
        const b2Vec2 n(k % 7 == 0 ? Fixed() : component(), k % 11 == 0 ? Fixed() : component());
        ASSERT_EQ(CentredBoxSupport(n), ScannedSupport(other, n)) << n.x.Raw() << "," << n.y.Raw();
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
