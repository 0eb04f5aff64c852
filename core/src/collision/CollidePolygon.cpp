// Polygon-polygon manifold (Box2D 2.2.1's b2CollidePolygon.cpp): separating-axis search over
// the edge normals of both polygons (full scan, as 2.3+; MaxSeparation.cpp), reference/incident face selection
// with hysteresis, and clipping of the incident edge against the reference face's side planes.
//
// Frames: 2.2.1 clips in world coordinates. lockbox runs the same steps in the frame of the
// reference polygon (poly1), reaching poly2 through the relative transform b2MulT(xf1, xf2).
// The reference vertices and normals are then exact (no rounding through the body
// transform), and the result depends only on the difference of the body positions, so a
// configuration moved by whole metres gives the identical manifold.
//
// Every separation is an exact Q32.32 dot product; comparisons never round.

#include "MaxSeparation.h"
#include "Midpoint.h"
#include "ReferenceFace.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {

namespace {

/// The edge of poly2 most anti-parallel to reference edge `edge1` of poly1, as two clip
/// vertices in poly1's frame with 2.2.1's feature ids (face of poly1, vertex of poly2).
void b2FindIncidentEdge(b2ClipVertex c[2], const b2PolygonShape* poly1, int32 edge1, const b2PolygonShape* poly2,
                        const b2Transform& xf) {
    const int32 count2 = poly2->m_vertexCount;
    const b2Vec2* vertices2 = poly2->m_vertices;
    const b2Vec2* normals2 = poly2->m_normals;

    // Get the normal of the reference edge in poly2's frame.
    const b2Vec2 normal1 = b2MulT(xf.q, poly1->m_normals[edge1]);

    // Find the incident edge on poly2 (first minimum on ties).
    int32 index = 0;
    Wide minDot = Wide::FromRaw(Wide::kMaxRaw);
    for (int32 i = 0; i < count2; ++i) {
        const Wide dot = b2DotWide(normal1, normals2[i]);
        if (dot < minDot) {
            minDot = dot;
            index = i;
        }
    }

    // Build the clip vertices for the incident edge.
    const int32 i1 = index;
    const int32 i2 = i1 + 1 < count2 ? i1 + 1 : 0;
    const int32 ends[2] = {i1, i2};
    for (int32 k = 0; k < 2; ++k) {
        c[k].v = b2Mul(xf, vertices2[ends[k]]);
        c[k].id.cf.indexA = static_cast<uint8>(edge1);
        c[k].id.cf.indexB = static_cast<uint8>(ends[k]);
        c[k].id.cf.typeA = b2ContactFeature::e_face;
        c[k].id.cf.typeB = b2ContactFeature::e_vertex;
    }
}

}  // namespace

// Find edge normal of max separation on A: return if separating axis is found.
// Find edge normal of max separation on B: return if separation axis is found.
// Choose reference edge as min(minA, minB).
// Find incident edge.
// Clip.
void b2CollidePolygons(b2Manifold* manifold, const b2PolygonShape* polyA, const b2Transform& xfA,
                       const b2PolygonShape* polyB, const b2Transform& xfB) {
    manifold->pointCount = 0;
    // An empty polygon (never Set) collides with nothing; this also keeps the separation
    // sentinels out of the hysteresis arithmetic below.
    if (polyA->m_vertexCount <= 0 || polyB->m_vertexCount <= 0) return;
    const Fixed totalRadius = polyA->m_radius + polyB->m_radius;
    const Wide totalRadiusWide(totalRadius);

    // Relative transforms: B's frame into A's, and (once A's edges found no gap) A's into B's.
    const b2Transform xfAB = b2MulT(xfA, xfB);
    int32 edgeA = 0;
    const Wide separationA = collision_detail::MaxSeparation(&edgeA, polyA, polyB, xfAB);
    if (separationA > totalRadiusWide) return;

    const b2Transform xfBA = b2MulT(xfB, xfA);
    int32 edgeB = 0;
    const Wide separationB = collision_detail::MaxSeparation(&edgeB, polyB, polyA, xfBA);
    if (separationB > totalRadiusWide) return;

    const b2PolygonShape* poly1;  // reference polygon
    const b2PolygonShape* poly2;  // incident polygon
    b2Transform xf;               // poly2's frame into poly1's
    int32 edge1;                  // reference edge
    bool flip;

    if (collision_detail::PreferSecond(separationA, separationB)) {
        poly1 = polyB;
        poly2 = polyA;
        xf = xfBA;
        edge1 = edgeB;
        manifold->type = b2Manifold::e_faceB;
        flip = true;
    } else {
        poly1 = polyA;
        poly2 = polyB;
        xf = xfAB;
        edge1 = edgeA;
        manifold->type = b2Manifold::e_faceA;
        flip = false;
    }

    b2ClipVertex incidentEdge[2];
    b2FindIncidentEdge(incidentEdge, poly1, edge1, poly2, xf);

    const int32 count1 = poly1->m_vertexCount;
    const b2Vec2* vertices1 = poly1->m_vertices;

    const int32 iv1 = edge1;
    const int32 iv2 = edge1 + 1 < count1 ? edge1 + 1 : 0;

    const b2Vec2 v11 = vertices1[iv1];
    const b2Vec2 v12 = vertices1[iv2];

    // In poly1's frame the local tangent and normal are also the clipping ones.
    b2Vec2 tangent = v12 - v11;
    tangent.Normalize();
    const b2Vec2 normal = b2Cross(tangent, Fixed(1));
    const b2Vec2 planePoint = collision_detail::MidpointRoundedOnSum(v11, v12);

    // Side offsets, extended by polytope skin thickness (rounded once each).
    const Fixed sideOffset1 = totalRadius - b2Dot(tangent, v11);
    const Fixed sideOffset2 = b2Dot(tangent, v12) + totalRadius;

    // Clip incident edge against extruded edge1 side edges.
    b2ClipVertex clipPoints1[2];
    b2ClipVertex clipPoints2[2];

    // Clip to box side 1
    int32 np = b2ClipSegmentToLine(clipPoints1, incidentEdge, -tangent, sideOffset1, iv1);
    if (np < 2) return;

    // Clip to negative box side 1
    np = b2ClipSegmentToLine(clipPoints2, clipPoints1, tangent, sideOffset2, iv2);
    if (np < 2) return;

    // Now clipPoints2 contains the clipped points.
    manifold->localNormal = normal;
    manifold->localPoint = planePoint;

    int32 pointCount = 0;
    for (int32 i = 0; i < b2_maxManifoldPoints; ++i) {
        // Height above the reference face, exact.
        const Wide separation = b2DotWide(normal, clipPoints2[i].v - v11);
        if (separation <= totalRadiusWide) {
            b2ManifoldPoint* cp = manifold->points + pointCount;
            const b2ContactFeature cf = clipPoints2[i].id.cf;
            // An unclipped point is a vertex of poly2: store that vertex exactly instead of
            // sending it to poly1's frame and back (which 2.2.1 does, and which rounds twice).
            if (cf.typeB == b2ContactFeature::e_vertex) {
                cp->localPoint = poly2->m_vertices[cf.indexB];
            } else {
                cp->localPoint = b2MulT(xf, clipPoints2[i].v);
            }
            cp->normalImpulse = Wide();
            cp->tangentImpulse = Wide();
            cp->id.cf = cf;
            if (flip) {
                // Swap features
                cp->id.cf.indexA = cf.indexB;
                cp->id.cf.indexB = cf.indexA;
                cp->id.cf.typeA = cf.typeB;
                cp->id.cf.typeB = cf.typeA;
            }
            ++pointCount;
        }
    }

    manifold->pointCount = pointCount;
}

}  // namespace lockbox
