// b2WorldManifold::Initialize, b2GetPointStates and b2ClipSegmentToLine against hand-computed
// values. Every expected value is exact in Q16.16, so most checks are bit-exact.

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/Collision.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

b2Transform At(Fixed x, Fixed y) { return b2Transform(b2Vec2(x, y), b2Rot()); }

b2Rot Quarter() {
    b2Rot q;  // +90 degrees, exactly
    q.s = 1;
    q.c = 0;
    return q;
}

TEST(ManifoldWorld, CirclesNormalPointAndSeparation) {
    b2Manifold m;
    m.type = b2Manifold::e_circles;
    m.pointCount = 1;
    m.localPoint = b2Vec2(0, 0);
    m.points[0].localPoint = b2Vec2(0, 0);
    b2WorldManifold wm;
    wm.Initialize(&m, At(1, 2), 1, At(2.5_fx, 2), 1);
    EXPECT_EQ(wm.normal, b2Vec2(1, 0));
    // cA = (2, 2), cB = (1.5, 2): midpoint (1.75, 2), separation 1.5 - 2.
    EXPECT_EQ(wm.points[0], b2Vec2(1.75_fx, 2));
    EXPECT_EQ(wm.separations[0], -0.5_fx);
}

TEST(ManifoldWorld, CirclesDiagonalNormalIsUnit) {
    b2Manifold m;
    m.type = b2Manifold::e_circles;
    m.pointCount = 1;
    m.localPoint = b2Vec2(0, 0);
    m.points[0].localPoint = b2Vec2(0, 0);
    b2WorldManifold wm;
    wm.Initialize(&m, At(0, 0), 0.5_fx, At(3, 4), 0.25_fx);
    EXPECT_EQ(wm.normal, b2Vec2(0.6_fx, 0.8_fx));
    EXPECT_EQ(wm.separations[0], 4.25_fx);
    // Midpoint of cA = (0.3, 0.4) and cB = (2.85, 3.8).
    EXPECT_NEAR(wm.points[0].x.ToDouble(), 1.575, 2e-5);
    EXPECT_NEAR(wm.points[0].y.ToDouble(), 2.1, 2e-5);
}

TEST(ManifoldWorld, CoincidentCirclesKeepTheDefaultNormal) {
    b2Manifold m;
    m.type = b2Manifold::e_circles;
    m.pointCount = 1;
    b2WorldManifold wm;
    wm.Initialize(&m, At(3, 3), 1, At(3, 3), 0.5_fx);
    EXPECT_EQ(wm.normal, b2Vec2(1, 0));
    EXPECT_EQ(wm.separations[0], -1.5_fx);
    EXPECT_EQ(wm.points[0], b2Vec2(3.25_fx, 3));
}

TEST(ManifoldWorld, CirclesOneRawApartStillGetADirection) {
    b2Manifold m;
    m.type = b2Manifold::e_circles;
    m.pointCount = 1;
    b2WorldManifold wm;
    wm.Initialize(&m, At(0, 0), 1, b2Transform(b2Vec2(0, Fixed::FromRaw(1)), b2Rot()), 1);
    EXPECT_EQ(wm.normal, b2Vec2(0, 1));
}

TEST(ManifoldWorld, FaceA) {
    b2Manifold m;
    m.type = b2Manifold::e_faceA;
    m.pointCount = 1;
    m.localNormal = b2Vec2(0, 1);
    m.localPoint = b2Vec2(0, 0.5_fx);
    m.points[0].localPoint = b2Vec2(0, -0.5_fx);
    b2WorldManifold wm;
    wm.Initialize(&m, At(0, 0), 0.25_fx, At(0.25_fx, 0.875_fx), 0.125_fx);
    // clip point (0.25, 0.375), 0.125 below the plane: cA y 0.75, cB y 0.25.
    EXPECT_EQ(wm.normal, b2Vec2(0, 1));
    EXPECT_EQ(wm.points[0], b2Vec2(0.25_fx, 0.5_fx));
    EXPECT_EQ(wm.separations[0], -0.5_fx);
}

TEST(ManifoldWorld, FaceBRotatedPointsFromAToB) {
    b2Manifold m;
    m.type = b2Manifold::e_faceB;
    m.pointCount = 2;
    m.localNormal = b2Vec2(1, 0);      // world (0, 1) after the quarter turn
    m.localPoint = b2Vec2(0.5_fx, 0);  // world (0, 1.5)
    m.points[0].localPoint = b2Vec2(0.25_fx, 1.25_fx);
    m.points[1].localPoint = b2Vec2(-0.75_fx, 1.75_fx);
    b2WorldManifold wm;
    wm.Initialize(&m, At(0, 0), 0.125_fx, b2Transform(b2Vec2(0, 1), Quarter()), 0.25_fx);
    EXPECT_EQ(wm.normal, b2Vec2(0, -1));
    // Point 0: 0.25 below B's face: cB y 1.75, cA y 1.125.
    EXPECT_EQ(wm.points[0], b2Vec2(0.25_fx, 1.4375_fx));
    EXPECT_EQ(wm.separations[0], -0.625_fx);
    // Point 1: 0.25 above B's face: separated by 0.25 - 0.375.
    EXPECT_EQ(wm.separations[1], -0.125_fx);
    EXPECT_EQ(wm.points[1], b2Vec2(-0.75_fx, 1.6875_fx));
}

TEST(ManifoldWorld, EmptyManifoldLeavesOutputAlone) {
    b2Manifold m;
    b2WorldManifold wm;
    wm.normal = b2Vec2(7, 7);
    wm.Initialize(&m, At(0, 0), 1, At(0, 0), 1);
    EXPECT_EQ(wm.normal, b2Vec2(7, 7));
}

b2ContactID Id(uint8 a, uint8 b, uint8 ta, uint8 tb) {
    b2ContactID id;
    id.cf.indexA = a;
    id.cf.indexB = b;
    id.cf.typeA = ta;
    id.cf.typeB = tb;
    return id;
}

TEST(ManifoldPointStates, AddPersistRemove) {
    b2Manifold m1, m2;
    m1.pointCount = 2;
    m1.points[0].id = Id(2, 0, 1, 0);
    m1.points[1].id = Id(2, 1, 1, 0);
    m2.pointCount = 2;
    m2.points[0].id = Id(2, 1, 1, 0);
    m2.points[1].id = Id(3, 1, 0, 1);
    b2PointState s1[2], s2[2];
    b2GetPointStates(s1, s2, &m1, &m2);
    EXPECT_EQ(s1[0], b2_removeState);
    EXPECT_EQ(s1[1], b2_persistState);
    EXPECT_EQ(s2[0], b2_persistState);
    EXPECT_EQ(s2[1], b2_addState);
}

TEST(ManifoldPointStates, EmptyAndFull) {
    b2Manifold empty, one;
    one.pointCount = 1;
    one.points[0].id = Id(0, 0, 0, 0);
    b2PointState s1[2], s2[2];
    b2GetPointStates(s1, s2, &empty, &one);
    EXPECT_EQ(s1[0], b2_nullState);
    EXPECT_EQ(s1[1], b2_nullState);
    EXPECT_EQ(s2[0], b2_addState);
    EXPECT_EQ(s2[1], b2_nullState);
    b2GetPointStates(s1, s2, &one, &empty);
    EXPECT_EQ(s1[0], b2_removeState);
    EXPECT_EQ(s2[0], b2_nullState);
    // A feature that differs only in its type byte is a different point.
    b2Manifold other = one;
    other.points[0].id = Id(0, 0, 1, 0);
    b2GetPointStates(s1, s2, &one, &other);
    EXPECT_EQ(s1[0], b2_removeState);
    EXPECT_EQ(s2[0], b2_addState);
}

struct ClipCase {
    const char* name;
    b2Vec2 v0, v1;
    b2Vec2 normal;
    Fixed offset;
    int32 expectedCount;
    b2Vec2 expected[2];
    bool secondIsNew;  ///< the last output vertex is the intersection
};

TEST(ManifoldClip, Table) {
    const ClipCase cases[] = {
        {"both behind", {0, 0}, {2, 0}, {1, 0}, 3, 2, {{0, 0}, {2, 0}}, false},
        {"both in front", {0, 0}, {2, 0}, {1, 0}, -1, 0, {}, false},
        {"straddles", {0, 0}, {2, 0}, {1, 0}, 1, 2, {{0, 0}, {1, 0}}, true},
        {"straddles reversed", {2, 0}, {0, 0}, {1, 0}, 1, 2, {{0, 0}, {1, 0}}, true},
        {"end point on the line counts as behind", {0, 0}, {1, 0}, {1, 0}, 1, 2, {{0, 0}, {1, 0}}, false},
        {"inexact intersection rounds once", {0, 0}, {3, 1}, {1, 0}, 1, 2, {{0, 0}, {1, Fixed::FromRaw(21845)}}, true},
        {"diagonal normal", {-1, 1}, {1, -1}, {0.6_fx, 0.8_fx}, 0, 2, {{1, -1}, {0, 0}}, true},
    };
    for (const ClipCase& c : cases) {
        SCOPED_TRACE(c.name);
        b2ClipVertex in[2], out[2];
        in[0].v = c.v0;
        in[0].id = Id(9, 4, 1, 0);
        in[1].v = c.v1;
        in[1].id = Id(9, 5, 1, 0);
        const int32 n = b2ClipSegmentToLine(out, in, c.normal, c.offset, 7);
        ASSERT_EQ(n, c.expectedCount);
        for (int32 i = 0; i < n; ++i) EXPECT_EQ(out[i].v, c.expected[i]) << i;
        if (c.secondIsNew) {
            // The new vertex: vertex 7 of A on the face of B that vIn[0] came from.
            EXPECT_EQ(out[1].id.cf.indexA, 7);
            EXPECT_EQ(out[1].id.cf.indexB, in[0].id.cf.indexB);
            EXPECT_EQ(out[1].id.cf.typeA, b2ContactFeature::e_vertex);
            EXPECT_EQ(out[1].id.cf.typeB, b2ContactFeature::e_face);
        } else if (n == 2) {
            EXPECT_EQ(out[1].id.Key(), in[1].id.Key());
        }
    }
}

TEST(ManifoldClip, IntersectionStaysOnTheSegmentForTinyDistances) {
    // d0 = +1 raw Q32.32 above the line, d1 far below: the intersection is v0 within 1 raw.
    b2ClipVertex in[2], out[2];
    in[0].v = b2Vec2(Fixed::FromRaw(1), 5);
    in[1].v = b2Vec2(-100, -7);
    const int32 n = b2ClipSegmentToLine(out, in, b2Vec2(1, 0), 0, 0);
    ASSERT_EQ(n, 2);
    EXPECT_EQ(out[0].v, in[1].v);
    EXPECT_EQ(out[1].v.x, 0);
    EXPECT_NEAR(out[1].v.y.ToDouble(), 5.0, 2e-4);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
