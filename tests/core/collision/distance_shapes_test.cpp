// b2DistanceProxy::Set on every shape type and b2TestOverlap (GJK with radii).

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/Distance.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

b2Transform Place(Fixed x, Fixed y, Fixed angle = Fixed()) {
    b2Transform xf;
    xf.Set(b2Vec2(x, y), angle);
    return xf;
}

TEST(DistanceShapes, ProxyFromEachShapeType) {
    b2CircleShape circle;
    ASSERT_EQ(circle.Set(b2Vec2(1, 2), 0.5_fx), b2ShapeError::ok);
    b2DistanceProxy p;
    p.Set(&circle, 0);
    EXPECT_EQ(p.GetVertexCount(), 1);
    EXPECT_EQ(p.GetVertex(0), b2Vec2(1, 2));
    EXPECT_EQ(p.m_radius, 0.5_fx);

    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(1, 0.5_fx), b2ShapeError::ok);
    p.Set(&box, 0);
    EXPECT_EQ(p.GetVertexCount(), 4);
    EXPECT_EQ(p.m_radius, b2_polygonRadius);
    EXPECT_EQ(p.GetSupportVertex(b2Vec2(1, 1)), b2Vec2(1, 0.5_fx));

    b2EdgeShape edge;
    ASSERT_EQ(edge.Set(b2Vec2(-1, 0), b2Vec2(2, 1)), b2ShapeError::ok);
    p.Set(&edge, 0);
    EXPECT_EQ(p.GetVertexCount(), 2);
    EXPECT_EQ(p.GetVertex(0), b2Vec2(-1, 0));
    EXPECT_EQ(p.GetVertex(1), b2Vec2(2, 1));

    const b2Vec2 square[4] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    b2ChainShape loop;
    ASSERT_EQ(loop.CreateLoop(square, 4), b2ShapeError::ok);
    for (int32 i = 0; i < loop.GetChildCount(); ++i) {
        p.Set(&loop, i);
        EXPECT_EQ(p.GetVertexCount(), 2);
        EXPECT_EQ(p.m_vertices, p.m_buffer);
        EXPECT_EQ(p.GetVertex(0), square[i]);
        EXPECT_EQ(p.GetVertex(1), square[(i + 1) % 4]);
    }
}

TEST(DistanceShapes, ChainChildAgainstCircle) {
    const b2Vec2 ground[3] = {{-5, 0}, {0, 0}, {5, 1}};
    b2ChainShape chain;
    ASSERT_EQ(chain.CreateChain(ground, 3), b2ShapeError::ok);
    b2CircleShape ball;
    ASSERT_EQ(ball.Set(b2Vec2(), 0.5_fx), b2ShapeError::ok);
    b2DistanceInput in;
    in.proxyA.Set(&chain, 0);
    in.proxyB.Set(&ball, 0);
    in.transformA = Place(0, 0);
    in.transformB = Place(-2, 3);
    in.useRadii = true;
    b2SimplexCache cache;
    b2DistanceOutput out;
    b2Distance(&out, &cache, &in);
    EXPECT_EQ(out.distance, Fixed(3) - 0.5_fx - b2_polygonRadius);
    EXPECT_EQ(out.pointA, b2Vec2(-2, b2_polygonRadius));
    EXPECT_EQ(out.pointB, b2Vec2(-2, 2.5_fx));
}

TEST(DistanceShapes, TestOverlapCountsTouchingAsOverlap) {
    b2PolygonShape box;
    ASSERT_EQ(box.SetAsBox(0.5_fx, 0.5_fx), b2ShapeError::ok);
    // Core gap of exactly two skins: the rounded shapes touch.
    const Fixed touching = Fixed(1) + Fixed(2) * b2_polygonRadius;
    EXPECT_TRUE(b2TestOverlap(&box, 0, &box, 0, Place(0, 0), Place(touching, 0)));
    EXPECT_FALSE(b2TestOverlap(&box, 0, &box, 0, Place(0, 0), Place(touching + Fixed::FromRaw(1), 0)));
    EXPECT_TRUE(b2TestOverlap(&box, 0, &box, 0, Place(0, 0), Place(0.3_fx, 0.2_fx, 0.7_fx)));
    EXPECT_FALSE(b2TestOverlap(&box, 0, &box, 0, Place(0, 0), Place(3, 3, 0.7_fx)));

    b2CircleShape circle;
    ASSERT_EQ(circle.Set(b2Vec2(), 1), b2ShapeError::ok);
    EXPECT_TRUE(b2TestOverlap(&circle, 0, &box, 0, Place(0, 0), Place(1.5_fx, 0)));
    EXPECT_FALSE(b2TestOverlap(&circle, 0, &box, 0, Place(0, 0), Place(1.6_fx, 0)));

    b2EdgeShape edge;
    ASSERT_EQ(edge.Set(b2Vec2(-3, 0), b2Vec2(3, 0)), b2ShapeError::ok);
    EXPECT_TRUE(b2TestOverlap(&edge, 0, &circle, 0, Place(0, 0), Place(1, 1)));
    EXPECT_FALSE(b2TestOverlap(&edge, 0, &circle, 0, Place(0, 0), Place(1, 1.02_fx)));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
