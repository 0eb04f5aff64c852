// b2EdgeShape and b2ChainShape: validation (unchanged on error), ghost vertices of chain
// children (open chains, loops, SetPrevVertex/SetNextVertex), two-sided ray casts, AABBs with
// the skin radius, no interior and no mass.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/EdgeShape.h"

using namespace lockbox;
using namespace lockbox::literals;

namespace LOCKBOX_TEST_FILE {
Fixed F(double v) { return Fixed::FromDoubleNondeterministic(v); }
b2Vec2 V(double x, double y) { return {F(x), F(y)}; }

void ExpectSameChain(const b2ChainShape& a, const b2ChainShape& b) {
    EXPECT_EQ(a.m_vertices, b.m_vertices);
    EXPECT_EQ(a.m_count, b.m_count);
    EXPECT_EQ(a.m_prevVertex, b.m_prevVertex);
    EXPECT_EQ(a.m_nextVertex, b.m_nextVertex);
    EXPECT_EQ(a.m_hasPrevVertex, b.m_hasPrevVertex);
    EXPECT_EQ(a.m_hasNextVertex, b.m_hasNextVertex);
}

TEST(ShapeEdge, SetValidatesAndClearsGhosts) {
    b2EdgeShape e;
    EXPECT_EQ(e.GetType(), b2Shape::e_edge);
    EXPECT_EQ(e.m_radius, b2_polygonRadius);
    ASSERT_EQ(e.Set(V(-1, 0), V(1, 0)), b2ShapeError::ok);
    e.m_hasVertex0 = true;
    e.m_vertex0 = V(-2, 0);
    const b2EdgeShape copy = e;
    EXPECT_EQ(e.Set(V(0, 0), b2Vec2(Fixed::FromRaw(327), Fixed())), b2ShapeError::duplicateVertices);
    EXPECT_EQ(e.Set(V(0, 0), V(0, 0)), b2ShapeError::duplicateVertices);
    EXPECT_EQ(e.Set(V(0, 0), V(0, 4097)), b2ShapeError::outOfRange);
    EXPECT_EQ(e.m_vertex1, copy.m_vertex1);
    EXPECT_EQ(e.m_vertex2, copy.m_vertex2);
    EXPECT_TRUE(e.m_hasVertex0);
    ASSERT_EQ(e.Set(V(0, 0), b2Vec2(Fixed::FromRaw(328), Fixed())), b2ShapeError::ok);
    EXPECT_FALSE(e.m_hasVertex0);
    EXPECT_FALSE(e.m_hasVertex3);
}

TEST(ShapeEdge, NoInteriorNoMassAABBWithRadius) {
    b2EdgeShape e;
    ASSERT_EQ(e.Set(V(-1, 0), V(3, 2)), b2ShapeError::ok);
    EXPECT_FALSE(e.TestPoint(b2Transform(), V(1, 1)));
    EXPECT_FALSE(e.TestPoint(b2Transform(), V(-1, 0)));
    b2MassData md;
    e.ComputeMass(&md, 5);
    EXPECT_EQ(md.mass, Wide());
    EXPECT_EQ(md.I, Wide());
    EXPECT_EQ(md.center, V(1, 1));
    b2AABB aabb;
    e.ComputeAABB(&aabb, b2Transform(V(1, 1), b2Rot()), 0);
    EXPECT_EQ(aabb.lowerBound, b2Vec2(Fixed(0) - b2_polygonRadius, Fixed(1) - b2_polygonRadius));
    EXPECT_EQ(aabb.upperBound, b2Vec2(Fixed(4) + b2_polygonRadius, Fixed(3) + b2_polygonRadius));
    // Rotated by 90 degrees: (x, y) -> (-y, x).
    e.ComputeAABB(&aabb, b2Transform(V(0, 0), b2Rot(F(1.5707963267948966))), 0);
    EXPECT_NEAR(aabb.lowerBound.x.ToDouble(), -2.01, 3e-5);
    EXPECT_NEAR(aabb.upperBound.x.ToDouble(), 0.01, 3e-5);
    EXPECT_NEAR(aabb.lowerBound.y.ToDouble(), -1.01, 3e-5);
    EXPECT_NEAR(aabb.upperBound.y.ToDouble(), 3.01, 3e-5);
    const std::unique_ptr<b2Shape> clone = e.Clone();
    ASSERT_EQ(clone->GetType(), b2Shape::e_edge);
    EXPECT_EQ(static_cast<const b2EdgeShape*>(clone.get())->m_vertex2, V(3, 2));
}

TEST(ShapeEdge, RayCastIsTwoSided) {
    b2EdgeShape e;
    ASSERT_EQ(e.Set(V(-1, 0), V(1, 0)), b2ShapeError::ok);
    const b2Transform id;
    b2RayCastOutput out;
    b2RayCastInput in{V(0, 2), V(0, -2), 1};
    ASSERT_TRUE(e.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, 0.5_fx);
    EXPECT_EQ(out.normal, V(0, 1));  // faces the ray origin
    in = {V(0.5, -2), V(0.5, 2), 1};
    ASSERT_TRUE(e.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, 0.5_fx);
    EXPECT_EQ(out.normal, V(0, -1));
    // maxFraction clipping, beyond the ends, parallel, pointing away.
    in = {V(0, 2), V(0, -2), F(0.49)};
    EXPECT_FALSE(e.RayCast(&out, in, id, 0));
    in = {V(1.01, 2), V(1.01, -2), 1};
    EXPECT_FALSE(e.RayCast(&out, in, id, 0));
    in = {V(-1, 2), V(-1, -2), 1};  // exactly through the end point: on the segment
    EXPECT_TRUE(e.RayCast(&out, in, id, 0));
    in = {V(-3, 0.5), V(3, 0.5), 1};
    EXPECT_FALSE(e.RayCast(&out, in, id, 0));
    in = {V(0, 2), V(0, 3), 1};
    EXPECT_FALSE(e.RayCast(&out, in, id, 0));
    // Rotated and translated: the edge from (5, 5) along the rotated x axis.
    const b2Transform xf(V(5, 5), b2Rot(F(0.5235987755982988)));  // 30 degrees
    in = {V(5 - 1, 5 + 1.7320508), V(5 + 1, 5 - 1.7320508), 1};   // along the rotated -y axis
    ASSERT_TRUE(e.RayCast(&out, in, xf, 0));
    EXPECT_NEAR(out.fraction.ToDouble(), 0.5, 3e-5);
    EXPECT_NEAR(out.normal.x.ToDouble(), -0.5, 3e-5);  // world normal: rotated (0, 1)
    EXPECT_NEAR(out.normal.y.ToDouble(), 0.8660254, 3e-5);
    // Rays across the whole Q16.16 range (differences beyond 2^31 raw are scaled down) and
    // edges written directly past the setter's range stay exact enough and overflow-free.
    in = {V(-32000, 1), V(32000, -1), 1};
    ASSERT_TRUE(e.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, 0.5_fx);
    EXPECT_EQ(out.normal, V(0, 1));
    b2EdgeShape wide;
    wide.m_vertex1 = V(-32000, 0);
    wide.m_vertex2 = V(32000, 0);
    in = {V(30000, 32000), V(30000, -32000), 1};
    ASSERT_TRUE(wide.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, 0.5_fx);
    // An unset (degenerate) edge never hits.
    EXPECT_FALSE(b2EdgeShape().RayCast(&out, {V(0, 1), V(0, -1), 1}, id, 0));
}

TEST(ShapeChain, CreateRejectsAndLeavesShapeUnchanged) {
    b2ChainShape chain;
    EXPECT_EQ(chain.GetType(), b2Shape::e_chain);
    EXPECT_EQ(chain.GetChildCount(), 0);
    const std::vector<b2Vec2> good = {V(0, 0), V(1, 0), V(2, 1)};
    ASSERT_EQ(chain.CreateChain(good.data(), 3), b2ShapeError::ok);
    chain.SetPrevVertex(V(-1, 0));
    const b2ChainShape copy = chain;
    const std::vector<b2Vec2> one = {V(0, 0)};
    EXPECT_EQ(chain.CreateChain(one.data(), 1), b2ShapeError::tooFewVertices);
    EXPECT_EQ(chain.CreateChain(nullptr, 0), b2ShapeError::tooFewVertices);
    EXPECT_EQ(chain.CreateLoop(good.data(), 2), b2ShapeError::tooFewVertices);
    const std::vector<b2Vec2> dup = {V(0, 0), V(1, 0), V(1.004, 0), V(2, 0)};
    EXPECT_EQ(chain.CreateChain(dup.data(), 4), b2ShapeError::duplicateVertices);
    EXPECT_EQ(chain.CreateLoop(dup.data(), 4), b2ShapeError::duplicateVertices);
    // The closing pair of a loop is checked; an open chain may end where it started.
    const std::vector<b2Vec2> closing = {V(0, 0), V(1, 0), V(1, 1), V(0.002, 0)};
    EXPECT_EQ(chain.CreateLoop(closing.data(), 4), b2ShapeError::duplicateVertices);
    const std::vector<b2Vec2> far = {V(0, 0), V(4096.5, 0)};
    EXPECT_EQ(chain.CreateChain(far.data(), 2), b2ShapeError::outOfRange);
    ExpectSameChain(chain, copy);
    EXPECT_EQ(chain.CreateChain(closing.data(), 4), b2ShapeError::ok);
}

TEST(ShapeChain, OpenChainGhostVertices) {
    const std::vector<b2Vec2> v = {V(0, 0), V(1, 0), V(2, 1), V(3, 1)};
    b2ChainShape chain;
    ASSERT_EQ(chain.CreateChain(v.data(), 4), b2ShapeError::ok);
    EXPECT_EQ(chain.m_count, 4);
    ASSERT_EQ(chain.GetChildCount(), 3);
    b2EdgeShape e;
    chain.GetChildEdge(&e, 0);
    EXPECT_EQ(e.GetType(), b2Shape::e_edge);
    EXPECT_EQ(e.m_radius, chain.m_radius);
    EXPECT_EQ(e.m_vertex1, v[0]);
    EXPECT_EQ(e.m_vertex2, v[1]);
    EXPECT_FALSE(e.m_hasVertex0);
    EXPECT_TRUE(e.m_hasVertex3);
    EXPECT_EQ(e.m_vertex3, v[2]);
    chain.GetChildEdge(&e, 1);
    EXPECT_TRUE(e.m_hasVertex0);
    EXPECT_TRUE(e.m_hasVertex3);
    EXPECT_EQ(e.m_vertex0, v[0]);
    EXPECT_EQ(e.m_vertex3, v[3]);
    chain.GetChildEdge(&e, 2);
    EXPECT_EQ(e.m_vertex0, v[1]);
    EXPECT_EQ(e.m_vertex1, v[2]);
    EXPECT_EQ(e.m_vertex2, v[3]);
    EXPECT_FALSE(e.m_hasVertex3);

    chain.SetPrevVertex(V(-1, -1));
    chain.SetNextVertex(V(4, 0));
    chain.GetChildEdge(&e, 0);
    EXPECT_TRUE(e.m_hasVertex0);
    EXPECT_EQ(e.m_vertex0, V(-1, -1));
    chain.GetChildEdge(&e, 2);
    EXPECT_TRUE(e.m_hasVertex3);
    EXPECT_EQ(e.m_vertex3, V(4, 0));
    // Re-creating resets the ghosts.
    ASSERT_EQ(chain.CreateChain(v.data(), 2), b2ShapeError::ok);
    EXPECT_EQ(chain.GetChildCount(), 1);
    chain.GetChildEdge(&e, 0);
    EXPECT_FALSE(e.m_hasVertex0);
    EXPECT_FALSE(e.m_hasVertex3);
}

TEST(ShapeChain, LoopGhostVerticesWrapAround) {
    const std::vector<b2Vec2> v = {V(0, 0), V(2, 0), V(2, 2), V(0, 2)};
    b2ChainShape loop;
    ASSERT_EQ(loop.CreateLoop(v.data(), 4), b2ShapeError::ok);
    EXPECT_EQ(loop.m_count, 5);
    EXPECT_EQ(loop.m_vertices.back(), v[0]);
    ASSERT_EQ(loop.GetChildCount(), 4);
    for (int i = 0; i < 4; ++i) {
        b2EdgeShape e;
        loop.GetChildEdge(&e, i);
        EXPECT_TRUE(e.m_hasVertex0);
        EXPECT_TRUE(e.m_hasVertex3);
        EXPECT_EQ(e.m_vertex0, v[(i + 3) % 4]) << i;
        EXPECT_EQ(e.m_vertex1, v[i]) << i;
        EXPECT_EQ(e.m_vertex2, v[(i + 1) % 4]) << i;
        EXPECT_EQ(e.m_vertex3, v[(i + 2) % 4]) << i;
    }
    // Copyable value semantics, and Clone.
    b2ChainShape copy = loop;
    copy.m_vertices[0] = V(9, 9);
    EXPECT_EQ(loop.m_vertices[0], v[0]);
    const std::unique_ptr<b2Shape> clone = loop.Clone();
    ASSERT_EQ(clone->GetType(), b2Shape::e_chain);
    EXPECT_EQ(clone->GetChildCount(), 4);
    ExpectSameChain(*static_cast<const b2ChainShape*>(clone.get()), loop);
}

TEST(ShapeChain, ChildRayCastAABBAndNoMass) {
    const std::vector<b2Vec2> v = {V(0, 0), V(2, 0), V(2, 2), V(0, 2)};
    b2ChainShape loop;
    ASSERT_EQ(loop.CreateLoop(v.data(), 4), b2ShapeError::ok);
    const b2Transform xf(V(10, 0), b2Rot());
    b2RayCastOutput out;
    // From inside the loop to the right: hits child 1 (x = 2) from the inside (two-sided).
    const b2RayCastInput in{V(11, 1), V(15, 1), 1};
    EXPECT_FALSE(loop.RayCast(&out, in, xf, 0));
    ASSERT_TRUE(loop.RayCast(&out, in, xf, 1));
    EXPECT_EQ(out.fraction, 0.25_fx);
    EXPECT_EQ(out.normal, V(-1, 0));
    // The closing child 3 runs (0, 2) -> (0, 0).
    const b2RayCastInput left{V(8, 1), V(12, 1), 1};
    ASSERT_TRUE(loop.RayCast(&out, left, xf, 3));
    EXPECT_EQ(out.fraction, 0.5_fx);
    EXPECT_EQ(out.normal, V(-1, 0));
    b2AABB aabb;
    loop.ComputeAABB(&aabb, xf, 3);
    EXPECT_EQ(aabb.lowerBound, b2Vec2(Fixed(10) - b2_polygonRadius, Fixed(0) - b2_polygonRadius));
    EXPECT_EQ(aabb.upperBound, b2Vec2(Fixed(10) + b2_polygonRadius, Fixed(2) + b2_polygonRadius));
    // Rotated by 90 degrees about (10, 0): child 0, (0, 0) -> (2, 0), maps to x = 10, y 0..2.
    loop.ComputeAABB(&aabb, b2Transform(V(10, 0), b2Rot(F(1.5707963267948966))), 0);
    EXPECT_NEAR(aabb.lowerBound.x.ToDouble(), 9.99, 3e-5);
    EXPECT_NEAR(aabb.upperBound.x.ToDouble(), 10.01, 3e-5);
    EXPECT_NEAR(aabb.lowerBound.y.ToDouble(), -0.01, 3e-5);
    EXPECT_NEAR(aabb.upperBound.y.ToDouble(), 2.01, 3e-5);
    // And a ray along -x at y = 1 hits that rotated child from the +x side.
    ASSERT_TRUE(loop.RayCast(&out, {V(14, 1), V(6, 1), 1}, b2Transform(V(10, 0), b2Rot(F(1.5707963267948966))), 0));
    EXPECT_EQ(out.fraction, 0.5_fx);
    EXPECT_NEAR(out.normal.x.ToDouble(), 1, 3e-5);
    EXPECT_FALSE(loop.TestPoint(xf, V(11, 1)));
    b2MassData md;
    loop.ComputeMass(&md, 3);
    EXPECT_EQ(md.mass, Wide());
    EXPECT_EQ(md.I, Wide());
    EXPECT_EQ(md.center, b2Vec2());
}

}  // namespace LOCKBOX_TEST_FILE
