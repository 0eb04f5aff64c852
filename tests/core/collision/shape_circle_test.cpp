// b2CircleShape: validation (shape unchanged on error), TestPoint, the exact ray cast against a
// long double reference and float Box2D 2.4.1, ComputeAABB with rotated transforms.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/CircleShape.h"

// After lockbox's headers: Box2D 2.4.1 #defines b2_linearSlop and friends. The tests live in
// namespace lockbox so that unqualified b2 names mean lockbox's; float Box2D is spelled ::b2.
#include "Box2DFloat.h"  // float Box2D without its constant macros

namespace lockbox {

using namespace lockbox::literals;

namespace LOCKBOX_TEST_FILE {
Fixed F(double v) { return Fixed::FromDoubleNondeterministic(v); }
b2Vec2 V(double x, double y) { return {F(x), F(y)}; }
double UnitError(const b2Vec2& n) { return std::fabs(std::hypot(n.x.ToDouble(), n.y.ToDouble()) - 1.0); }

TEST(ShapeCircle, ConstructionAndSetRejectInvalidRadius) {
    b2ShapeError error = b2ShapeError::ok;
    b2CircleShape bad(Fixed(0), V(1, 1), &error);
    EXPECT_EQ(error, b2ShapeError::nonPositiveRadius);
    EXPECT_EQ(bad.m_radius, Fixed());
    EXPECT_EQ(bad.m_p, b2Vec2());

    b2CircleShape good(0.5_fx, V(1, 2), &error);
    EXPECT_EQ(error, b2ShapeError::ok);
    EXPECT_EQ(good.m_radius, 0.5_fx);
    EXPECT_EQ(good.m_p, V(1, 2));
    EXPECT_EQ(good.GetType(), b2Shape::e_circle);

    EXPECT_EQ(good.SetRadius(-1), b2ShapeError::nonPositiveRadius);
    EXPECT_EQ(good.SetRadius(0), b2ShapeError::nonPositiveRadius);
    EXPECT_EQ(good.Set(V(4095.5, 0), 1), b2ShapeError::outOfRange);
    EXPECT_EQ(good.Set(V(0, -4000), 97), b2ShapeError::outOfRange);
    EXPECT_EQ(good.SetRadius(4096), b2ShapeError::outOfRange);
    EXPECT_EQ(good.m_radius, 0.5_fx);
    EXPECT_EQ(good.m_p, V(1, 2));
    EXPECT_EQ(good.Set(V(0, -4000), 96), b2ShapeError::ok);
    EXPECT_EQ(good.SetRadius(Fixed::FromRaw(1)), b2ShapeError::ok);

    b2CircleShape far(1, V(5000, 0), &error);
    EXPECT_EQ(error, b2ShapeError::outOfRange);
    b2CircleShape noReport(-1_fx);  // the error pointer is optional
    EXPECT_EQ(noReport.m_radius, Fixed());
}

TEST(ShapeCircle, SupportHelpersAndClone) {
    b2CircleShape c(1, V(2, 3));
    EXPECT_EQ(c.GetSupport(V(1, 0)), 0);
    EXPECT_EQ(c.GetSupportVertex(V(0, 1)), V(2, 3));
    EXPECT_EQ(c.GetVertexCount(), 1);
    EXPECT_EQ(c.GetVertex(0), V(2, 3));
    EXPECT_EQ(c.GetChildCount(), 1);
    const std::unique_ptr<b2Shape> clone = c.Clone();
    ASSERT_EQ(clone->GetType(), b2Shape::e_circle);
    EXPECT_EQ(static_cast<const b2CircleShape*>(clone.get())->m_p, V(2, 3));
    EXPECT_EQ(clone->m_radius, Fixed(1));
}

TEST(ShapeCircle, TestPointRotatedAndBoundary) {
    b2CircleShape c(1, V(2, 0));
    const b2Transform xf(V(-1, 1), b2Rot(F(1.5707963267948966)));  // centre lands at (-1, 3)
    EXPECT_TRUE(c.TestPoint(xf, V(-1, 3)));
    EXPECT_TRUE(c.TestPoint(xf, V(-1, 3.99)));
    EXPECT_FALSE(c.TestPoint(xf, V(-1, 4.01)));
    EXPECT_FALSE(c.TestPoint(xf, V(2, 0)));  // the body-frame centre is not inside in the world
    // The boundary is inside, exactly: identity transform.
    EXPECT_TRUE(c.TestPoint(b2Transform(), V(3, 0)));
    EXPECT_FALSE(c.TestPoint(b2Transform(), b2Vec2(Fixed(3) + Fixed::FromRaw(1), Fixed(0))));
    // Far points (differences near 2^32 raw) do not overflow.
    EXPECT_FALSE(c.TestPoint(b2Transform(), V(-32000, -32000)));
}

TEST(ShapeCircle, RayCastHitMissClipAndInside) {
    b2CircleShape c(1, V(0, 0));
    const b2Transform id;
    b2RayCastOutput out;
    b2RayCastInput in{V(-3, 0), V(3, 0), 1};
    ASSERT_TRUE(c.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, Fixed::FromRatio(1, 3));
    EXPECT_EQ(out.normal, V(-1, 0));
    in.maxFraction = F(0.33);
    EXPECT_FALSE(c.RayCast(&out, in, id, 0));
    in.maxFraction = F(0.34);
    EXPECT_TRUE(c.RayCast(&out, in, id, 0));
    // Tangent ray touches: discriminant 0.
    in = {V(-3, 1), V(3, 1), 1};
    ASSERT_TRUE(c.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, 0.5_fx);
    EXPECT_EQ(out.normal, V(0, 1));
    // Misses.
    in = {V(-3, 1.01), V(3, 1.01), 1};
    EXPECT_FALSE(c.RayCast(&out, in, id, 0));
    in = {V(-3, 0), V(-5, 0), 1};
    EXPECT_FALSE(c.RayCast(&out, in, id, 0));
    in = {V(-3, 0), V(-3, 0), 1};
    EXPECT_FALSE(c.RayCast(&out, in, id, 0));
    // Starting inside: no hit.
    in = {V(0.5, 0), V(5, 0), 1};
    EXPECT_FALSE(c.RayCast(&out, in, id, 0));
    // Starting on the boundary heading in: hit at 0 (as 2.2.1).
    in = {V(-1, 0), V(1, 0), 1};
    ASSERT_TRUE(c.RayCast(&out, in, id, 0));
    EXPECT_EQ(out.fraction, Fixed());
}

TEST(ShapeCircle, RayCastMatchesReferenceAcrossScales) {
    // Radii 0.05 - 100 m, rays up to ~400 m long, rotated transforms; reference in long double
    // on the same Q16.16 inputs, plus float Box2D 2.4.1 as a sanity check.
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(-1, 1);
    int hits = 0, box2dAgree = 0, box2dCompared = 0;
    long double maxFracErr = 0, maxNormalErr = 0;
    for (int t = 0; t < 20000; ++t) {
        const double r = 0.05 * std::pow(2000.0, (u(rng) + 1) / 2);
        b2CircleShape c(F(r), V(r * u(rng), r * u(rng)));
        const b2Transform xf(V(50 * u(rng), 50 * u(rng)), b2Rot(F(3 * u(rng))));
        const double reach = 4 * r;
        const b2Vec2 centre = xf.p + b2Mul(xf.q, c.m_p);
        const b2RayCastInput in{b2Vec2(centre.x + F(reach * u(rng)), centre.y + F(reach * u(rng))),
                                b2Vec2(centre.x + F(reach * u(rng)), centre.y + F(reach * u(rng))),
                                F(0.5 + u(rng) / 2)};
        b2RayCastOutput out;
        const bool hit = c.RayCast(&out, in, xf, 0);
        // long double reference with the same centre and radius.
        const long double sx = (in.p1.x - centre.x).ToDouble(), sy = (in.p1.y - centre.y).ToDouble();
        const long double rx = (in.p2.x - in.p1.x).ToDouble(), ry = (in.p2.y - in.p1.y).ToDouble();
        const long double R = c.m_radius.ToDouble();
        const long double b = sx * sx + sy * sy - R * R, cc = sx * rx + sy * ry, rr = rx * rx + ry * ry;
        const long double sigma = cc * cc - rr * b;
        bool refHit = false;
        long double frac = 0;
        if (sigma >= 0 && rr > 0 && b >= 0) {
            const long double a = -(cc + std::sqrt(sigma));
            frac = a / rr;
            refHit = a >= 0 && frac <= in.maxFraction.ToDouble();
        }
        const long double margin =
            std::min(std::fabs(frac - in.maxFraction.ToDouble()), std::fabs(sigma) / (rr * R * R));
        if (hit != refHit && (margin < 1e-6 || std::fabs(b) / (R * R) < 1e-6)) continue;
        ASSERT_EQ(hit, refHit) << t;
        if (!hit) continue;
        ++hits;
        maxFracErr = std::max(maxFracErr, std::fabs(out.fraction.ToDouble() - frac));
        const long double nx = sx + frac * rx, ny = sy + frac * ry, nl = std::hypot(nx, ny);
        maxNormalErr =
            std::max(maxNormalErr, std::hypot(out.normal.x.ToDouble() - nx / nl, out.normal.y.ToDouble() - ny / nl));
        EXPECT_LE(UnitError(out.normal), 2.0 / 65536);

        // Float Box2D on the same world data.
        ::b2CircleShape fc;
        fc.m_radius = static_cast<float>(c.m_radius.ToDouble());
        fc.m_p.Set(static_cast<float>(c.m_p.x.ToDouble()), static_cast<float>(c.m_p.y.ToDouble()));
        ::b2Transform fxf(::b2Vec2(static_cast<float>(xf.p.x.ToDouble()), static_cast<float>(xf.p.y.ToDouble())),
                          ::b2Rot(0));
        fxf.q.s = static_cast<float>(xf.q.s.ToDouble());
        fxf.q.c = static_cast<float>(xf.q.c.ToDouble());
        ::b2RayCastInput fin;
        fin.p1.Set(static_cast<float>(in.p1.x.ToDouble()), static_cast<float>(in.p1.y.ToDouble()));
        fin.p2.Set(static_cast<float>(in.p2.x.ToDouble()), static_cast<float>(in.p2.y.ToDouble()));
        fin.maxFraction = static_cast<float>(in.maxFraction.ToDouble());
        ::b2RayCastOutput fout;
        if (fc.RayCast(&fout, fin, fxf, 0)) {
            ++box2dCompared;
            box2dAgree += std::fabs(fout.fraction - out.fraction.ToDouble()) < 1e-3;
        }
    }
    std::printf(
        "[circle ray] 20000 rays, %d hits, max |fraction err| %.3Le, max normal err %.3Le; "
        "float Box2D agrees (1e-3) on %d of %d\n",
        hits, maxFracErr, maxNormalErr, box2dAgree, box2dCompared);
    EXPECT_GT(hits, 3000);
    EXPECT_LE(maxFracErr, 1e-4L);
    EXPECT_LE(maxNormalErr, 1e-3L);
    EXPECT_GE(box2dAgree, box2dCompared * 99 / 100);
}

TEST(ShapeCircle, RayCastFarFromOriginDoesNotOverflow) {
    b2CircleShape c(Fixed(2), V(0, 0));
    const b2Transform xf(V(-30000, 30000), b2Rot());
    b2RayCastInput in{V(30000, -30000), V(-30000, 30000), 1};
    b2RayCastOutput out;
    ASSERT_TRUE(c.RayCast(&out, in, xf, 0));
    const double len = std::hypot(60000.0, 60000.0);
    EXPECT_NEAR(out.fraction.ToDouble(), (len - 2) / len, 2e-5);
    EXPECT_LE(UnitError(out.normal), 2.0 / 65536);
}

TEST(ShapeCircle, ComputeAABBRotatedIncludesRadius) {
    b2CircleShape c(0.5_fx, V(1, 0));
    b2AABB aabb;
    c.ComputeAABB(&aabb, b2Transform(V(2, 2), b2Rot(F(3.14159265358979))), 0);
    EXPECT_NEAR(aabb.lowerBound.x.ToDouble(), 0.5, 3e-5);
    EXPECT_NEAR(aabb.upperBound.x.ToDouble(), 1.5, 3e-5);
    EXPECT_NEAR(aabb.lowerBound.y.ToDouble(), 1.5, 3e-5);
    EXPECT_NEAR(aabb.upperBound.y.ToDouble(), 2.5, 3e-5);
    c.ComputeAABB(&aabb, b2Transform(), 0);
    EXPECT_EQ(aabb.lowerBound, V(0.5, -0.5));
    EXPECT_EQ(aabb.upperBound, V(1.5, 0.5));
}

}  // namespace LOCKBOX_TEST_FILE

}  // namespace lockbox
