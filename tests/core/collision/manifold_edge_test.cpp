// b2CollideEdgeAndCircle and b2CollideEdgeAndPolygon: every region of the edge, both sides,
// with and without ghost vertices, convex and concave corners, and the chain seam (a box
// across the joint of two chain edges must get the seam-free normal, never an internal one).

#include <cmath>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

constexpr uint8 kFace = b2ContactFeature::e_face;
constexpr uint8 kVertex = b2ContactFeature::e_vertex;

b2EdgeShape Edge(b2Vec2 v1, b2Vec2 v2) {
    b2EdgeShape e;
    EXPECT_EQ(e.Set(v1, v2), b2ShapeError::ok);
    return e;
}

b2EdgeShape EdgeWithGhosts(b2Vec2 v0, b2Vec2 v1, b2Vec2 v2, b2Vec2 v3, bool has0 = true, bool has3 = true) {
    b2EdgeShape e = Edge(v1, v2);
    e.m_vertex0 = v0;
    e.m_vertex3 = v3;
    e.m_hasVertex0 = has0;
    e.m_hasVertex3 = has3;
    return e;
}

b2CircleShape Circle(Fixed r) {
    b2CircleShape c;
    c.m_radius = r;
    return c;
}

b2Transform At(Fixed x, Fixed y, Fixed angle = 0) {
    b2Transform xf;
    xf.Set(b2Vec2(x, y), angle);
    return xf;
}

struct EdgeCircleCase {
    const char* name;
    b2EdgeShape edge;
    b2Vec2 center;
    int32 count;
    b2Manifold::Type type;
    b2Vec2 localNormal;
    b2Vec2 localPoint;
    uint8 indexA, typeA;
};

TEST(ManifoldEdgeCircle, Regions) {
    // Edge from (-1, 0) to (1, 0); circle radius 0.5; contact radius 0.5 + 0.01.
    const b2EdgeShape plain = Edge({-1, 0}, {1, 0});
    const b2EdgeShape ghosts = EdgeWithGhosts({-2, 0}, {-1, 0}, {1, 0}, {2, 0});
    const b2EdgeShape convexGhosts = EdgeWithGhosts({-2, -1}, {-1, 0}, {1, 0}, {2, -1});
    const Fixed touch = 0.5_fx + b2_polygonRadius;
    const Fixed r2 = Fixed::FromRaw(46341);  // 1/sqrt(2)
    const EdgeCircleCase cases[] = {
        {"face, above", plain, {0, 0.375_fx}, 1, b2Manifold::e_faceA, {0, 1}, {-1, 0}, 0, kFace},
        {"face, below", plain, {0.5_fx, -0.375_fx}, 1, b2Manifold::e_faceA, {0, -1}, {-1, 0}, 0, kFace},
        {"face, exactly touching", plain, {0.25_fx, touch}, 1, b2Manifold::e_faceA, {0, 1}, {-1, 0}, 0, kFace},
        {"face, 1 raw beyond", plain, {0.25_fx, touch + Fixed::FromRaw(1)}, 0, {}, {}, {}, 0, 0},
        {"vertex A region", plain, {-1.25_fx, 0.25_fx}, 1, b2Manifold::e_circles, {}, {-1, 0}, 0, kVertex},
        {"vertex B region", plain, {1.25_fx, -0.25_fx}, 1, b2Manifold::e_circles, {}, {1, 0}, 1, kVertex},
        {"vertex B region, separated", plain, {1.375_fx, 0.375_fx}, 0, {}, {}, {}, 0, 0},
        {"exactly above the end point: vertex region",
         plain,
         {1, 0.25_fx},
         1,
         b2Manifold::e_circles,
         {},
         {1, 0},
         1,
         kVertex},
        {"ghost after B: next edge owns the contact", ghosts, {1.25_fx, 0.25_fx}, 0, {}, {}, {}, 0, 0},
        {"ghost before A: previous edge owns it", ghosts, {-1.25_fx, 0.25_fx}, 0, {}, {}, {}, 0, 0},
        {"ghosts do not change the face region",
         ghosts,
         {0, 0.375_fx},
         1,
         b2Manifold::e_faceA,
         {0, 1},
         {-1, 0},
         0,
         kFace},
        {"convex corner: vertex region kept",
         convexGhosts,
         {1.25_fx, 0.25_fx},
         1,
         b2Manifold::e_circles,
         {},
         {1, 0},
         1,
         kVertex},
        {"diagonal face",
         Edge({0, 0}, {2, 2}),
         {0.75_fx, 1.25_fx},
         1,
         b2Manifold::e_faceA,
         {-r2, r2},
         {0, 0},
         0,
         kFace},
    };
    const b2CircleShape circle = Circle(0.5_fx);
    for (const EdgeCircleCase& c : cases) {
        SCOPED_TRACE(c.name);
        b2Manifold m;
        b2CollideEdgeAndCircle(&m, &c.edge, b2Transform(), &circle, b2Transform(c.center, b2Rot()));
        ASSERT_EQ(m.pointCount, c.count);
        if (c.count == 0) continue;
        EXPECT_EQ(m.type, c.type);
        if (c.type == b2Manifold::e_faceA) {
            EXPECT_EQ(m.localNormal, c.localNormal);
        }
        EXPECT_EQ(m.localPoint, c.localPoint);
        EXPECT_EQ(m.points[0].localPoint, b2Vec2());
        EXPECT_EQ(m.points[0].id.cf.indexA, c.indexA);
        EXPECT_EQ(m.points[0].id.cf.typeA, c.typeA);
        EXPECT_EQ(m.points[0].id.cf.indexB, 0);
        EXPECT_EQ(m.points[0].id.cf.typeB, kVertex);
    }
}

TEST(ManifoldEdgeCircle, RotatedEdgeWorldManifold) {
    // A 4 m edge turned by 30 degrees; a circle 0.25 m above its middle, radius 0.5.
    const b2EdgeShape e = Edge({-2, 0}, {2, 0});
    const b2CircleShape circle = Circle(0.5_fx);
    const b2Transform xfA = At(5, 7, 0.5235988_fx);
    const b2Transform xfB(b2Mul(xfA, b2Vec2(0.5_fx, 0.25_fx)), b2Rot());
    b2Manifold m;
    b2CollideEdgeAndCircle(&m, &e, xfA, &circle, xfB);
    ASSERT_EQ(m.pointCount, 1);
    b2WorldManifold wm;
    wm.Initialize(&m, xfA, e.m_radius, xfB, circle.m_radius);
    EXPECT_NEAR(wm.normal.x.ToDouble(), -0.5, 3e-5);
    EXPECT_NEAR(wm.normal.y.ToDouble(), std::sqrt(0.75), 3e-5);
    EXPECT_NEAR(wm.separations[0].ToDouble(), 0.25 - 0.5 - b2_polygonRadius.ToDouble(), 5e-5);
}

b2PolygonShape Box(Fixed hx, Fixed hy) {
    b2PolygonShape p;
    EXPECT_EQ(p.SetAsBox(hx, hy), b2ShapeError::ok);
    return p;
}

TEST(ManifoldEdgePolygon, BoxRestingOnFrontSide) {
    // Edge (2,0) -> (-2,0): its right-hand normal (e.y, -e.x) points up, so a box above is in
    // front. Box of half-size 0.5 with 5 mm of penetration.
    const b2EdgeShape e = Edge({2, 0}, {-2, 0});
    const b2PolygonShape box = Box(0.5_fx, 0.5_fx);
    const b2Transform xfB = At(0.25_fx, 0.5_fx - b2_linearSlop);
    b2Manifold m;
    b2CollideEdgeAndPolygon(&m, &e, b2Transform(), &box, xfB);
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_EQ(m.type, b2Manifold::e_faceA);
    EXPECT_EQ(m.localNormal, b2Vec2(0, 1));
    EXPECT_EQ(m.localPoint, b2Vec2(2, 0));
    // Incident face: the box bottom (face 0, vertices 0 and 1), unclipped and exact.
    EXPECT_EQ(m.points[0].localPoint, b2Vec2(-0.5_fx, -0.5_fx));
    EXPECT_EQ(m.points[1].localPoint, b2Vec2(0.5_fx, -0.5_fx));
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(m.points[i].id.cf.indexA, 0);
        EXPECT_EQ(m.points[i].id.cf.indexB, i);
        EXPECT_EQ(m.points[i].id.cf.typeA, kFace);
        EXPECT_EQ(m.points[i].id.cf.typeB, kVertex);
    }
    b2WorldManifold wm;
    wm.Initialize(&m, b2Transform(), e.m_radius, xfB, box.m_radius);
    EXPECT_EQ(wm.normal, b2Vec2(0, 1));
    EXPECT_EQ(wm.separations[0], -(b2_linearSlop + b2_polygonRadius + b2_polygonRadius));
}

TEST(ManifoldEdgePolygon, BoxOnBackSideUsesTheFlippedFace) {
    // Edge (-2,0) -> (2,0): its right-hand normal points down, the box above is behind it.
    const b2EdgeShape e = Edge({-2, 0}, {2, 0});
    const b2PolygonShape box = Box(0.5_fx, 0.5_fx);
    b2Manifold m;
    b2CollideEdgeAndPolygon(&m, &e, b2Transform(), &box, At(0, 0.5_fx - b2_linearSlop));
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_EQ(m.type, b2Manifold::e_faceA);
    EXPECT_EQ(m.localNormal, b2Vec2(0, 1));
    EXPECT_EQ(m.localPoint, b2Vec2(2, 0));  // rf.v1 = m_v2 on the back side
}

struct GapCase {
    const char* name;
    Fixed gap;
    int32 count;
};

TEST(ManifoldEdgePolygon, SkinThreshold) {
    // 2.2.1 uses 2 * polygonRadius as the contact distance, whatever the shape radii.
    const b2EdgeShape e = Edge({2, 0}, {-2, 0});
    const b2PolygonShape box = Box(0.5_fx, 0.5_fx);
    const Fixed skins = b2_polygonRadius + b2_polygonRadius;
    const GapCase cases[] = {
        {"deep", -0.25_fx, 2},
        {"touching", 0, 2},
        {"skins exactly touching", skins, 2},
        {"1 raw beyond", skins + Fixed::FromRaw(1), 0},
        {"far", 1, 0},
    };
    for (const GapCase& c : cases) {
        SCOPED_TRACE(c.name);
        b2Manifold m;
        b2CollideEdgeAndPolygon(&m, &e, b2Transform(), &box, At(0, 0.5_fx + c.gap));
        EXPECT_EQ(m.pointCount, c.count);
    }
}

TEST(ManifoldEdgePolygon, DiamondOnEdgeOnePointFaceB) {
    // A box turned by 45 degrees touching the edge with a corner: either reference gives the
    // contact at the corner with the edge normal within the box's cone.
    const b2EdgeShape e = Edge({2, 0}, {-2, 0});
    const b2PolygonShape box = Box(0.5_fx, 0.5_fx);
    const b2Transform xfB =
        At(0.3_fx, Fixed::FromDoubleNondeterministic(0.5 * std::sqrt(2.0)) - b2_linearSlop, 0.7853982_fx);
    b2Manifold m;
    b2CollideEdgeAndPolygon(&m, &e, b2Transform(), &box, xfB);
    ASSERT_EQ(m.pointCount, 1);
    b2WorldManifold wm;
    wm.Initialize(&m, b2Transform(), e.m_radius, xfB, box.m_radius);
    EXPECT_NEAR(wm.normal.x.ToDouble(), 0, 1e-4);
    EXPECT_NEAR(wm.normal.y.ToDouble(), 1, 1e-4);
    EXPECT_NEAR(wm.points[0].x.ToDouble(), 0.3, 1e-4);
}

/// World normals of every contact between `box` at xfB and the children of `chain`.
std::vector<b2Vec2> ChainNormals(const b2ChainShape& chain, const b2PolygonShape& box, const b2Transform& xfB) {
    std::vector<b2Vec2> normals;
    for (int32 i = 0; i < chain.GetChildCount(); ++i) {
        b2EdgeShape edge;
        chain.GetChildEdge(&edge, i);
        b2Manifold m;
        b2CollideEdgeAndPolygon(&m, &edge, b2Transform(), &box, xfB);
        if (m.pointCount == 0) continue;
        b2WorldManifold wm;
        wm.Initialize(&m, b2Transform(), edge.m_radius, xfB, box.m_radius);
        normals.push_back(wm.normal);
    }
    return normals;
}

TEST(ManifoldEdgePolygon, ChainSeamGivesNoInternalNormal) {
    // Flat ground as a chain (4,0) -> (0,0) -> (-4,0) (normals up). A box of half-size 0.5
    // sunk 5 cm with its right side 1 cm past the seam: against the first edge alone the
    // box's right face is the shallowest axis (1 cm < 5 cm), an internal horizontal normal
    // that would catch a sliding box. The ghost vertices must rule it out.
    const b2Vec2 ground[] = {{4, 0}, {0, 0}, {-4, 0}};
    b2ChainShape chain;
    ASSERT_EQ(chain.CreateChain(ground, 3), b2ShapeError::ok);
    const b2PolygonShape box = Box(0.5_fx, 0.5_fx);
    for (const Fixed x : {-0.49_fx, -0.25_fx, Fixed(0), 0.25_fx, 0.49_fx}) {
        for (const Fixed angle : {Fixed(0), 0.02_fx, -0.02_fx}) {
            SCOPED_TRACE(x.ToDouble());
            SCOPED_TRACE(angle.ToDouble());
            const b2Transform xfB = At(x, 0.45_fx, angle);
            const std::vector<b2Vec2> normals = ChainNormals(chain, box, xfB);
            ASSERT_FALSE(normals.empty());
            // Either the ground normal (0, 1) or, for the tilted box, its bottom face's
            // normal (-sin 0.02, cos 0.02): never anything near horizontal.
            for (const b2Vec2& n : normals) {
                EXPECT_LE(std::fabs(n.x.ToDouble()), std::sin(0.02) + 1e-4);
                EXPECT_GE(n.y.ToDouble(), std::cos(0.02) - 1e-4);
            }
        }
    }
    // Control: the same edge without ghosts does produce the internal normal.
    const b2EdgeShape lone = Edge({4, 0}, {0, 0});
    const b2Transform xfB = At(-0.49_fx, 0.45_fx);
    b2Manifold m;
    b2CollideEdgeAndPolygon(&m, &lone, b2Transform(), &box, xfB);
    ASSERT_GT(m.pointCount, 0);
    b2WorldManifold wm;
    wm.Initialize(&m, b2Transform(), lone.m_radius, xfB, box.m_radius);
    EXPECT_NEAR(std::fabs(wm.normal.x.ToDouble()), 1, 1e-4);
}

TEST(ManifoldEdgePolygon, ConcaveCornerAcceptsBothFaces) {
    // A V-shaped valley: (-2,2) -> (0,0) -> (2,2) as a chain (normals up into the valley... the
    // chain goes right to left for upward normals: (2,2) -> (0,0) -> (-2,2)). A box dropped
    // into the corner touches both edges, each with its own face normal.
    const b2Vec2 valley[] = {{2, 2}, {0, 0}, {-2, 2}};
    b2ChainShape chain;
    ASSERT_EQ(chain.CreateChain(valley, 3), b2ShapeError::ok);
    const b2PolygonShape box = Box(0.25_fx, 0.25_fx);
    // The box corner sits in the valley, the box turned 45 degrees so its sides lie on the
    // edges, sunk a little.
    const b2Transform xfB = At(0, Fixed::FromDoubleNondeterministic(0.25 * std::sqrt(2.0)) - 0.01_fx, 0.7853982_fx);
    const std::vector<b2Vec2> normals = ChainNormals(chain, box, xfB);
    ASSERT_EQ(normals.size(), 2u);
    const double r2 = std::sqrt(0.5);
    EXPECT_NEAR(normals[0].x.ToDouble(), -r2, 1e-3);
    EXPECT_NEAR(normals[0].y.ToDouble(), r2, 1e-3);
    EXPECT_NEAR(normals[1].x.ToDouble(), r2, 1e-3);
    EXPECT_NEAR(normals[1].y.ToDouble(), r2, 1e-3);
}

TEST(ManifoldEdgePolygon, ConvexCornerLimitsTheNormalRange) {
    // A hill top: (2,-1) -> (0,0) -> (-2,-1) (normals outward, up). A box centred over the
    // apex may take any normal between the two face normals; never one pointing below them.
    const b2Vec2 hill[] = {{2, -1}, {0, 0}, {-2, -1}};
    b2ChainShape chain;
    ASSERT_EQ(chain.CreateChain(hill, 3), b2ShapeError::ok);
    const b2PolygonShape box = Box(0.5_fx, 0.25_fx);
    const std::vector<b2Vec2> normals = ChainNormals(chain, box, At(0, 0.25_fx));
    ASSERT_FALSE(normals.empty());
    for (const b2Vec2& n : normals) {
        // Face normals are (+-1, 2)/sqrt(5): y >= 2/sqrt(5) - tolerance.
        EXPECT_GE(n.y.ToDouble(), 2 / std::sqrt(5.0) - 1e-3);
    }
}

TEST(ManifoldEdgePolygon, OneSidedGhostFlagsAreHonoured) {
    // Only m_vertex3 set (the end of an open chain): the box past the v1 end still collides
    // with the bare vertex, while the v2 end defers to the next edge.
    const b2EdgeShape e = EdgeWithGhosts({6, 0}, {4, 0}, {0, 0}, {-4, 0}, false, true);
    const b2PolygonShape box = Box(0.5_fx, 0.5_fx);
    b2Manifold m;
    b2CollideEdgeAndPolygon(&m, &e, b2Transform(), &box, At(-0.49_fx, 0.45_fx));
    ASSERT_GT(m.pointCount, 0);
    b2WorldManifold wm;
    wm.Initialize(&m, b2Transform(), e.m_radius, At(-0.49_fx, 0.45_fx), box.m_radius);
    EXPECT_NEAR(wm.normal.y.ToDouble(), 1, 1e-4);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
