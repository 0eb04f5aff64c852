// b2PolygonShape: every rejection of Set/SetAsBox (shape unchanged afterwards), SetFromHull on
// random clouds, normals, TestPoint, RayCast and ComputeAABB under rotated transforms.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/PolygonShape.h"

using namespace lockbox;
using namespace lockbox::literals;

namespace LOCKBOX_TEST_FILE {

Fixed F(double v) { return Fixed::FromDoubleNondeterministic(v); }
b2Vec2 V(double x, double y) { return {F(x), F(y)}; }

// Byte-wise identity of two polygons (members are plain values).
void ExpectSamePolygon(const b2PolygonShape& a, const b2PolygonShape& b) {
    EXPECT_EQ(a.m_vertexCount, b.m_vertexCount);
    EXPECT_EQ(a.m_radius, b.m_radius);
    EXPECT_EQ(a.m_centroid, b.m_centroid);
    for (int i = 0; i < b2_maxPolygonVertices; ++i) {
        EXPECT_EQ(a.m_vertices[i], b.m_vertices[i]) << i;
        EXPECT_EQ(a.m_normals[i], b.m_normals[i]) << i;
    }
}

// Checks `error` is returned by Set and that both an empty and a set polygon stay unchanged.
void ExpectSetRejects(const std::vector<b2Vec2>& pts, b2ShapeError error) {
    b2PolygonShape empty;
    const b2PolygonShape emptyCopy = empty;
    EXPECT_EQ(empty.Set(pts.data(), static_cast<int32>(pts.size())), error) << b2ShapeErrorMessage(error);
    ExpectSamePolygon(empty, emptyCopy);
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(1, 2, V(0.5, -0.25), F(0.3)), b2ShapeError::ok);
    const b2PolygonShape boxCopy = box;
    EXPECT_EQ(box.Set(pts.data(), static_cast<int32>(pts.size())), error);
    ExpectSamePolygon(box, boxCopy);
    EXPECT_EQ(b2ValidatePolygon(pts.data(), static_cast<int32>(pts.size())), error);
}

double UnitError(const b2Vec2& n) { return std::fabs(std::hypot(n.x.ToDouble(), n.y.ToDouble()) - 1.0); }

TEST(ShapePolygon, SetAcceptsConvexCounterClockwise) {
    const std::vector<b2Vec2> tri = {V(0, 0), V(1, 0), V(0, 1)};
    b2PolygonShape p;
    ASSERT_EQ(p.Set(tri.data(), 3), b2ShapeError::ok);
    EXPECT_EQ(p.GetType(), b2Shape::e_polygon);
    EXPECT_EQ(p.GetVertexCount(), 3);
    EXPECT_EQ(p.GetVertex(1), V(1, 0));
    EXPECT_EQ(p.m_radius, b2_polygonRadius);
    EXPECT_TRUE(p.Validate());
    // Normals exact for axis-aligned edges; the hypotenuse within 2 ULP of unit length.
    EXPECT_EQ(p.m_normals[0], b2Vec2(0, -1));
    EXPECT_EQ(p.m_normals[2], b2Vec2(-1, 0));
    EXPECT_LE(UnitError(p.m_normals[1]), 2.0 / 65536);
    EXPECT_NEAR(p.m_normals[1].x.ToDouble(), std::sqrt(0.5), 2.0 / 65536);
    // Centroid (1/3, 1/3), rounded once.
    EXPECT_EQ(p.m_centroid, b2Vec2(Fixed::FromRatio(1, 3), Fixed::FromRatio(1, 3)));
    EXPECT_EQ(b2ShapeErrorMessage(b2ShapeError::ok), std::string("ok"));
}

TEST(ShapePolygon, SetRejectsEveryInvalidInput) {
    ExpectSetRejects({V(0, 0), V(1, 0)}, b2ShapeError::tooFewVertices);
    ExpectSetRejects({}, b2ShapeError::tooFewVertices);
    std::vector<b2Vec2> nine;
    for (int k = 0; k < 9; ++k) nine.push_back(V(std::cos(k * 0.6981), std::sin(k * 0.6981)));
    ExpectSetRejects(nine, b2ShapeError::tooManyVertices);
    ExpectSetRejects({V(0, 0), V(4097, 0), V(0, 1)}, b2ShapeError::outOfRange);
    ExpectSetRejects({V(0, 0), V(1, 0), V(0, -4096.01)}, b2ShapeError::outOfRange);
    // Duplicates: exact, and closer than the weld distance (163 raw apart), even non-adjacent.
    ExpectSetRejects({V(0, 0), V(1, 0), V(1, 0), V(0, 1)}, b2ShapeError::duplicateVertices);
    ExpectSetRejects({V(0, 0), V(1, 0), b2Vec2(Fixed(1), Fixed::FromRaw(163)), V(0, 1)},
                     b2ShapeError::duplicateVertices);
    // Exactly at the weld distance is accepted (and then fails for another reason or passes).
    {
        const std::vector<b2Vec2> pts = {V(0, 0), V(1, 0), b2Vec2(Fixed(1), Fixed::FromRaw(164)), V(0, 1)};
        EXPECT_NE(b2ValidatePolygon(pts.data(), 4), b2ShapeError::duplicateVertices);
    }
    // Collinear: all on a line; a slightly bent line; a redundant mid-edge vertex.
    ExpectSetRejects({V(0, 0), V(1, 0), V(2, 0)}, b2ShapeError::collinear);
    ExpectSetRejects({V(0, 0), V(1, 0.001), V(2, 0)}, b2ShapeError::collinear);
    ExpectSetRejects({V(0, 0), V(1, 0), V(2, 0), V(0, 1)}, b2ShapeError::collinear);
    ExpectSetRejects({V(0, 0), V(1, -0.002), V(2, 0), V(1, 1)}, b2ShapeError::collinear);
    // Clockwise convex polygons.
    ExpectSetRejects({V(0, 0), V(0, 1), V(1, 0)}, b2ShapeError::clockwise);
    ExpectSetRejects({V(-1, -1), V(-1, 1), V(1, 1), V(1, -1)}, b2ShapeError::clockwise);
    // Non-convex: a dart, and a self-intersecting bow tie.
    ExpectSetRejects({V(0, 0), V(2, 1), V(0, 2), V(0.5, 1)}, b2ShapeError::notConvex);
    ExpectSetRejects({V(0, 0), V(1, 0), V(0, 1), V(1, 1)}, b2ShapeError::notConvex);
    // Pentagram order of a regular pentagon.
    {
        std::vector<b2Vec2> pent;
        for (int k = 0; k < 5; ++k) pent.push_back(V(std::cos(k * 1.2566371), std::sin(k * 1.2566371)));
        const std::vector<b2Vec2> pentagram = {pent[0], pent[2], pent[4], pent[1], pent[3]};
        ExpectSetRejects(pentagram, b2ShapeError::notConvex);
    }
    // Area below 2^-10 m^2: a 3 cm square (9e-4 m^2) is refused, a 3.2 cm one accepted.
    ExpectSetRejects({V(0, 0), V(0.03, 0), V(0.03, 0.03), V(0, 0.03)}, b2ShapeError::areaTooSmall);
    {
        const std::vector<b2Vec2> ok = {V(0, 0), V(0.032, 0), V(0.032, 0.032), V(0, 0.032)};
        b2PolygonShape p;
        EXPECT_EQ(p.Set(ok.data(), 4), b2ShapeError::ok);
    }
    // Every error has a distinct message.
    for (int e = 1; e <= static_cast<int>(b2ShapeError::outOfRange); ++e) {
        EXPECT_STRNE(b2ShapeErrorMessage(static_cast<b2ShapeError>(e)), "ok");
        EXPECT_STRNE(b2ShapeErrorMessage(static_cast<b2ShapeError>(e)), "unknown shape error");
    }
}

TEST(ShapePolygon, SetAsBoxRejectsAndLeavesShapeUnchanged) {
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(2, 1), b2ShapeError::ok);
    const b2PolygonShape copy = box;
    EXPECT_EQ(box.SetAsBox(0, 1), b2ShapeError::nonPositiveExtent);
    EXPECT_EQ(box.SetAsBox(1, -1), b2ShapeError::nonPositiveExtent);
    EXPECT_EQ(box.SetAsBox(-1, 1, V(0, 0), 0), b2ShapeError::nonPositiveExtent);
    EXPECT_EQ(box.SetAsBox(4097, 1), b2ShapeError::outOfRange);
    EXPECT_EQ(box.SetAsBox(1, 1, V(4096, 0), 0), b2ShapeError::outOfRange);
    EXPECT_EQ(box.SetAsBox(1, 1, V(5000, 0), 0), b2ShapeError::outOfRange);
    EXPECT_EQ(box.SetAsBox(0.01_fx, 0.01_fx), b2ShapeError::areaTooSmall);
    EXPECT_EQ(box.SetAsBox(10, 0.001_fx), b2ShapeError::duplicateVertices);               // 2 mm thick
    EXPECT_EQ(box.SetAsBox(10, 0.0012_fx, V(1, 1), 1), b2ShapeError::duplicateVertices);  // 2.4 mm, rotated
    ExpectSamePolygon(box, copy);
    // 3 mm thick is above the weld distance (2.5 mm): accepted.
    EXPECT_EQ(box.SetAsBox(10, 0.0015_fx, V(1, 1), 1), b2ShapeError::ok);
}

TEST(ShapePolygon, SetAsBoxMatchesTheManual) {
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(2, 1), b2ShapeError::ok);
    EXPECT_EQ(box.m_vertexCount, 4);
    EXPECT_EQ(box.m_vertices[0], V(-2, -1));
    EXPECT_EQ(box.m_vertices[2], V(2, 1));
    EXPECT_EQ(box.m_normals[1], V(1, 0));
    EXPECT_EQ(box.m_centroid, b2Vec2());
    EXPECT_TRUE(box.Validate());

    const b2Vec2 c = V(3, -2);
    const Fixed angle = F(0.5);
    ASSERT_EQ(box.SetAsBox(2, 1, c, angle), b2ShapeError::ok);
    EXPECT_EQ(box.m_centroid, c);
    EXPECT_TRUE(box.Validate());
    const b2Rot q(angle);
    for (int i = 0; i < 4; ++i) {
        const double sx = (i == 1 || i == 2) ? 2 : -2, sy = i >= 2 ? 1 : -1;
        const double ca = std::cos(0.5), sa = std::sin(0.5);
        EXPECT_NEAR(box.m_vertices[i].x.ToDouble(), 3 + ca * sx - sa * sy, 3e-5);
        EXPECT_NEAR(box.m_vertices[i].y.ToDouble(), -2 + sa * sx + ca * sy, 3e-5);
        EXPECT_LE(UnitError(box.m_normals[i]), 3.0 / 65536);
    }
    EXPECT_EQ(box.m_normals[1], q.GetXAxis());
}

TEST(ShapePolygon, SetFromHullOnRandomCloudsIsConvexAndContainsAllPoints) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> coord(-3, 3);
    int accepted = 0, collinear = 0, areaSmall = 0, tooMany = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const int n = 3 + static_cast<int>(rng() % 10);  // 3..12 points
        const double scale = trial % 3 == 0 ? 0.05 : 1.0;
        std::vector<b2Vec2> pts;
        for (int k = 0; k < n; ++k) pts.push_back(V(scale * coord(rng), scale * coord(rng)));
        b2PolygonShape p;
        const b2PolygonShape before = p;
        const b2ShapeError e = p.SetFromHull(pts.data(), n);
        if (e != b2ShapeError::ok) {
            ExpectSamePolygon(p, before);
            // Only the documented outcomes of a hull: too many hull vertices, a sliver, tiny.
            EXPECT_TRUE(e == b2ShapeError::tooManyVertices || e == b2ShapeError::collinear ||
                        e == b2ShapeError::areaTooSmall)
                << b2ShapeErrorMessage(e);
            tooMany += e == b2ShapeError::tooManyVertices;
            collinear += e == b2ShapeError::collinear;
            areaSmall += e == b2ShapeError::areaTooSmall;
            continue;
        }
        ++accepted;
        ASSERT_TRUE(p.Validate());
        ASSERT_EQ(b2ValidatePolygon(p.m_vertices, p.m_vertexCount), b2ShapeError::ok);
        // Every input point is inside, or outside by less than the weld distance per dropped
        // hull vertex (at most 2 here).
        for (const b2Vec2& q : pts) {
            for (int i = 0; i < p.m_vertexCount; ++i) {
                const double d = (q.x - p.m_vertices[i].x).ToDouble() * p.m_normals[i].x.ToDouble() +
                                 (q.y - p.m_vertices[i].y).ToDouble() * p.m_normals[i].y.ToDouble();
                EXPECT_LE(d, 2 * b2_polygonWeldDistance.ToDouble() + 1e-9);
            }
        }
        // Input order does not matter: a reversed and rotated list gives the same polygon.
        std::vector<b2Vec2> shuffled(pts.rbegin(), pts.rend());
        std::rotate(shuffled.begin(), shuffled.begin() + static_cast<long>(trial % n), shuffled.end());
        b2PolygonShape again;
        ASSERT_EQ(again.SetFromHull(shuffled.data(), n), b2ShapeError::ok);
        ExpectSamePolygon(p, again);
    }
    std::printf("[hull] 3000 clouds: %d accepted, %d too many hull vertices, %d collinear, %d area too small\n",
                accepted, tooMany, collinear, areaSmall);
    EXPECT_GT(accepted, 2000);
}

TEST(ShapePolygon, SetFromHullHandlesInteriorAndCollinearPoints) {
    // A square's corners plus its centre, edge midpoints and duplicates: the hull is the square.
    const std::vector<b2Vec2> pts = {V(0, 0), V(1, 1),  V(-1, -1), V(1, -1),   V(0, -1),
                                     V(1, 1), V(-1, 1), V(1, 0),   V(-1, 0.5), V(0.5, 0.5)};
    b2PolygonShape p;
    ASSERT_EQ(p.SetFromHull(pts.data(), static_cast<int32>(pts.size())), b2ShapeError::ok);
    ASSERT_EQ(p.m_vertexCount, 4);
    // Starts at the lowest-x, lowest-y point and runs counter-clockwise.
    EXPECT_EQ(p.m_vertices[0], V(-1, -1));
    EXPECT_EQ(p.m_vertices[1], V(1, -1));
    EXPECT_EQ(p.m_vertices[2], V(1, 1));
    EXPECT_EQ(p.m_vertices[3], V(-1, 1));
    // A vertex 1 mm off the chord is welded away.
    const std::vector<b2Vec2> bent = {V(-1, -1), V(1, -1), V(1, 1), V(0, 1.001), V(-1, 1)};
    ASSERT_EQ(p.SetFromHull(bent.data(), 5), b2ShapeError::ok);
    EXPECT_EQ(p.m_vertexCount, 4);
    const std::vector<b2Vec2> line = {V(0, 0), V(1, 1), V(2, 2), V(3, 3)};
    EXPECT_EQ(p.SetFromHull(line.data(), 4), b2ShapeError::collinear);
    EXPECT_EQ(p.SetFromHull(line.data(), 2), b2ShapeError::tooFewVertices);
    const std::vector<b2Vec2> far = {V(0, 0), V(5000, 0), V(0, 1)};
    EXPECT_EQ(p.SetFromHull(far.data(), 3), b2ShapeError::outOfRange);
}

TEST(ShapePolygon, TestPointWithRotatedTransform) {
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(2, 1), b2ShapeError::ok);
    b2Transform xf(V(10, -5), b2Rot(F(0.5)));
    const double c = std::cos(0.5), s = std::sin(0.5);
    auto world = [&](double x, double y) { return V(10 + c * x - s * y, -5 + s * x + c * y); };
    EXPECT_TRUE(box.TestPoint(xf, world(0, 0)));
    EXPECT_TRUE(box.TestPoint(xf, world(1.99, 0.99)));
    EXPECT_TRUE(box.TestPoint(xf, world(-1.99, -0.5)));
    EXPECT_FALSE(box.TestPoint(xf, world(2.01, 0)));
    EXPECT_FALSE(box.TestPoint(xf, world(0, -1.01)));
    EXPECT_FALSE(box.TestPoint(xf, V(2, 1)));  // inside in the body frame, not in the world
    // Boundary counts as inside (identity transform: exact).
    EXPECT_TRUE(box.TestPoint(b2Transform(), V(2, 1)));
    EXPECT_FALSE(box.TestPoint(b2Transform(), b2Vec2(Fixed(2) + Fixed::FromRaw(1), Fixed(0))));
    EXPECT_FALSE(b2PolygonShape().TestPoint(b2Transform(), V(0, 0)));
}

TEST(ShapePolygon, RayCastHitMissClipAndInside) {
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(1, 1), b2ShapeError::ok);
    const b2Transform id;
    b2RayCastOutput out;
    b2RayCastInput in{V(-3, 0), V(3, 0), 1};
    ASSERT_TRUE(box.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, Fixed::FromRatio(1, 3));
    EXPECT_EQ(out.normal, V(-1, 0));
    // maxFraction clips: the hit at 1/3 is beyond 0.3.
    in.maxFraction = F(0.3);
    EXPECT_FALSE(box.RayCast(&out, in, id, 0));
    in.maxFraction = F(0.34);
    EXPECT_TRUE(box.RayCast(&out, in, id, 0));
    // Exactly at maxFraction: hit.
    in = {V(-3, 0), V(-1, 0), 1};
    ASSERT_TRUE(box.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, Fixed(1));
    // Miss: passes above; points away; parallel outside a face.
    in = {V(-3, 1.5), V(3, 1.5), 1};
    EXPECT_FALSE(box.RayCast(&out, in, id, 0));
    in = {V(-3, 0), V(-6, 0), 1};
    EXPECT_FALSE(box.RayCast(&out, in, id, 0));
    // Starting inside: no hit (2.2.1 semantics).
    in = {V(0, 0), V(5, 0), 1};
    EXPECT_FALSE(box.RayCast(&out, in, id, 0));
    // Zero-length ray outside.
    in = {V(-3, 0), V(-3, 0), 1};
    EXPECT_FALSE(box.RayCast(&out, in, id, 0));

    // Rotated and translated box against random rays: compare with a double reference.
    const b2Transform xf(V(4, 2), b2Rot(F(0.7)));
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-6, 10);
    int hits = 0;
    double maxErr = 0;
    for (int t = 0; t < 20000; ++t) {
        b2RayCastInput r{V(u(rng), u(rng)), V(u(rng), u(rng)), F(std::fabs(u(rng)) / 5)};
        const bool hit = box.RayCast(&out, r, xf, 0);
        // Reference: slab test in the box frame with doubles (box vertices are exact here).
        const double c = xf.q.c.ToDouble(), s = xf.q.s.ToDouble();
        auto local = [&](const b2Vec2& p) {
            const double dx = p.x.ToDouble() - 4, dy = p.y.ToDouble() - 2;
            return std::pair<double, double>{c * dx + s * dy, -s * dx + c * dy};
        };
        auto [x1, y1] = local(r.p1);
        auto [x2, y2] = local(r.p2);
        double lo = 0, hi = r.maxFraction.ToDouble();
        bool refHit = true, entered = false;
        const double p[2] = {x1, y1}, d[2] = {x2 - x1, y2 - y1};
        for (int i = 0; i < 2 && refHit; ++i) {
            if (d[i] == 0) {
                refHit = std::fabs(p[i]) <= 1;
                continue;
            }
            double t1 = (-1 - p[i]) / d[i], t2 = (1 - p[i]) / d[i];
            if (t1 > t2) std::swap(t1, t2);
            if (t1 > lo) {
                lo = t1;
                entered = true;
            }
            hi = std::min(hi, t2);
            refHit = lo <= hi;
        }
        refHit = refHit && entered;
        // Near-tangent and near-limit cases may differ by rounding: skip those within 1e-3.
        const double margin = std::min({std::fabs(lo - hi), std::fabs(lo - r.maxFraction.ToDouble()), lo});
        if (hit != refHit && margin < 1e-3) continue;
        ASSERT_EQ(hit, refHit) << t;
        if (hit) {
            ++hits;
            maxErr = std::max(maxErr, std::fabs(out.fraction.ToDouble() - lo));
            EXPECT_LE(UnitError(out.normal), 3.0 / 65536);
        }
    }
    std::printf("[polygon ray] 20000 rays, %d hits, max |fraction error| %.3g\n", hits, maxErr);
    EXPECT_GT(hits, 1000);
    EXPECT_LT(maxErr, 1e-3);
}

TEST(ShapePolygon, ComputeAABBIncludesRadiusUnderRotation) {
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(2, 1), b2ShapeError::ok);
    b2AABB aabb;
    box.ComputeAABB(&aabb, b2Transform(V(1, 1), b2Rot()), 0);
    EXPECT_EQ(aabb.lowerBound, b2Vec2(Fixed(-1) - b2_polygonRadius, Fixed(0) - b2_polygonRadius));
    EXPECT_EQ(aabb.upperBound, b2Vec2(Fixed(3) + b2_polygonRadius, Fixed(2) + b2_polygonRadius));
    // Rotated by 90 degrees: extents swap.
    box.ComputeAABB(&aabb, b2Transform(V(0, 0), b2Rot(F(1.5707963))), 0);
    EXPECT_NEAR(aabb.upperBound.x.ToDouble(), 1.01, 5e-5);
    EXPECT_NEAR(aabb.upperBound.y.ToDouble(), 2.01, 5e-5);
    EXPECT_NEAR(aabb.lowerBound.x.ToDouble(), -1.01, 5e-5);
    // 45 degrees: half-width (2 + 1) / sqrt(2).
    box.ComputeAABB(&aabb, b2Transform(V(0, 0), b2Rot(F(0.78539816))), 0);
    EXPECT_NEAR(aabb.upperBound.x.ToDouble(), 3 / std::sqrt(2.0) + 0.01, 5e-5);
    EXPECT_NEAR(aabb.lowerBound.y.ToDouble(), -3 / std::sqrt(2.0) - 0.01, 5e-5);
}

TEST(ShapePolygon, CloneKeepsTypeAndValue) {
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(1, 2, V(1, 1), F(0.2)), b2ShapeError::ok);
    const std::unique_ptr<b2Shape> clone = box.Clone();
    ASSERT_EQ(clone->GetType(), b2Shape::e_polygon);
    ExpectSamePolygon(*static_cast<const b2PolygonShape*>(clone.get()), box);
    EXPECT_EQ(clone->GetChildCount(), 1);
}

}  // namespace LOCKBOX_TEST_FILE
