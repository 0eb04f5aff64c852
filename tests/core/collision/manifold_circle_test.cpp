// b2CollideCircles and b2CollidePolygonAndCircle: table-driven cases with exact expectations
// (touching, separated by 1 raw, deep overlap, coincident centres, rotated frames, every
// Voronoi region of the polygon).

#include <cmath>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

b2CircleShape Circle(Fixed r, b2Vec2 p = b2Vec2()) {
    b2CircleShape c;
    c.m_radius = r;
    c.m_p = p;
    return c;
}

b2Transform At(Fixed x, Fixed y, Fixed angle = 0) {
    b2Transform xf;
    xf.Set(b2Vec2(x, y), angle);
    return xf;
}

struct CircleCase {
    const char* name;
    b2Vec2 pA;  ///< centre in body A
    Fixed rA;
    b2Transform xfA;
    b2Vec2 pB;
    Fixed rB;
    b2Transform xfB;
    int32 count;
};

TEST(ManifoldCircles, Table) {
    const Fixed oneRaw = Fixed::FromRaw(1);
    const CircleCase cases[] = {
        {"exactly touching", {0, 0}, 1, At(0, 0), {0, 0}, 1, At(2, 0), 1},
        {"one raw apart", {0, 0}, 1, At(0, 0), {0, 0}, 1, At(2 + oneRaw, 0), 0},
        {"separated", {0, 0}, 0.5_fx, At(0, 0), {0, 0}, 0.5_fx, At(0, 3), 0},
        {"deep overlap", {0, 0}, 2, At(1, 1), {0, 0}, 1, At(1.5_fx, 1), 1},
        {"coincident centres", {0, 0}, 1, At(4, 4), {0, 0}, 1, At(4, 4), 1},
        {"offset centres, rotated", {1, 0}, 1, At(0, 0, 1.5707963_fx), {0, -1}, 1.25_fx, At(0, 2, 3.14159_fx), 1},
        {"offset centres, rotated, apart",
         {1, 0},
         0.5_fx,
         At(0, 0, 1.5707963_fx),
         {0, -1},
         0.5_fx,
         At(0, 2, 3.14159_fx),
         0},
        {"contact-scale radii touching",
         {0, 0},
         b2_linearSlop,
         At(0, 0),
         {0, 0},
         b2_linearSlop,
         At(b2_linearSlop + b2_linearSlop, 0),
         1},
        {"contact-scale radii 1 raw apart",
         {0, 0},
         b2_linearSlop,
         At(0, 0),
         {0, 0},
         b2_linearSlop,
         At(b2_linearSlop + b2_linearSlop + oneRaw, 0),
         0},
    };
    for (const CircleCase& c : cases) {
        SCOPED_TRACE(c.name);
        const b2CircleShape a = Circle(c.rA, c.pA), b = Circle(c.rB, c.pB);
        b2Manifold m;
        m.pointCount = 5;  // must be overwritten
        b2CollideCircles(&m, &a, c.xfA, &b, c.xfB);
        ASSERT_EQ(m.pointCount, c.count);
        if (c.count == 0) continue;
        EXPECT_EQ(m.type, b2Manifold::e_circles);
        EXPECT_EQ(m.localPoint, c.pA);
        EXPECT_EQ(m.points[0].localPoint, c.pB);
        EXPECT_EQ(m.points[0].id.Key(), 0u);
    }
}

TEST(ManifoldCircles, WorldSeparationMatchesGeometry) {
    // A's centre (1, 0) turned by 90 degrees sits at (0, 1); B's (0, -1) turned by 180
    // degrees at (0, 3): 2 m apart, overlapping by 0.5 m with radii 1.25.
    const b2CircleShape a = Circle(1.25_fx, {1, 0}), b = Circle(1.25_fx, {0, -1});
    const b2Transform xfA = At(0, 0, 1.5707963_fx), xfB = At(0, 2, 3.14159_fx);
    b2Manifold m;
    b2CollideCircles(&m, &a, xfA, &b, xfB);
    ASSERT_EQ(m.pointCount, 1);
    b2WorldManifold wm;
    wm.Initialize(&m, xfA, a.m_radius, xfB, b.m_radius);
    EXPECT_NEAR(wm.normal.x.ToDouble(), 0, 1e-4);
    EXPECT_NEAR(wm.normal.y.ToDouble(), 1, 1e-4);
    EXPECT_NEAR(wm.separations[0].ToDouble(), 2 - 2.5, 1e-4);
    EXPECT_NEAR(wm.points[0].y.ToDouble(), 2.0, 1e-4);
}

b2PolygonShape Box(Fixed hx, Fixed hy) {
    b2PolygonShape p;
    EXPECT_EQ(p.SetAsBox(hx, hy), b2ShapeError::ok);
    return p;
}

struct PolyCircleCase {
    const char* name;
    b2Vec2 center;  ///< circle centre in the box frame (box at the origin, unrotated)
    Fixed radius;
    int32 count;
    b2Vec2 localNormal;
    b2Vec2 localPoint;
};

TEST(ManifoldPolygonCircle, RegionsOfAUnitBox) {
    // Box of half-size 1 (skin 0.01): vertices (-1,-1) (1,-1) (1,1) (-1,1); faces 0 bottom,
    // 1 right, 2 top, 3 left.
    const Fixed r = 0.5_fx;
    const Fixed skinTouch = 1 + b2_polygonRadius + r;  // face distance at which they touch
    const Fixed invSqrt2 = Fixed::FromRaw(46341);
    const PolyCircleCase cases[] = {
        {"face region, overlapping", {0, 1.25_fx}, r, 1, {0, 1}, {0, 1}},
        {"face region, exactly touching the skin", {0.25_fx, skinTouch}, r, 1, {0, 1}, {0, 1}},
        {"face region, 1 raw beyond", {0.25_fx, skinTouch + Fixed::FromRaw(1)}, r, 0, {}, {}},
        {"right face", {1.25_fx, -0.5_fx}, r, 1, {1, 0}, {1, 0}},
        {"vertex region", {1.25_fx, 1.25_fx}, r, 1, {invSqrt2, invSqrt2}, {1, 1}},
        {"vertex region, separated", {1.375_fx, 1.375_fx}, r, 0, {}, {}},
        {"vertex region v1 of face 0",
         {-1.25_fx, -1.125_fx},
         r,
         1,
         {Fixed::FromRaw(-58617), Fixed::FromRaw(-29309)},
         {-1, -1}},
        {"centre inside, nearest the right face", {0.25_fx, 0.125_fx}, r, 1, {1, 0}, {1, 0}},
        {"centre exactly on the top face", {0.5_fx, 1}, r, 1, {0, 1}, {0, 1}},
        {"centre at the origin: first face wins ties", {0, 0}, r, 1, {0, -1}, {0, -1}},
        {"far away", {5, 5}, r, 0, {}, {}},
    };
    const b2PolygonShape box = Box(1, 1);
    for (const PolyCircleCase& c : cases) {
        SCOPED_TRACE(c.name);
        b2CircleShape circle = Circle(c.radius);
        b2Manifold m;
        b2CollidePolygonAndCircle(&m, &box, b2Transform(), &circle, b2Transform(c.center, b2Rot()));
        ASSERT_EQ(m.pointCount, c.count);
        if (c.count == 0) continue;
        EXPECT_EQ(m.type, b2Manifold::e_faceA);
        EXPECT_EQ(m.localNormal, c.localNormal);
        EXPECT_EQ(m.localPoint, c.localPoint);
        EXPECT_EQ(m.points[0].localPoint, b2Vec2());
        EXPECT_EQ(m.points[0].id.Key(), 0u);
    }
}

TEST(ManifoldPolygonCircle, RotatedBoxWorldManifold) {
    // Box turned by 45 degrees: its corner (1,1) points along +y at height sqrt(2). A circle of
    // radius 0.5 centred at height 1.75 overlaps the corner by sqrt(2) + 0.01 + 0.5 - 1.75.
    const b2PolygonShape box = Box(1, 1);
    const b2CircleShape circle = Circle(0.5_fx);
    const b2Transform xfA = At(10, -3, 0.785398_fx);
    const b2Transform xfB(b2Vec2(10, -3 + 1.75_fx), b2Rot());
    b2Manifold m;
    b2CollidePolygonAndCircle(&m, &box, xfA, &circle, xfB);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_EQ(m.localPoint, b2Vec2(1, 1));
    b2WorldManifold wm;
    wm.Initialize(&m, xfA, box.m_radius, xfB, circle.m_radius);
    EXPECT_NEAR(wm.normal.x.ToDouble(), 0, 2e-4);
    EXPECT_NEAR(wm.normal.y.ToDouble(), 1, 2e-4);
    const double expectedSep = 1.75 - std::sqrt(2.0) - 0.5 - b2_polygonRadius.ToDouble();
    EXPECT_NEAR(wm.separations[0].ToDouble(), expectedSep, 1e-4);
}

TEST(ManifoldPolygonCircle, CentreOnAVertexGetsAUnitNormal) {
    // The circle centre exactly on a box corner: whatever region wins, the normal must be a
    // unit vector (never the normalised zero vector).
    const b2PolygonShape box = Box(1, 1);
    const b2CircleShape circle = Circle(0.25_fx);
    for (const b2Vec2& corner : {b2Vec2(1, 1), b2Vec2(-1, 1), b2Vec2(-1, -1), b2Vec2(1, -1)}) {
        b2Manifold m;
        b2CollidePolygonAndCircle(&m, &box, b2Transform(), &circle, b2Transform(corner, b2Rot()));
        ASSERT_EQ(m.pointCount, 1);
        EXPECT_NEAR(m.localNormal.Length().ToDouble(), 1.0, 1e-4);
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
