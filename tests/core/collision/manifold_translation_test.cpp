// Translation exactness: every pair function gives bit-identical manifolds when the whole
// configuration moves by whole metres (up to +-15,000 m), and the world manifold moves by
// exactly the same metres. This holds without a bound: the collide functions work in the frame
// of shape A through b2MulT(xfA, xfB), which only sees the exact difference of the positions,
// and b2WorldManifold rounds only rotations (never a sum with the position).

#include <vector>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "manifold_diff_common.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using manifold_diff::Rng;

enum class Kind { circles, polygonCircle, polygons, edgeCircle, edgePolygon, ghostEdgeCircle, ghostEdgePolygon };

struct Config {
    b2CircleShape circleA, circleB;
    b2PolygonShape polyA, polyB;
    b2EdgeShape edgeA;
    b2Transform xfA, xfB;
    Fixed rA, rB;
};

Config MakeConfig(Kind kind, Rng& rng) {
    Config c;
    c.xfA = manifold_diff::RandomTransform(rng, 20);
    double reachA = 0, reachB = 0;
    const bool edge = kind == Kind::edgeCircle || kind == Kind::edgePolygon || kind == Kind::ghostEdgeCircle ||
                      kind == Kind::ghostEdgePolygon;
    if (kind == Kind::circles) {
        c.circleA.m_radius = rng.Fx(0.05, 2);
        c.circleA.m_p = b2Vec2(rng.Fx(-0.5, 0.5), rng.Fx(-0.5, 0.5));
        c.rA = c.circleA.m_radius;
        reachA = c.rA.ToDouble() + 0.7;
    } else if (edge) {
        manifold_diff::RandomEdge(rng, &c.edgeA, kind == Kind::ghostEdgeCircle || kind == Kind::ghostEdgePolygon);
        c.rA = c.edgeA.m_radius;
        reachA = 4;
    } else {
        manifold_diff::RandomPolygon(rng, &c.polyA);
        c.rA = c.polyA.m_radius;
        reachA = manifold_diff::Extent(c.polyA) + 0.5;
    }
    if (kind == Kind::polygons || kind == Kind::edgePolygon || kind == Kind::ghostEdgePolygon) {
        manifold_diff::RandomPolygon(rng, &c.polyB);
        c.rB = c.polyB.m_radius;
        reachB = manifold_diff::Extent(c.polyB) + 0.5;
    } else {
        c.circleB.m_radius = rng.Fx(0.05, 2);
        c.circleB.m_p = b2Vec2(rng.Fx(-0.5, 0.5), rng.Fx(-0.5, 0.5));
        c.rB = c.circleB.m_radius;
        reachB = c.rB.ToDouble() + 0.7;
    }
    if (edge) {
        // Near a random point of the edge (in A's frame), within B's reach.
        const b2Vec2 e = c.edgeA.m_vertex2 - c.edgeA.m_vertex1;
        const Fixed t = rng.Fx(0, 1);
        const b2Vec2 onEdge = c.edgeA.m_vertex1 + b2Vec2(t * e.x, t * e.y);
        const double r = reachB * 0.8;
        c.xfB.q.Set(rng.Fx(-3.14159, 3.14159));
        c.xfB.p = b2Mul(c.xfA, onEdge + b2Vec2(rng.Fx(-r, r), rng.Fx(-r, r)));
    } else {
        c.xfB = manifold_diff::PlaceNear(rng, c.xfA, (reachA + reachB) * 0.7);
    }
    return c;
}

b2Manifold Collide(Kind kind, const Config& c, const b2Transform& xfA, const b2Transform& xfB) {
    b2Manifold m;
    switch (kind) {
        case Kind::circles: b2CollideCircles(&m, &c.circleA, xfA, &c.circleB, xfB); break;
        case Kind::polygonCircle: b2CollidePolygonAndCircle(&m, &c.polyA, xfA, &c.circleB, xfB); break;
        case Kind::polygons: b2CollidePolygons(&m, &c.polyA, xfA, &c.polyB, xfB); break;
        case Kind::edgeCircle:
        case Kind::ghostEdgeCircle: b2CollideEdgeAndCircle(&m, &c.edgeA, xfA, &c.circleB, xfB); break;
        case Kind::edgePolygon:
        case Kind::ghostEdgePolygon: b2CollideEdgeAndPolygon(&m, &c.edgeA, xfA, &c.polyB, xfB); break;
    }
    return m;
}

void ExpectSameManifold(const b2Manifold& a, const b2Manifold& b) {
    ASSERT_EQ(a.pointCount, b.pointCount);
    if (a.pointCount == 0) return;
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.localNormal, b.localNormal);
    EXPECT_EQ(a.localPoint, b.localPoint);
    for (int32 i = 0; i < a.pointCount; ++i) {
        EXPECT_EQ(a.points[i].localPoint, b.points[i].localPoint);
        EXPECT_EQ(a.points[i].id.Key(), b.points[i].id.Key());
    }
}

class ManifoldTranslation : public ::testing::TestWithParam<Kind> {};

TEST_P(ManifoldTranslation, WholeMetreShiftsAreExact) {
    const Kind kind = GetParam();
    Rng rng{0x7A45u + static_cast<unsigned>(kind)};
    const std::vector<b2Vec2> fixedOffsets = {{15000, 15000}, {-15000, -15000}, {15000, -14999}, {-7, 3},
                                              {12345, -6789}, {1, 0},           {0, -1}};
    int touching = 0;
    constexpr int kConfigs = 300;
    for (int k = 0; k < kConfigs; ++k) {
        const Config c = MakeConfig(kind, rng);
        const b2Manifold base = Collide(kind, c, c.xfA, c.xfB);
        b2WorldManifold baseWorld;
        baseWorld.Initialize(&base, c.xfA, c.rA, c.xfB, c.rB);
        if (base.pointCount > 0) ++touching;
        std::vector<b2Vec2> offsets = fixedOffsets;
        offsets.emplace_back(static_cast<int32>(rng.Int(-15000, 15000)), static_cast<int32>(rng.Int(-15000, 15000)));
        for (const b2Vec2& off : offsets) {
            SCOPED_TRACE(k);
            SCOPED_TRACE(off.x.ToDouble());
            SCOPED_TRACE(off.y.ToDouble());
            const b2Transform xfA(c.xfA.p + off, c.xfA.q), xfB(c.xfB.p + off, c.xfB.q);
            const b2Manifold moved = Collide(kind, c, xfA, xfB);
            ExpectSameManifold(base, moved);
            if (base.pointCount == 0 || moved.pointCount != base.pointCount) continue;
            b2WorldManifold world;
            world.Initialize(&moved, xfA, c.rA, xfB, c.rB);
            EXPECT_EQ(world.normal, baseWorld.normal);
            for (int32 i = 0; i < moved.pointCount; ++i) {
                EXPECT_EQ(world.points[i], baseWorld.points[i] + off);
                EXPECT_EQ(world.separations[i], baseWorld.separations[i]);
            }
        }
        if (HasFailure()) break;
    }
    // The sample must contain contacts, not only misses.
    EXPECT_GT(touching, kConfigs / 5);
}

std::string KindName(const ::testing::TestParamInfo<Kind>& info) {
    static const char* const kNames[] = {"Circles",     "PolygonCircle",   "Polygons",        "EdgeCircle",
                                         "EdgePolygon", "GhostEdgeCircle", "GhostEdgePolygon"};
    return kNames[static_cast<int>(info.param)];
}

INSTANTIATE_TEST_SUITE_P(AllPairs, ManifoldTranslation,
                         ::testing::Values(Kind::circles, Kind::polygonCircle, Kind::polygons, Kind::edgeCircle,
                                           Kind::edgePolygon, Kind::ghostEdgeCircle, Kind::ghostEdgePolygon),
                         KindName);

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
