// Edge-circle and edge-polygon manifolds (Box2D 2.2.1's b2CollideEdge.cpp), with the ghost
// vertices m_vertex0 / m_vertex3 that let a shape slide across the seams of a chain without
// catching on an internal normal.
//
// Everything runs in the edge's frame (A), reaching shape B through b2MulT(xfA, xfB): the
// manifold depends only on the difference of the body positions, so a configuration moved by
// whole metres gives the identical manifold. Separations, region tests and distance tests are
// exact Q32.32 (or 128-bit) values; nothing is compared after rounding.

#include "ReferenceFace.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {

namespace {

/// |a|^2 as an unsigned 128-bit value, for a signed Q32.32 raw a.
detail::U128 Square(int64_t a) { return detail::MulU64(detail::AbsU64(a), detail::AbsU64(a)); }

/// A single-point edge-circle manifold.
void SetEdgeCirclePoint(b2Manifold* manifold, b2Manifold::Type type, const b2Vec2& localNormal,
                        const b2Vec2& localPoint, const b2ContactFeature& cf, const b2Vec2& circleCenter) {
    manifold->pointCount = 1;
    manifold->type = type;
    manifold->localNormal = localNormal;
    manifold->localPoint = localPoint;
    manifold->points[0].id = b2ContactID{};
    manifold->points[0].id.cf = cf;
    manifold->points[0].localPoint = circleCenter;
}

}  // namespace

// Compute contact points for edge versus circle. This accounts for edge connectivity.
void b2CollideEdgeAndCircle(b2Manifold* manifold, const b2EdgeShape* edgeA, const b2Transform& xfA,
                            const b2CircleShape* circleB, const b2Transform& xfB) {
    manifold->pointCount = 0;

    // Compute circle in frame of edge.
    const b2Vec2 Q = b2Mul(b2MulT(xfA, xfB), circleB->m_p);

    const b2Vec2 A = edgeA->m_vertex1;
    const b2Vec2 B = edgeA->m_vertex2;
    const b2Vec2 e = B - A;

    // Barycentric coordinates (scaled by |e|^2; only their signs are used).
    const Wide u = b2DotWide(e, B - Q);
    const Wide v = b2DotWide(e, Q - A);

    const Fixed radius = edgeA->m_radius + circleB->m_radius;
    const Wide radiusSqr = MulWide(radius, radius);

    b2ContactFeature cf;
    cf.indexB = 0;
    cf.typeB = b2ContactFeature::e_vertex;

    // Region A
    if (v <= Wide()) {
        if (b2DistanceSquaredWide(Q, A) > radiusSqr) return;

        // Is there an edge connected to A?
        if (edgeA->m_hasVertex0) {
            const b2Vec2 e1 = A - edgeA->m_vertex0;
            const Wide u1 = b2DotWide(e1, A - Q);
            // Is the circle in Region AB of the previous edge?
            if (u1 > Wide()) return;
        }

        cf.indexA = 0;
        cf.typeA = b2ContactFeature::e_vertex;
        SetEdgeCirclePoint(manifold, b2Manifold::e_circles, b2Vec2(), A, cf, circleB->m_p);
        return;
    }

    // Region B
    if (u <= Wide()) {
        if (b2DistanceSquaredWide(Q, B) > radiusSqr) return;

        // Is there an edge connected to B?
        if (edgeA->m_hasVertex3) {
            const b2Vec2 e2 = edgeA->m_vertex3 - B;
            const Wide v2 = b2DotWide(e2, Q - B);
            // Is the circle in Region AB of the next edge?
            if (v2 > Wide()) return;
        }

        cf.indexA = 1;
        cf.typeA = b2ContactFeature::e_vertex;
        SetEdgeCirclePoint(manifold, b2Manifold::e_circles, b2Vec2(), B, cf, circleB->m_p);
        return;
    }

    // Region AB. Box2D projects Q onto the edge, P = (u A + v B) / |e|^2, and tests |Q - P|^2.
    // The same squared distance is cross(e, Q - A)^2 / |e|^2, so the test is done without a
    // division as cross^2 > r^2 |e|^2, exactly in 128 bits. |e|^2 > 0 here: u > 0 needs e != 0.
    const Wide cross = b2CrossWide(e, Q - A);
    const Wide den = e.LengthSquaredWide();
    const detail::U128 lhs = Square(cross.Raw());
    const detail::U128 rhs = detail::MulU64(static_cast<uint64_t>(radiusSqr.Raw()), static_cast<uint64_t>(den.Raw()));
    if (detail::LessU128(rhs, lhs)) return;

    b2Vec2 n(-e.y, e.x);
    if (b2DotWide(n, Q - A) < Wide()) n.Set(-n.x, -n.y);
    n.Normalize();

    cf.indexA = 0;
    cf.typeA = b2ContactFeature::e_face;
    SetEdgeCirclePoint(manifold, b2Manifold::e_faceA, n, A, cf, circleB->m_p);
}

namespace {

/// The best separating axis found so far.
struct b2EPAxis {
    enum Type { e_unknown, e_edgeA, e_edgeB };
    Type type = e_unknown;
    int32 index = 0;
    Wide separation;  ///< exact, Q32.32 m
};

/// Polygon B expressed in frame A.
struct b2TempPolygon {
    b2Vec2 vertices[b2_maxPolygonVertices];
    b2Vec2 normals[b2_maxPolygonVertices];
    int32 count = 0;
};

/// Reference face used for clipping.
struct b2ReferenceFace {
    int32 i1 = 0, i2 = 0;
    b2Vec2 v1, v2;
    b2Vec2 normal;
    b2Vec2 sideNormal1;
    Fixed sideOffset1;
    b2Vec2 sideNormal2;
    Fixed sideOffset2;
};

/// Collides an edge and a polygon, taking edge adjacency into account. 2.2.1's algorithm:
/// 1. classify v1 and v2 (convex or concave corner with the neighbouring edges);
/// 2. classify the polygon centroid as in front of or behind the edge;
/// 3. flip the normal if necessary;
/// 4.-5. bound the admissible normals by the adjacent edges' normals;
/// 6. visit each separating axis, accepting only those within the bounds;
/// 7. return if any axis separates;
/// 8. clip.
class b2EPCollider {
public:
    void Collide(b2Manifold* manifold, const b2EdgeShape* edgeA, const b2Transform& xfA, const b2PolygonShape* polygonB,
                 const b2Transform& xfB);

private:
    b2EPAxis ComputeEdgeSeparation() const;
    b2EPAxis ComputePolygonSeparation() const;
    void SetLimits(const b2Vec2& normal, const b2Vec2& lower, const b2Vec2& upper) {
        m_normal = normal;
        m_lowerLimit = lower;
        m_upperLimit = upper;
    }

    b2TempPolygon m_polygonB;
    b2Transform m_xf;
    b2Vec2 m_centroidB;
    b2Vec2 m_v0, m_v1, m_v2, m_v3;
    b2Vec2 m_normal0, m_normal1, m_normal2;
    b2Vec2 m_normal;
    b2Vec2 m_lowerLimit, m_upperLimit;
    Fixed m_radius;
    bool m_front = false;
};

void b2EPCollider::Collide(b2Manifold* manifold, const b2EdgeShape* edgeA, const b2Transform& xfA,
                           const b2PolygonShape* polygonB, const b2Transform& xfB) {
    m_xf = b2MulT(xfA, xfB);
    m_centroidB = b2Mul(m_xf, polygonB->m_centroid);

    m_v0 = edgeA->m_vertex0;
    m_v1 = edgeA->m_vertex1;
    m_v2 = edgeA->m_vertex2;
    m_v3 = edgeA->m_vertex3;

    const bool hasVertex0 = edgeA->m_hasVertex0;
    const bool hasVertex3 = edgeA->m_hasVertex3;

    const b2Vec2 rawEdge1 = m_v2 - m_v1;
    b2Vec2 edge1 = rawEdge1;
    edge1.Normalize();
    m_normal1.Set(edge1.y, -edge1.x);
    // Which side of each edge the centroid is on: exact signs of Q32.32 dot products.
    const bool front1 = b2DotWide(m_normal1, m_centroidB - m_v1) >= Wide();
    bool front0 = false, front2 = false;
    bool convex1 = false, convex2 = false;

    // Is there a preceding edge? Convexity is the sign of the exact cross product of the raw
    // edge vectors: the same sign as 2.2.1's cross of the normalised edges, without the
    // rounding that can flip it for nearly collinear neighbours. 2.2.1 counts a straight
    // corner as convex at v1 (>=) and concave at v2 (>); kept as is.
    if (hasVertex0) {
        const b2Vec2 rawEdge0 = m_v1 - m_v0;
        b2Vec2 edge0 = rawEdge0;
        edge0.Normalize();
        m_normal0.Set(edge0.y, -edge0.x);
        convex1 = b2CrossWide(rawEdge0, rawEdge1) >= Wide();
        front0 = b2DotWide(m_normal0, m_centroidB - m_v0) >= Wide();
    }

    // Is there a following edge?
    if (hasVertex3) {
        const b2Vec2 rawEdge2 = m_v3 - m_v2;
        b2Vec2 edge2 = rawEdge2;
        edge2.Normalize();
        m_normal2.Set(edge2.y, -edge2.x);
        convex2 = b2CrossWide(rawEdge1, rawEdge2) > Wide();
        front2 = b2DotWide(m_normal2, m_centroidB - m_v2) >= Wide();
    }

    // Determine front or back collision. Determine collision normal limits.
    const b2Vec2 n0 = m_normal0, n1 = m_normal1, n2 = m_normal2;
    if (hasVertex0 && hasVertex3) {
        if (convex1 && convex2) {
            m_front = front0 || front1 || front2;
            if (m_front)
                SetLimits(n1, n0, n2);
            else
                SetLimits(-n1, -n1, -n1);
        } else if (convex1) {
            m_front = front0 || (front1 && front2);
            if (m_front)
                SetLimits(n1, n0, n1);
            else
                SetLimits(-n1, -n2, -n1);
        } else if (convex2) {
            m_front = front2 || (front0 && front1);
            if (m_front)
                SetLimits(n1, n1, n2);
            else
                SetLimits(-n1, -n1, -n0);
        } else {
            m_front = front0 && front1 && front2;
            if (m_front)
                SetLimits(n1, n1, n1);
            else
                SetLimits(-n1, -n2, -n0);
        }
    } else if (hasVertex0) {
        if (convex1) {
            m_front = front0 || front1;
            if (m_front)
                SetLimits(n1, n0, -n1);
            else
                SetLimits(-n1, n1, -n1);
        } else {
            m_front = front0 && front1;
            if (m_front)
                SetLimits(n1, n1, -n1);
            else
                SetLimits(-n1, n1, -n0);
        }
    } else if (hasVertex3) {
        if (convex2) {
            m_front = front1 || front2;
            if (m_front)
                SetLimits(n1, -n1, n2);
            else
                SetLimits(-n1, -n1, n1);
        } else {
            m_front = front1 && front2;
            if (m_front)
                SetLimits(n1, -n1, n1);
            else
                SetLimits(-n1, -n2, n1);
        }
    } else {
        m_front = front1;
        if (m_front)
            SetLimits(n1, -n1, -n1);
        else
            SetLimits(-n1, n1, n1);
    }

    // Get polygonB in frameA.
    m_polygonB.count = polygonB->m_vertexCount;
    for (int32 i = 0; i < polygonB->m_vertexCount; ++i) {
        m_polygonB.vertices[i] = b2Mul(m_xf, polygonB->m_vertices[i]);
        m_polygonB.normals[i] = b2Mul(m_xf.q, polygonB->m_normals[i]);
    }

    // 2.2.1 uses twice the polygon skin here, whatever the shapes' radii.
    m_radius = b2_polygonRadius + b2_polygonRadius;
    const Wide radiusWide(m_radius);

    manifold->pointCount = 0;

    const b2EPAxis edgeAxis = ComputeEdgeSeparation();

    // If no valid normal can be found than this edge should not collide.
    if (edgeAxis.type == b2EPAxis::e_unknown) return;
    if (edgeAxis.separation > radiusWide) return;

    const b2EPAxis polygonAxis = ComputePolygonSeparation();
    if (polygonAxis.type != b2EPAxis::e_unknown && polygonAxis.separation > radiusWide) return;

    // Hysteresis for jitter reduction (ReferenceFace.h): the polygon axis only when sepP > 0.98
    // sepE + 0.001, so that nearly equal separations keep the edge face.
    b2EPAxis primaryAxis;
    if (polygonAxis.type == b2EPAxis::e_unknown) {
        primaryAxis = edgeAxis;
    } else if (collision_detail::PreferSecond(edgeAxis.separation, polygonAxis.separation)) {
        primaryAxis = polygonAxis;
    } else {
        primaryAxis = edgeAxis;
    }

    b2ClipVertex ie[2];
    b2ReferenceFace rf;
    if (primaryAxis.type == b2EPAxis::e_edgeA) {
        manifold->type = b2Manifold::e_faceA;

        // Search for the polygon normal that is most anti-parallel to the edge normal.
        int32 bestIndex = 0;
        Wide bestValue = b2DotWide(m_normal, m_polygonB.normals[0]);
        for (int32 i = 1; i < m_polygonB.count; ++i) {
            const Wide value = b2DotWide(m_normal, m_polygonB.normals[i]);
            if (value < bestValue) {
                bestValue = value;
                bestIndex = i;
            }
        }

        const int32 i1 = bestIndex;
        const int32 i2 = i1 + 1 < m_polygonB.count ? i1 + 1 : 0;

        ie[0].v = m_polygonB.vertices[i1];
        ie[0].id.cf.indexA = 0;
        ie[0].id.cf.indexB = static_cast<uint8>(i1);
        ie[0].id.cf.typeA = b2ContactFeature::e_face;
        ie[0].id.cf.typeB = b2ContactFeature::e_vertex;

        ie[1].v = m_polygonB.vertices[i2];
        ie[1].id.cf.indexA = 0;
        ie[1].id.cf.indexB = static_cast<uint8>(i2);
        ie[1].id.cf.typeA = b2ContactFeature::e_face;
        ie[1].id.cf.typeB = b2ContactFeature::e_vertex;

        if (m_front) {
            rf.i1 = 0;
            rf.i2 = 1;
            rf.v1 = m_v1;
            rf.v2 = m_v2;
            rf.normal = m_normal1;
        } else {
            rf.i1 = 1;
            rf.i2 = 0;
            rf.v1 = m_v2;
            rf.v2 = m_v1;
            rf.normal = -m_normal1;
        }
    } else {
        manifold->type = b2Manifold::e_faceB;

        ie[0].v = m_v1;
        ie[0].id.cf.indexA = 0;
        ie[0].id.cf.indexB = static_cast<uint8>(primaryAxis.index);
        ie[0].id.cf.typeA = b2ContactFeature::e_vertex;
        ie[0].id.cf.typeB = b2ContactFeature::e_face;

        ie[1].v = m_v2;
        ie[1].id.cf.indexA = 0;
        ie[1].id.cf.indexB = static_cast<uint8>(primaryAxis.index);
        ie[1].id.cf.typeA = b2ContactFeature::e_vertex;
        ie[1].id.cf.typeB = b2ContactFeature::e_face;

        rf.i1 = primaryAxis.index;
        rf.i2 = rf.i1 + 1 < m_polygonB.count ? rf.i1 + 1 : 0;
        rf.v1 = m_polygonB.vertices[rf.i1];
        rf.v2 = m_polygonB.vertices[rf.i2];
        rf.normal = m_polygonB.normals[rf.i1];
    }

    rf.sideNormal1.Set(rf.normal.y, -rf.normal.x);
    rf.sideNormal2 = -rf.sideNormal1;
    rf.sideOffset1 = b2Dot(rf.sideNormal1, rf.v1);
    rf.sideOffset2 = b2Dot(rf.sideNormal2, rf.v2);

    // Clip incident edge against extruded edge1 side edges.
    b2ClipVertex clipPoints1[2];
    b2ClipVertex clipPoints2[2];

    // Clip to box side 1
    int32 np = b2ClipSegmentToLine(clipPoints1, ie, rf.sideNormal1, rf.sideOffset1, rf.i1);
    if (np < b2_maxManifoldPoints) return;

    // Clip to negative box side 1
    np = b2ClipSegmentToLine(clipPoints2, clipPoints1, rf.sideNormal2, rf.sideOffset2, rf.i2);
    if (np < b2_maxManifoldPoints) return;

    // Now clipPoints2 contains the clipped points.
    if (primaryAxis.type == b2EPAxis::e_edgeA) {
        manifold->localNormal = rf.normal;
        manifold->localPoint = rf.v1;
    } else {
        manifold->localNormal = polygonB->m_normals[rf.i1];
        manifold->localPoint = polygonB->m_vertices[rf.i1];
    }

    int32 pointCount = 0;
    for (int32 i = 0; i < b2_maxManifoldPoints; ++i) {
        const Wide separation = b2DotWide(rf.normal, clipPoints2[i].v - rf.v1);
        if (separation <= radiusWide) {
            b2ManifoldPoint* cp = manifold->points + pointCount;
            const b2ContactFeature cf = clipPoints2[i].id.cf;
            if (primaryAxis.type == b2EPAxis::e_edgeA) {
                // An unclipped point is a vertex of the polygon: store it exactly rather than
                // sending it to frame A and back (2.2.1's b2MulT, two roundings).
                if (cf.typeB == b2ContactFeature::e_vertex) {
                    cp->localPoint = polygonB->m_vertices[cf.indexB];
                } else {
                    cp->localPoint = b2MulT(m_xf, clipPoints2[i].v);
                }
                cp->id.cf = cf;
            } else {
                cp->localPoint = clipPoints2[i].v;
                cp->id.cf.typeA = cf.typeB;
                cp->id.cf.typeB = cf.typeA;
                cp->id.cf.indexA = cf.indexB;
                cp->id.cf.indexB = cf.indexA;
            }
            cp->normalImpulse = Wide();
            cp->tangentImpulse = Wide();
            ++pointCount;
        }
    }

    manifold->pointCount = pointCount;
}

b2EPAxis b2EPCollider::ComputeEdgeSeparation() const {
    b2EPAxis axis;
    axis.type = b2EPAxis::e_edgeA;
    axis.index = m_front ? 0 : 1;
    axis.separation = Wide::FromRaw(Wide::kMaxRaw);

    for (int32 i = 0; i < m_polygonB.count; ++i) {
        const Wide s = b2DotWide(m_normal, m_polygonB.vertices[i] - m_v1);
        if (s < axis.separation) axis.separation = s;
    }
    return axis;
}

b2EPAxis b2EPCollider::ComputePolygonSeparation() const {
    b2EPAxis axis;
    axis.type = b2EPAxis::e_unknown;
    axis.index = -1;
    axis.separation = Wide::FromRaw(-Wide::kMaxRaw);

    const b2Vec2 perp(-m_normal.y, m_normal.x);
    // Box2D's tolerance on the normal limits: b2_angularSlop used as a cosine difference
    // (dimensionless, raw 2288 = 0.0349), so a polygon normal within about 2 degrees beyond a
    // limit is still admitted.
    const Wide limitTol(b2_angularSlop);

    for (int32 i = 0; i < m_polygonB.count; ++i) {
        const b2Vec2 n = -m_polygonB.normals[i];

        const Wide s1 = b2DotWide(n, m_polygonB.vertices[i] - m_v1);
        const Wide s2 = b2DotWide(n, m_polygonB.vertices[i] - m_v2);
        const Wide s = b2Min(s1, s2);

        if (s > Wide(m_radius)) {
            // No collision
            axis.type = b2EPAxis::e_edgeB;
            axis.index = i;
            axis.separation = s;
            return axis;
        }

        // Adjacency
        if (b2DotWide(n, perp) >= Wide()) {
            if (b2DotWide(n - m_upperLimit, m_normal) < -limitTol) continue;
        } else {
            if (b2DotWide(n - m_lowerLimit, m_normal) < -limitTol) continue;
        }

        if (s > axis.separation) {
            axis.type = b2EPAxis::e_edgeB;
            axis.index = i;
            axis.separation = s;
        }
    }

    return axis;
}

}  // namespace

void b2CollideEdgeAndPolygon(b2Manifold* manifold, const b2EdgeShape* edgeA, const b2Transform& xfA,
                             const b2PolygonShape* polygonB, const b2Transform& xfB) {
    b2EPCollider collider;
    collider.Collide(manifold, edgeA, xfA, polygonB, xfB);
}

}  // namespace lockbox
