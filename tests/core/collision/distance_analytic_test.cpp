// b2Distance against closed-form distances: circles, boxes at known offsets and rotations,
// point and segment against a polygon, touching and overlapping shapes, warm starts.

#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/Distance.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

// Four counter-clockwise corners of a box with half extents hx, hy (local frame).
std::array<b2Vec2, 4> Box(Fixed hx, Fixed hy) {
    return {b2Vec2(-hx, -hy), b2Vec2(hx, -hy), b2Vec2(hx, hy), b2Vec2(-hx, hy)};
}

b2Transform At(Fixed x, Fixed y, Fixed angle = Fixed()) {
    b2Transform xf;
    xf.Set(b2Vec2(x, y), angle);
    return xf;
}

b2DistanceOutput Gjk(const b2DistanceProxy& a, const b2Transform& xfA, const b2DistanceProxy& b, const b2Transform& xfB,
                     bool useRadii, b2SimplexCache* cache = nullptr) {
    b2DistanceInput input;
    input.proxyA = a;
    input.proxyB = b;
    input.transformA = xfA;
    input.transformB = xfB;
    input.useRadii = useRadii;
    b2SimplexCache local;
    b2DistanceOutput out;
    b2Distance(&out, cache ? cache : &local, &input);
    return out;
}

constexpr double kUlp = 1.0 / 65536.0;

void ExpectNear(Fixed actual, double expected, double ulps, const char* what) {
    EXPECT_NEAR(actual.ToDouble(), expected, ulps * kUlp) << what;
}

TEST(DistanceAnalytic, CircleCircle) {
    const b2Vec2 origin;
    b2DistanceProxy a, b;
    a.Set(&origin, 1, 1);
    b.Set(&origin, 1, 0.5_fx);
    const b2DistanceOutput out = Gjk(a, At(0, 0), b, At(3, 4), true);
    ExpectNear(out.distance, 3.5, 1, "distance");
    ExpectNear(out.pointA.x, 0.6, 2, "pA.x");
    ExpectNear(out.pointA.y, 0.8, 2, "pA.y");
    ExpectNear(out.pointB.x, 2.7, 2, "pB.x");
    ExpectNear(out.pointB.y, 3.6, 2, "pB.y");
    const b2DistanceOutput core = Gjk(a, At(0, 0), b, At(3, 4), false);
    EXPECT_EQ(core.distance, Fixed(5));
    // Overlapping circles: distance 0, both points at the midpoint of the centres.
    const b2DistanceOutput over = Gjk(a, At(0, 0), b, At(1, 0), true);
    EXPECT_EQ(over.distance, Fixed());
    EXPECT_EQ(over.pointA, over.pointB);
    EXPECT_EQ(over.pointA, b2Vec2(0.5_fx, 0));
}

TEST(DistanceAnalytic, AxisAlignedBoxes) {
    const auto boxA = Box(1, 1), boxB = Box(0.5_fx, 0.5_fx);
    b2DistanceProxy a, b;
    a.Set(boxA.data(), 4, b2_polygonRadius);
    b.Set(boxB.data(), 4, b2_polygonRadius);
    const b2DistanceOutput out = Gjk(a, At(0, 0), b, At(3, 0.2_fx), false);
    EXPECT_EQ(out.distance, 1.5_fx);
    EXPECT_EQ(out.pointA.x, Fixed(1));
    EXPECT_EQ(out.pointB.x, 2.5_fx);
    const b2DistanceOutput withRadii = Gjk(a, At(0, 0), b, At(3, 0.2_fx), true);
    EXPECT_EQ(withRadii.distance, 1.5_fx - Fixed(2) * b2_polygonRadius);
    // Diagonal offset: corner (1, 1) to corner (2, 2.5).
    const b2DistanceOutput diag = Gjk(a, At(0, 0), b, At(2.5_fx, 3), false);
    ExpectNear(diag.distance, std::sqrt(1.0 + 2.25), 1, "diag");
}

TEST(DistanceAnalytic, RotatedBoxes) {
    const auto boxA = Box(1, 1), boxB = Box(0.5_fx, 0.5_fx);
    b2DistanceProxy a, b;
    a.Set(boxA.data(), 4, 0);
    b.Set(boxB.data(), 4, 0);
    const Fixed quarterPi = Fixed::FromRaw(51472);
    // B turned by 45 degrees: its corner points at A's right face.
    const b2DistanceOutput out = Gjk(a, At(0, 0), b, At(3, 0, quarterPi), false);
    ExpectNear(out.distance, 3.0 - 1.0 - 0.5 * std::sqrt(2.0), 3, "45 deg");
    ExpectNear(out.pointA.x, 1.0, 1, "face point");
    // Both rotated by 30 degrees about their own centres, placed along the rotated x axis.
    const double angle = 0.5235987755982988;
    const Fixed a30 = Fixed::FromRaw(34315);
    const Fixed cx = Fixed::FromRaw(static_cast<int32_t>(std::lround(4 * std::cos(angle) * 65536)));
    const Fixed cy = Fixed::FromRaw(static_cast<int32_t>(std::lround(4 * std::sin(angle) * 65536)));
    const b2DistanceOutput rot = Gjk(a, At(0, 0, a30), b, At(cx, cy, a30), false);
    ExpectNear(rot.distance, 4.0 - 1.0 - 0.5, 4, "30 deg aligned");
}

TEST(DistanceAnalytic, PointAndSegmentAgainstPolygon) {
    const auto box = Box(1, 1);
    b2DistanceProxy poly;
    poly.Set(box.data(), 4, 0);
    const b2Vec2 point(2, 3);
    b2DistanceProxy p;
    p.Set(&point, 1, 0);
    const b2DistanceOutput corner = Gjk(poly, At(0, 0), p, At(0, 0), false);
    ExpectNear(corner.distance, std::sqrt(5.0), 1, "point to corner");
    EXPECT_EQ(corner.pointA, b2Vec2(1, 1));
    EXPECT_EQ(corner.pointB, point);
    // A point inside the polygon.
    const b2Vec2 inside(0.25_fx, -0.5_fx);
    p.Set(&inside, 1, 0);
    EXPECT_EQ(Gjk(poly, At(0, 0), p, At(0, 0), false).distance, Fixed());
    // A point above the top face: the witness on A is the foot of the perpendicular.
    const b2Vec2 above(0.3_fx, 2.75_fx);
    p.Set(&above, 1, 0);
    const b2DistanceOutput face = Gjk(poly, At(0, 0), p, At(0, 0), false);
    EXPECT_EQ(face.distance, 1.75_fx);
    EXPECT_EQ(face.pointA, b2Vec2(0.3_fx, 1));

    const std::array<b2Vec2, 2> seg = {b2Vec2(-1, 2), b2Vec2(1, 3)};
    b2DistanceProxy s;
    s.Set(seg.data(), 2, b2_polygonRadius);
    const b2DistanceOutput segOut = Gjk(poly, At(0, 0), s, At(0, 0), false);
    EXPECT_EQ(segOut.distance, Fixed(1));
    EXPECT_EQ(segOut.pointB, b2Vec2(-1, 2));
    EXPECT_EQ(segOut.pointA, b2Vec2(-1, 1));
    // The same segment crossing the box.
    const std::array<b2Vec2, 2> cross = {b2Vec2(-3, 0.5_fx), b2Vec2(3, -0.25_fx)};
    s.Set(cross.data(), 2, 0);
    EXPECT_EQ(Gjk(poly, At(0, 0), s, At(0, 0), false).distance, Fixed());
}

TEST(DistanceAnalytic, TouchingAndOverlapping) {
    const auto box = Box(1, 1);
    b2DistanceProxy a, b;
    a.Set(box.data(), 4, b2_polygonRadius);
    b.Set(box.data(), 4, b2_polygonRadius);
    // Faces in contact: core distance 0.
    EXPECT_EQ(Gjk(a, At(0, 0), b, At(2, 0.5_fx), false).distance, Fixed());
    // Corner to corner.
    EXPECT_EQ(Gjk(a, At(0, 0), b, At(2, 2), false).distance, Fixed());
    // Skins touching exactly: separated cores, rounded distance 0.
    const Fixed gap = Fixed(2) * b2_polygonRadius;
    const b2DistanceOutput skins = Gjk(a, At(0, 0), b, At(Fixed(2) + gap, 0), true);
    EXPECT_EQ(skins.distance, Fixed());
    EXPECT_EQ(skins.pointA, skins.pointB);
    // One raw unit further: separated by exactly one raw unit.
    const b2DistanceOutput apart = Gjk(a, At(0, 0), b, At(Fixed(2) + gap + Fixed::FromRaw(1), 0), true);
    EXPECT_EQ(apart.distance, Fixed::FromRaw(1));
    // Deep overlap, rotated.
    const b2DistanceOutput deep = Gjk(a, At(0, 0, 0.3_fx), b, At(0.5_fx, 0.25_fx, -1.1_fx), true);
    EXPECT_EQ(deep.distance, Fixed());
    EXPECT_EQ(deep.pointA, deep.pointB);
}

TEST(DistanceAnalytic, WarmStartGivesSameResultWithFewerIterations) {
    std::array<b2Vec2, 6> hexagon;
    for (int i = 0; i < 6; ++i) {
        const double t = i * 1.0471975511965976;
        hexagon[static_cast<size_t>(i)] =
            b2Vec2(Fixed::FromRaw(static_cast<int32_t>(std::lround(std::cos(t) * 65536))),
                   Fixed::FromRaw(static_cast<int32_t>(std::lround(std::sin(t) * 65536))));
    }
    const auto box = Box(0.7_fx, 0.2_fx);
    b2DistanceProxy a, b;
    a.Set(hexagon.data(), 6, b2_polygonRadius);
    b.Set(box.data(), 4, b2_polygonRadius);
    int32 coldTotal = 0, warmTotal = 0;
    b2SimplexCache cache;
    for (int step = 0; step < 40; ++step) {
        const b2Transform xfA = At(0, 0, Fixed::FromRaw(step * 900));
        const b2Transform xfB =
            At(Fixed(3) - Fixed::FromRaw(step * 1500), Fixed::FromRaw(step * 700), Fixed::FromRaw(-step * 1300));
        const b2DistanceOutput cold = Gjk(a, xfA, b, xfB, true);
        const b2DistanceOutput warm = Gjk(a, xfA, b, xfB, true, &cache);
        EXPECT_EQ(cold.distance, warm.distance) << step;
        EXPECT_NEAR(cold.pointA.x.ToDouble(), warm.pointA.x.ToDouble(), 4 * kUlp) << step;
        EXPECT_NEAR(cold.pointA.y.ToDouble(), warm.pointA.y.ToDouble(), 4 * kUlp) << step;
        EXPECT_LE(warm.iterations, cold.iterations) << step;
        coldTotal += cold.iterations;
        warmTotal += warm.iterations;
    }
    EXPECT_LT(warmTotal, coldTotal);
    // The same configuration twice: the cache already holds the answer.
    b2SimplexCache again;
    const b2Transform xfB = At(2, 1, 0.4_fx);
    const b2DistanceOutput first = Gjk(a, At(0, 0), b, xfB, false, &again);
    const b2DistanceOutput second = Gjk(a, At(0, 0), b, xfB, false, &again);
    EXPECT_EQ(first.distance, second.distance);
    EXPECT_EQ(first.pointA, second.pointA);
    EXPECT_EQ(first.pointB, second.pointB);
    EXPECT_LT(second.iterations, first.iterations);
}

TEST(DistanceAnalytic, ForeignCacheIsDiscarded) {
    const auto box = Box(1, 1);
    b2DistanceProxy a, b;
    a.Set(box.data(), 4, 0);
    b.Set(box.data(), 4, 0);
    const b2DistanceOutput cold = Gjk(a, At(0, 0), b, At(3, 1, 0.5_fx), false);
    // Indices beyond these proxies (from an octagon, say): ignored, as if count were 0.
    b2SimplexCache foreign;
    foreign.count = 2;
    foreign.indexA[0] = 7;
    foreign.indexB[0] = 1;
    foreign.indexA[1] = 6;
    foreign.indexB[1] = 2;
    foreign.metric = Wide(Fixed(1));
    const b2DistanceOutput warm = Gjk(a, At(0, 0), b, At(3, 1, 0.5_fx), false, &foreign);
    EXPECT_EQ(warm.distance, cold.distance);
    EXPECT_EQ(warm.pointA, cold.pointA);
    EXPECT_EQ(warm.iterations, cold.iterations);
}

TEST(DistanceAnalytic, ProxyCopyKeepsOwnBuffer) {
    b2DistanceProxy original;
    original.m_buffer[0] = b2Vec2(1, 2);
    original.m_buffer[1] = b2Vec2(3, 4);
    original.Set(original.m_buffer, 2, 0);
    const b2DistanceProxy copy = original;
    EXPECT_EQ(copy.m_vertices, copy.m_buffer);
    EXPECT_EQ(copy.GetVertex(1), b2Vec2(3, 4));
    EXPECT_EQ(copy.GetSupport(b2Vec2(1, 0)), 1);
    EXPECT_EQ(copy.GetSupportVertex(b2Vec2(-1, 0)), b2Vec2(1, 2));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
