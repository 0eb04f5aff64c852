// World manifolds, point states and segment clipping (Box2D 2.2.1's b2Collision.cpp).
//
// Translation exactness: world points are formed as b2Mul(q, local) + p, so the only rounding
// is in the rotation, which does not depend on the body position; the translation is then an
// exact integer add. (b2Mul(xf, v) rounds the sum rotation + p once, and a rounding tie can
// round differently on either side of the origin.) Every later quantity is built from
// differences of such points, so a configuration moved by whole metres gives the same world
// manifold moved by the same metres, bit for bit.

#include "lockbox/collision/Collision.h"

namespace lockbox {

namespace {

/// World position of a body-frame point: rotation rounded once, translation added exactly.
b2Vec2 ToWorld(const b2Transform& xf, const b2Vec2& local) { return b2Mul(xf.q, local) + xf.p; }

/// round(w / 2) as Q16.16 with one rounding (ties away from zero). |w| stays far below 2^62
/// here: w is a sum of a few dot products of in-world vectors with unit normals.
Fixed HalfToFixed(Wide w) {
    const int64_t raw = detail::ShiftRound(w.Raw(), 17);
    return Fixed::FromRaw(detail::NarrowRaw(raw, "HalfToFixed", w.Raw(), 0));
}

/// a + round((b - a) / 2): the midpoint, rounded on the difference so that it moves exactly
/// with a translation of both points.
b2Vec2 MidpointRoundedOnDifference(const b2Vec2& a, const b2Vec2& b) {
    const int64_t dx = int64_t{b.x.Raw()} - a.x.Raw();
    const int64_t dy = int64_t{b.y.Raw()} - a.y.Raw();
    const Fixed hx = Fixed::FromRaw(detail::NarrowRaw(detail::ShiftRound(dx, 1), "MidpointRoundedOnDifference", dx, 0));
    const Fixed hy = Fixed::FromRaw(detail::NarrowRaw(detail::ShiftRound(dy, 1), "MidpointRoundedOnDifference", dy, 0));
    return {a.x + hx, a.y + hy};
}

}  // namespace

void b2WorldManifold::Initialize(const b2Manifold* manifold, const b2Transform& xfA, Fixed radiusA,
                                 const b2Transform& xfB, Fixed radiusB) {
    if (manifold->pointCount == 0) return;

    switch (manifold->type) {
        case b2Manifold::e_circles: {
            normal.Set(1, 0);
            const b2Vec2 pointA = ToWorld(xfA, manifold->localPoint);
            const b2Vec2 pointB = ToWorld(xfB, manifold->points[0].localPoint);
            const b2Vec2 d = pointB - pointA;
            // Box2D normalises only when distSqr > epsilon^2. The exact integer test is d != 0:
            // Normalize keeps the direction of even a 1-raw vector, so no threshold is needed.
            if (d.LengthSquaredWide() > Wide()) {
                normal = d;
                normal.Normalize();
            }
            const b2Vec2 cA = pointA + radiusA * normal;
            const b2Vec2 cB = pointB - radiusB * normal;
            points[0] = MidpointRoundedOnDifference(cA, cB);
            // Box2D 2.3+: dot(cB - cA, n), which is |d| - rA - rB; the correctly rounded length
            // is the only rounding (a dot with the rounded unit normal would add its 2-ULP
            // length error times |d|).
            separations[0] = d.Length() - radiusA - radiusB;
            break;
        }
        case b2Manifold::e_faceA: {
            normal = b2Mul(xfA.q, manifold->localNormal);
            const b2Vec2 planePoint = ToWorld(xfA, manifold->localPoint);
            for (int32 i = 0; i < manifold->pointCount; ++i) {
                const b2Vec2 clipPoint = ToWorld(xfB, manifold->points[i].localPoint);
                // Distance of the clip point above the reference plane, exact.
                const Wide dist = b2DotWide(clipPoint - planePoint, normal);
                // cA = clip + (rA - dist) n, cB = clip - rB n; their midpoint is
                // clip + (rA - dist - rB)/2 n, formed with a single rounding of the scalar.
                const Fixed half = HalfToFixed(Wide(radiusA) - dist - Wide(radiusB));
                points[i] = clipPoint + half * normal;
                separations[i] = (dist - Wide(radiusA) - Wide(radiusB)).ToFixed();
            }
            break;
        }
        case b2Manifold::e_faceB: {
            normal = b2Mul(xfB.q, manifold->localNormal);
            const b2Vec2 planePoint = ToWorld(xfB, manifold->localPoint);
            for (int32 i = 0; i < manifold->pointCount; ++i) {
                const b2Vec2 clipPoint = ToWorld(xfA, manifold->points[i].localPoint);
                const Wide dist = b2DotWide(clipPoint - planePoint, normal);
                const Fixed half = HalfToFixed(Wide(radiusB) - dist - Wide(radiusA));
                points[i] = clipPoint + half * normal;
                separations[i] = (dist - Wide(radiusA) - Wide(radiusB)).ToFixed();
            }
            // Ensure the normal points from A to B.
            normal = -normal;
            break;
        }
    }
}

void b2GetPointStates(b2PointState state1[b2_maxManifoldPoints], b2PointState state2[b2_maxManifoldPoints],
                      const b2Manifold* manifold1, const b2Manifold* manifold2) {
    for (int32 i = 0; i < b2_maxManifoldPoints; ++i) {
        state1[i] = b2_nullState;
        state2[i] = b2_nullState;
    }

    // Detect persists and removes.
    for (int32 i = 0; i < manifold1->pointCount; ++i) {
        const uint32 key = manifold1->points[i].id.Key();
        state1[i] = b2_removeState;
        for (int32 j = 0; j < manifold2->pointCount; ++j) {
            if (manifold2->points[j].id.Key() == key) {
                state1[i] = b2_persistState;
                break;
            }
        }
    }

    // Detect persists and adds.
    for (int32 i = 0; i < manifold2->pointCount; ++i) {
        const uint32 key = manifold2->points[i].id.Key();
        state2[i] = b2_addState;
        for (int32 j = 0; j < manifold1->pointCount; ++j) {
            if (manifold1->points[j].id.Key() == key) {
                state2[i] = b2_persistState;
                break;
            }
        }
    }
}

int32 b2ClipSegmentToLine(b2ClipVertex vOut[2], const b2ClipVertex vIn[2], const b2Vec2& normal, Fixed offset,
                          int32 vertexIndexA) {
    int32 numOut = 0;

    // Signed distances of the end points to the line, exact (Q32.32).
    const Wide distance0 = b2DotWide(normal, vIn[0].v) - Wide(offset);
    const Wide distance1 = b2DotWide(normal, vIn[1].v) - Wide(offset);

    // If the points are behind the plane
    if (distance0 <= Wide()) vOut[numOut++] = vIn[0];
    if (distance1 <= Wide()) vOut[numOut++] = vIn[1];

    // If the points are on different sides of the plane. Box2D tests d0 * d1 < 0; the sign
    // test is the same without the product (which could overflow), and it guarantees
    // d0 - d1 != 0 for the division below.
    const bool straddles = (distance0 < Wide() && distance1 > Wide()) || (distance0 > Wide() && distance1 < Wide());
    if (straddles) {
        // Intersection point: v0 + d0 / (d0 - d1) * (v1 - v0), each coordinate rounded once
        // from the exact 128-bit product. |d0 / (d0 - d1)| < 1, so the point lies between the
        // end points and cannot leave the Q16.16 range.
        const detail::S128 den = detail::MulS64(distance0.Raw() - distance1.Raw(), 1);
        auto lerp = [&](Fixed a, Fixed b) {
            const int64_t delta = int64_t{b.Raw()} - a.Raw();
            const detail::S128 q = detail::DivRoundS128(detail::MulS64(distance0.Raw(), delta), den);
            const int64_t step = q.negative ? -static_cast<int64_t>(q.mag.lo) : static_cast<int64_t>(q.mag.lo);
            return Fixed::FromRaw(static_cast<int32_t>(int64_t{a.Raw()} + step));
        };
        vOut[numOut].v = b2Vec2(lerp(vIn[0].v.x, vIn[1].v.x), lerp(vIn[0].v.y, vIn[1].v.y));

        // VertexA is hitting edgeB.
        vOut[numOut].id.cf.indexA = static_cast<uint8>(vertexIndexA);
        vOut[numOut].id.cf.indexB = vIn[0].id.cf.indexB;
        vOut[numOut].id.cf.typeA = b2ContactFeature::e_vertex;
        vOut[numOut].id.cf.typeB = b2ContactFeature::e_face;
        ++numOut;
    }

    return numOut;
}

}  // namespace lockbox
