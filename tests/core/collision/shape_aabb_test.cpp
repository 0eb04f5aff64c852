// b2AABB::RayCast (slab method with exact ratios): hit, miss, parallel, starting inside,
// maxFraction clipping, and agreement with a double reference on random rays. A polygon's AABB
// against its rotated vertices, for the boxes that skip the rotation and for those that cannot.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/fixed/Overflow.h"

using namespace lockbox;
using namespace lockbox::literals;

namespace LOCKBOX_TEST_FILE {
Fixed F(double v) { return Fixed::FromDoubleNondeterministic(v); }
b2Vec2 V(double x, double y) { return {F(x), F(y)}; }

TEST(ShapeAABB, RayCastCases) {
    const b2AABB box{V(-1, -2), V(3, 2)};
    b2RayCastOutput out;
    ASSERT_TRUE(box.RayCast(&out, {V(-5, 0), V(5, 0), 1}));
    EXPECT_EQ(out.fraction, 0.4_fx);
    EXPECT_EQ(out.normal, V(-1, 0));
    ASSERT_TRUE(box.RayCast(&out, {V(0, 6), V(0, -6), 1}));
    EXPECT_EQ(out.fraction, Fixed::FromRatio(4, 12));
    EXPECT_EQ(out.normal, V(0, 1));
    ASSERT_TRUE(box.RayCast(&out, {V(7, 1), V(-1, 1), 1}));
    EXPECT_EQ(out.fraction, 0.5_fx);
    EXPECT_EQ(out.normal, V(1, 0));
    // Diagonal: the y slab is entered at 3/8, the x slab at 1/2; the later one gives the hit.
    ASSERT_TRUE(box.RayCast(&out, {V(-3, -5), V(1, 3), 1}));
    EXPECT_EQ(out.fraction, 0.5_fx);
    EXPECT_EQ(out.normal, V(-1, 0));
    // maxFraction clipping.
    EXPECT_FALSE(box.RayCast(&out, {V(-5, 0), V(5, 0), F(0.39)}));
    // 0.4 itself is not representable: 0.4_fx (raw 26214) is just below the exact hit, one
    // raw more is above it. The comparison is exact, so the boundary is sharp.
    EXPECT_FALSE(box.RayCast(&out, {V(-5, 0), V(5, 0), 0.4_fx}));
    EXPECT_TRUE(box.RayCast(&out, {V(-5, 0), V(5, 0), 0.4_fx + Fixed::FromRaw(1)}));
    // Starting inside: no hit.
    EXPECT_FALSE(box.RayCast(&out, {V(0, 0), V(5, 0), 1}));
    // Parallel outside and inside a slab.
    EXPECT_FALSE(box.RayCast(&out, {V(-5, 2.5), V(5, 2.5), 1}));
    EXPECT_TRUE(box.RayCast(&out, {V(-5, 2), V(5, 2), 1}));
    // Miss, pointing away, zero length.
    EXPECT_FALSE(box.RayCast(&out, {V(-5, 0), V(-5, 10), 1}));
    EXPECT_FALSE(box.RayCast(&out, {V(-5, 0), V(-6, 0), 1}));
    EXPECT_FALSE(box.RayCast(&out, {V(-5, 0), V(-5, 0), 1}));
    // Across the whole Q16.16 range (differences near 2^32 raw) without overflow.
    ASSERT_TRUE(box.RayCast(&out, {V(-32000, -32000), V(32000, 32000), 1}));
    EXPECT_NEAR(out.fraction.ToDouble(), 31998.0 / 64000.0, 2e-5);
}

TEST(ShapeAABB, RayCastMatchesDoubleReference) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-10, 10);
    int hits = 0;
    for (int t = 0; t < 20000; ++t) {
        const double x0 = u(rng), y0 = u(rng);
        const b2AABB box{V(x0, y0), V(x0 + std::fabs(u(rng)) / 2, y0 + std::fabs(u(rng)) / 2)};
        const b2RayCastInput in{V(u(rng), u(rng)), V(u(rng), u(rng)), F(std::fabs(u(rng)) / 8)};
        b2RayCastOutput out;
        const bool hit = box.RayCast(&out, in);
        const double p[2] = {in.p1.x.ToDouble(), in.p1.y.ToDouble()};
        const double d[2] = {(in.p2.x - in.p1.x).ToDouble(), (in.p2.y - in.p1.y).ToDouble()};
        const double lo[2] = {box.lowerBound.x.ToDouble(), box.lowerBound.y.ToDouble()};
        const double hi[2] = {box.upperBound.x.ToDouble(), box.upperBound.y.ToDouble()};
        double tmin = -1e300, tmax = 1e300;
        bool ref = true;
        for (int i = 0; i < 2 && ref; ++i) {
            if (d[i] == 0) {
                ref = lo[i] <= p[i] && p[i] <= hi[i];
                continue;
            }
            double t1 = (lo[i] - p[i]) / d[i], t2 = (hi[i] - p[i]) / d[i];
            if (t1 > t2) std::swap(t1, t2);
            tmin = std::max(tmin, t1);
            tmax = std::min(tmax, t2);
            ref = tmin <= tmax;
        }
        ref = ref && tmin >= 0 && tmin <= in.maxFraction.ToDouble();
        // Doubles round the slab fractions; skip reference-ambiguous near ties.
        if (hit != ref && (std::fabs(tmin - tmax) < 1e-12 || std::fabs(tmin) < 1e-12 ||
                           std::fabs(tmin - in.maxFraction.ToDouble()) < 1e-12)) {
            continue;
        }
        ASSERT_EQ(hit, ref) << t;
        if (hit) {
            ++hits;
            EXPECT_LE(std::fabs(out.fraction.ToDouble() - tmin), 0.5 / 65536 + 1e-12);
        }
    }
    EXPECT_GT(hits, 500);
}

// The AABB as Box2D defines it: every vertex transformed, the least and greatest coordinates,
// widened by the polygon's skin.
b2AABB RotatedVertices(const b2PolygonShape& polygon, const b2Transform& xf) {
    b2Vec2 lower = b2Mul(xf, polygon.GetVertex(0));
    b2Vec2 upper = lower;
    for (int32 i = 1; i < polygon.GetVertexCount(); ++i) {
        const b2Vec2 v = b2Mul(xf, polygon.GetVertex(i));
        lower = b2Min(lower, v);
        upper = b2Max(upper, v);
    }
    const b2Vec2 r(polygon.m_radius, polygon.m_radius);
    return {lower - r, upper + r};
}

// ComputeAABB's result and the saturations it counted, against the reference's; returns the
// reference's count.
uint64_t ExpectSameAABB(const b2PolygonShape& polygon, const b2Transform& xf) {
    ResetSaturationCount();
    const b2AABB expected = RotatedVertices(polygon, xf);
    const uint64_t expectedSaturations = SaturationCount();
    ResetSaturationCount();
    b2AABB aabb;
    polygon.ComputeAABB(&aabb, xf, 0);
    EXPECT_EQ(SaturationCount(), expectedSaturations);
    EXPECT_EQ(aabb.lowerBound, expected.lowerBound)
        << "p " << xf.p.x.Raw() << "," << xf.p.y.Raw() << " q " << xf.q.c.Raw() << "," << xf.q.s.Raw();
    EXPECT_EQ(aabb.upperBound, expected.upperBound);
    return expectedSaturations;
}

// Checked builds trap on a saturation; this handler returns, so that the saturated results of
// the boxes at the edge of the range can be compared too.
void ReturningHandler(const char*, int64_t, int64_t) {}

TEST(ShapeAABB, PolygonBoxesMatchTheirRotatedVertices) {
    struct KeepSaturating {
        OverflowTrapHandler previous = SetOverflowTrapHandler(&ReturningHandler);
        ~KeepSaturating() { SetOverflowTrapHandler(previous); }
    } keepSaturating;
    std::mt19937_64 rng(11);
    // Half-extents from one raw unit to 2^30 raw (16384 m), of every bit length.
    auto extent = [&] { return Fixed::FromRaw(static_cast<int32>(1 + (rng() >> (34 + rng() % 30)))); };
    auto anywhere = [&](int bits) {
        return Fixed::FromRaw(
            static_cast<int32>(static_cast<int64_t>(rng() >> (64 - bits)) - (int64_t{1} << (bits - 1))));
    };
    int boxes = 0;
    for (int t = 0; t < 40000; ++t) {
        b2PolygonShape polygon;
        const Fixed hx = extent(), hy = extent();
        b2Transform xf;
        xf.q = b2Rot(anywhere(20));  // any angle, wrapped as the rotation does
        // Positions near the origin, and some near the edge of the range, where a corner may
        // saturate and the box must take the loop.
        xf.p = t % 8 == 0 ? b2Vec2(anywhere(32), anywhere(32)) : b2Vec2(anywhere(24), anywhere(24));
        if (t % 5 == 0) {
            // Not centred, or turned: the loop.
            if (polygon.SetAsBox(hx, hy, b2Vec2(anywhere(18), anywhere(18)), anywhere(18)) != b2ShapeError::ok)
                continue;
        } else {
            if (polygon.SetAsBox(hx, hy) != b2ShapeError::ok) continue;
            ++boxes;
        }
        ExpectSameAABB(polygon, xf);
    }
    EXPECT_GT(boxes, 10000);
    // Exact quarter turns and the identity, where one product of each pair is zero.
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(Fixed(2), Fixed(0.5)), b2ShapeError::ok);
    for (const Fixed angle : {Fixed(0), b2_pi / 2, b2_pi, -b2_pi / 2, b2_pi / 4}) {
        b2Transform xf;
        xf.q = b2Rot(angle);
        xf.p = b2Vec2(Fixed(3), Fixed(-7));
        ExpectSameAABB(box, xf);
    }
    // At the edge of the range: a corner that saturates is counted as the loop counts it.
    b2Transform far;
    far.q = b2Rot(Fixed(0.3));
    far.p = b2Vec2(Fixed::FromRaw(Fixed::kMaxRaw - 5), Fixed(0));
    EXPECT_GT(ExpectSameAABB(box, far), 0u);
}

}  // namespace LOCKBOX_TEST_FILE
