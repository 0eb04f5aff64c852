// Circle-circle and polygon-circle manifolds (Box2D 2.2.1's b2CollideCircle.cpp).
//
// Both work in the frame of shape A: the circle centre is carried there through the relative
// transform b2MulT(xfA, xfB), which depends only on the difference of the body positions. The
// manifold is therefore identical bit for bit when both bodies move by the same whole metres.
// Every distance test compares exact Q32.32 squares (never a square rounded to Q16.16).

#include "Midpoint.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {

namespace {

/// A single-point manifold carrying the circle centre, with the all-zero contact id.
void SetCirclePoint(b2Manifold* manifold, b2Manifold::Type type, const b2Vec2& localNormal, const b2Vec2& localPoint,
                    const b2Vec2& circleCenter) {
    manifold->pointCount = 1;
    manifold->type = type;
    manifold->localNormal = localNormal;
    manifold->localPoint = localPoint;
    manifold->points[0].localPoint = circleCenter;
    manifold->points[0].id = b2ContactID{};
}

}  // namespace

void b2CollideCircles(b2Manifold* manifold, const b2CircleShape* circleA, const b2Transform& xfA,
                      const b2CircleShape* circleB, const b2Transform& xfB) {
    manifold->pointCount = 0;

    // Centre of B in the frame of A.
    const b2Vec2 pB = b2Mul(b2MulT(xfA, xfB), circleB->m_p);
    const b2Vec2 d = pB - circleA->m_p;
    const Wide distSqr = d.LengthSquaredWide();
    const Fixed radius = circleA->m_radius + circleB->m_radius;
    if (distSqr > MulWide(radius, radius)) return;

    SetCirclePoint(manifold, b2Manifold::e_circles, b2Vec2(), circleA->m_p, circleB->m_p);
}

void b2CollidePolygonAndCircle(b2Manifold* manifold, const b2PolygonShape* polygonA, const b2Transform& xfA,
                               const b2CircleShape* circleB, const b2Transform& xfB) {
    manifold->pointCount = 0;

    // Compute circle position in the frame of the polygon.
    const b2Vec2 cLocal = b2Mul(b2MulT(xfA, xfB), circleB->m_p);

    // Find the min separating edge. Separations are exact Q32.32 dot products.
    int32 normalIndex = 0;
    Wide separation = Wide::FromRaw(-Wide::kMaxRaw);
    const Fixed radius = polygonA->m_radius + circleB->m_radius;
    const Wide radiusWide(radius);
    const int32 vertexCount = polygonA->m_vertexCount;
    const b2Vec2* vertices = polygonA->m_vertices;
    const b2Vec2* normals = polygonA->m_normals;

    for (int32 i = 0; i < vertexCount; ++i) {
        const Wide s = b2DotWide(normals[i], cLocal - vertices[i]);
        if (s > radiusWide) {
            // Early out.
            return;
        }
        if (s > separation) {
            separation = s;
            normalIndex = i;
        }
    }

    // Vertices that subtend the incident face.
    const int32 vertIndex1 = normalIndex;
    const int32 vertIndex2 = vertIndex1 + 1 < vertexCount ? vertIndex1 + 1 : 0;
    const b2Vec2 v1 = vertices[vertIndex1];
    const b2Vec2 v2 = vertices[vertIndex2];

    // If the center is inside the polygon. Box2D tests separation < b2_epsilon; with exact
    // separations the smallest positive value is 1 raw Q32.32, so the test is separation <= 0.
    if (separation <= Wide()) {
        SetCirclePoint(manifold, b2Manifold::e_faceA, normals[normalIndex],
                       collision_detail::MidpointRoundedOnSum(v1, v2), circleB->m_p);
        return;
    }

    // Compute barycentric coordinates (only their signs matter, so they stay exact).
    const Wide u1 = b2DotWide(cLocal - v1, v2 - v1);
    const Wide u2 = b2DotWide(cLocal - v2, v1 - v2);
    const Wide radiusSqr = MulWide(radius, radius);

    if (u1 <= Wide() || u2 <= Wide()) {
        // Vertex region of v1 (u1 <= 0) or v2.
        const b2Vec2 v = u1 <= Wide() ? v1 : v2;
        if (b2DistanceSquaredWide(cLocal, v) > radiusSqr) return;
        b2Vec2 normal = cLocal - v;
        // The centre can coincide with v2 while separation > 0 (the rounded face normal puts
        // v2 a few raw in front of its own face). Normalising the zero vector would give no
        // direction, so the face normal is used: the contact is then at the vertex, pushed
        // out along the face it belongs to.
        if (normal.LengthSquaredWide() == Wide()) {
            normal = normals[vertIndex1];
        } else {
            normal.Normalize();
        }
        SetCirclePoint(manifold, b2Manifold::e_faceA, normal, v, circleB->m_p);
        return;
    }

    // Face region. separation = dot(c - (v1 + v2) / 2, n); twice it is exact in int64 (the
    // components of 2c - v1 - v2 stay below 2^33 raw, the products below 2^51).
    const b2Vec2& n = normals[vertIndex1];
    const int64_t tx = 2 * int64_t{cLocal.x.Raw()} - v1.x.Raw() - v2.x.Raw();
    const int64_t ty = 2 * int64_t{cLocal.y.Raw()} - v1.y.Raw() - v2.y.Raw();
    const int64_t twiceSeparation = tx * n.x.Raw() + ty * n.y.Raw();
    if (twiceSeparation > 2 * radiusWide.Raw()) return;

    SetCirclePoint(manifold, b2Manifold::e_faceA, n, collision_detail::MidpointRoundedOnSum(v1, v2), circleB->m_p);
}

}  // namespace lockbox
