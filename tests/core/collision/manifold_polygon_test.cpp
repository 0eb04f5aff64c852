// b2CollidePolygons: resting, separated, within the skin, overhanging (clipped), reference face
// on B (feature swap), vertex-face contact, deep overlap and rotated frames; feature ids as
// Box2D 2.2.1 builds them.

#include <cmath>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

b2PolygonShape Box(Fixed hx, Fixed hy) {
    b2PolygonShape p;
    EXPECT_EQ(p.SetAsBox(hx, hy), b2ShapeError::ok);
    return p;
}

b2Transform At(Fixed x, Fixed y) { return b2Transform(b2Vec2(x, y), b2Rot()); }

b2ContactFeature Cf(uint8 ia, uint8 ib, uint8 ta, uint8 tb) {
    b2ContactFeature f;
    f.indexA = ia;
    f.indexB = ib;
    f.typeA = ta;
    f.typeB = tb;
    return f;
}

void ExpectFeature(const b2ContactFeature& got, const b2ContactFeature& want) {
    EXPECT_EQ(got.indexA, want.indexA);
    EXPECT_EQ(got.indexB, want.indexB);
    EXPECT_EQ(got.typeA, want.typeA);
    EXPECT_EQ(got.typeB, want.typeB);
}

constexpr uint8 kFace = b2ContactFeature::e_face;
constexpr uint8 kVertex = b2ContactFeature::e_vertex;

// Box A (half-size 1) at the origin; box B (half-size 0.5) above it. Faces of a SetAsBox box:
// 0 bottom, 1 right, 2 top, 3 left; vertices 0 (-,-), 1 (+,-), 2 (+,+), 3 (-,+).
TEST(ManifoldPolygons, RestingBoxTwoPointsOnFaceA) {
    const b2PolygonShape a = Box(1, 1), b = Box(0.5_fx, 0.5_fx);
    b2Manifold m;
    b2CollidePolygons(&m, &a, At(0, 0), &b, At(0.25_fx, 1.5_fx - b2_linearSlop));
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_EQ(m.type, b2Manifold::e_faceA);
    EXPECT_EQ(m.localNormal, b2Vec2(0, 1));
    EXPECT_EQ(m.localPoint, b2Vec2(0, 1));
    // Unclipped incident vertices are B's own vertices, exactly.
    EXPECT_EQ(m.points[0].localPoint, b2Vec2(-0.5_fx, -0.5_fx));
    EXPECT_EQ(m.points[1].localPoint, b2Vec2(0.5_fx, -0.5_fx));
    ExpectFeature(m.points[0].id.cf, Cf(2, 0, kFace, kVertex));
    ExpectFeature(m.points[1].id.cf, Cf(2, 1, kFace, kVertex));

    b2WorldManifold wm;
    wm.Initialize(&m, At(0, 0), a.m_radius, At(0.25_fx, 1.5_fx - b2_linearSlop), b.m_radius);
    EXPECT_EQ(wm.normal, b2Vec2(0, 1));
    for (int i = 0; i < 2; ++i) {
        // Overlap of the skins: linearSlop + 2 * polygonRadius.
        EXPECT_EQ(wm.separations[i], -(b2_linearSlop + b2_polygonRadius + b2_polygonRadius));
    }
}

struct GapCase {
    const char* name;
    Fixed gap;  ///< distance between the solid faces (m)
    int32 count;
};

TEST(ManifoldPolygons, SkinThreshold) {
    const b2PolygonShape a = Box(1, 1), b = Box(0.5_fx, 0.5_fx);
    const Fixed skins = a.m_radius + b.m_radius;
    const GapCase cases[] = {
        {"deep", -0.25_fx, 2},
        {"faces touching", 0, 2},
        {"inside the skins", skins - Fixed::FromRaw(1), 2},
        {"skins exactly touching", skins, 2},
        {"1 raw beyond the skins", skins + Fixed::FromRaw(1), 0},
        {"separated", 0.5_fx, 0},
    };
    for (const GapCase& c : cases) {
        SCOPED_TRACE(c.name);
        b2Manifold m;
        b2CollidePolygons(&m, &a, At(0, 0), &b, At(0, 1.5_fx + c.gap));
        EXPECT_EQ(m.pointCount, c.count);
    }
}

TEST(ManifoldPolygons, OverhangIsClippedAtTheSidePlane) {
    // B spans x in [0.7, 1.7]: its right vertex is clipped at A's side plane x = 1 + skins.
    const b2PolygonShape a = Box(1, 1), b = Box(0.5_fx, 0.5_fx);
    const b2Transform xfB = At(1.2_fx, 1.5_fx);
    b2Manifold m;
    b2CollidePolygons(&m, &a, At(0, 0), &b, xfB);
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_EQ(m.type, b2Manifold::e_faceA);
    EXPECT_EQ(m.points[0].localPoint, b2Vec2(-0.5_fx, -0.5_fx));
    ExpectFeature(m.points[0].id.cf, Cf(2, 0, kFace, kVertex));
    // Clipped point: A's vertex 2 (1, 1), the start of its top face (2 -> 3), against the
    // face of B that starts at B's vertex 0.
    ExpectFeature(m.points[1].id.cf, Cf(2, 0, kVertex, kFace));
    const Fixed clipX = 1 + a.m_radius + b.m_radius - 1.2_fx;  // in B's frame
    EXPECT_NEAR(m.points[1].localPoint.x.ToDouble(), clipX.ToDouble(), 2e-5);
    EXPECT_EQ(m.points[1].localPoint.y, -0.5_fx);
}

TEST(ManifoldPolygons, ReferenceFaceOnBSwapsFeatures) {
    // A small box tilted by 0.1 rad, its lowest corner 5 mm into B's top face: B's face gives
    // the larger separation, so B is the reference (e_faceB) and the ids are swapped.
    const b2PolygonShape a = Box(0.5_fx, 0.5_fx), b = Box(2, 1);
    b2Transform xfA;
    xfA.q.Set(0.1_fx);
    // Lowest corner of A: rotated (-0.5,-0.5) or (0.5,-0.5); place it at y = 1 - 0.005.
    const b2Vec2 c0 = b2Mul(xfA.q, b2Vec2(-0.5_fx, -0.5_fx)), c1 = b2Mul(xfA.q, b2Vec2(0.5_fx, -0.5_fx));
    const Fixed lowest = b2Min(c0.y, c1.y);
    xfA.p = b2Vec2(0.3_fx, 1 - b2_linearSlop - lowest);
    b2Manifold m;
    b2CollidePolygons(&m, &a, xfA, &b, At(0, 0));
    EXPECT_EQ(m.type, b2Manifold::e_faceB);
    EXPECT_EQ(m.localNormal, b2Vec2(0, 1));
    ASSERT_GE(m.pointCount, 1);
    // After a +0.1 rad turn A's lowest corner is its vertex 0 (-0.5, -0.5): the only point,
    // the vertex of A on B's face 2 (2.2.1's swap of face-of-1 / vertex-of-2).
    ASSERT_EQ(m.pointCount, 1);
    ExpectFeature(m.points[0].id.cf, Cf(0, 2, kVertex, kFace));
    EXPECT_EQ(m.points[0].localPoint, b2Vec2(-0.5_fx, -0.5_fx));
    b2WorldManifold wm;
    wm.Initialize(&m, xfA, a.m_radius, At(0, 0), b.m_radius);
    EXPECT_EQ(wm.normal, b2Vec2(0, -1));  // from A to B
    double minSep = 1;
    for (int i = 0; i < m.pointCount; ++i) minSep = std::min(minSep, wm.separations[i].ToDouble());
    EXPECT_NEAR(minSep, -(b2_linearSlop + b2_polygonRadius + b2_polygonRadius).ToDouble(), 3e-5);
}

TEST(ManifoldPolygons, DiamondCornerGivesOnePoint) {
    // B turned by 45 degrees, its lower corner 5 mm into A's top face: the incident edge's
    // other end is far above the skin, so one point survives.
    const b2PolygonShape a = Box(1, 1), b = Box(0.5_fx, 0.5_fx);
    b2Transform xfB;
    xfB.q.Set(0.7853982_fx);
    const double halfDiag = 0.5 * std::sqrt(2.0);
    xfB.p = b2Vec2(0.1_fx, 1 + Fixed::FromDoubleNondeterministic(halfDiag) - b2_linearSlop);
    b2Manifold m;
    b2CollidePolygons(&m, &a, At(0, 0), &b, xfB);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_EQ(m.type, b2Manifold::e_faceA);
    b2WorldManifold wm;
    wm.Initialize(&m, At(0, 0), a.m_radius, xfB, b.m_radius);
    EXPECT_EQ(wm.normal, b2Vec2(0, 1));
    EXPECT_NEAR(wm.separations[0].ToDouble(), -(b2_linearSlop + b2_polygonRadius + b2_polygonRadius).ToDouble(), 5e-5);
    EXPECT_NEAR(wm.points[0].x.ToDouble(), 0.1, 5e-5);
}

TEST(ManifoldPolygons, RotatedPairMatchesUnrotated) {
    // The resting configuration turned as a whole by 0.3 rad about the origin and moved: the
    // manifold's local data is the same (within rounding of the rotated frames), and the world
    // normal is the turned normal.
    const b2PolygonShape a = Box(1, 1), b = Box(0.5_fx, 0.5_fx);
    b2Transform xfA, xfB;
    xfA.Set(b2Vec2(3, -2), 0.3_fx);
    xfB.q = xfA.q;
    xfB.p = b2Mul(xfA, b2Vec2(0.25_fx, 1.5_fx - b2_linearSlop));
    b2Manifold m;
    b2CollidePolygons(&m, &a, xfA, &b, xfB);
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_EQ(m.type, b2Manifold::e_faceA);
    EXPECT_EQ(m.localNormal, b2Vec2(0, 1));
    ExpectFeature(m.points[0].id.cf, Cf(2, 0, kFace, kVertex));
    ExpectFeature(m.points[1].id.cf, Cf(2, 1, kFace, kVertex));
    b2WorldManifold wm;
    wm.Initialize(&m, xfA, a.m_radius, xfB, b.m_radius);
    EXPECT_NEAR(wm.normal.x.ToDouble(), -std::sin(0.3), 3e-5);
    EXPECT_NEAR(wm.normal.y.ToDouble(), std::cos(0.3), 3e-5);
    for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(wm.separations[i].ToDouble(), -(b2_linearSlop + b2_polygonRadius + b2_polygonRadius).ToDouble(),
                    5e-5);
    }
}

TEST(ManifoldPolygons, DeepOverlapPicksTheShallowestAxis) {
    // B sunk 0.4 m into A's top face and 0.1 m past its right side: the right face (0.1 m of
    // overlap... plus B's width) is not shallower, the top face is: normal (0, 1).
    const b2PolygonShape a = Box(1, 1), b = Box(0.5_fx, 0.5_fx);
    b2Manifold m;
    b2CollidePolygons(&m, &a, At(0, 0), &b, At(0.2_fx, 1.1_fx));
    ASSERT_GE(m.pointCount, 1);
    b2WorldManifold wm;
    wm.Initialize(&m, At(0, 0), a.m_radius, At(0.2_fx, 1.1_fx), b.m_radius);
    EXPECT_EQ(wm.normal, b2Vec2(0, 1));
    // And symmetric: B deep into A's right face instead.
    b2CollidePolygons(&m, &a, At(0, 0), &b, At(1.1_fx, 0.2_fx));
    ASSERT_GE(m.pointCount, 1);
    wm.Initialize(&m, At(0, 0), a.m_radius, At(1.1_fx, 0.2_fx), b.m_radius);
    EXPECT_EQ(wm.normal, b2Vec2(1, 0));
}

TEST(ManifoldPolygons, HysteresisKeepsFaceAForNearlyEqualSeparations) {
    // Equal boxes face to face: sepA == sepB, so A stays the reference (B needs to be deeper
    // than 0.98 sepA + 1 mm).
    const b2PolygonShape a = Box(0.5_fx, 0.5_fx), b = Box(0.5_fx, 0.5_fx);
    b2Manifold m;
    b2CollidePolygons(&m, &a, At(0, 0), &b, At(0, 1 - b2_linearSlop));
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_EQ(m.type, b2Manifold::e_faceA);
    ExpectFeature(m.points[0].id.cf, Cf(2, 0, kFace, kVertex));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
