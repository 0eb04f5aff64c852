// The polygon collision's separating-axis search: the scan (Box2D 2.3+'s b2FindMaxSeparation,
// every edge) and its closed form for two centred boxes.
#include "MaxSeparation.h"

#include <cstdlib>

#include "shapes/CentredBox.h"

namespace lockbox::collision_detail {

namespace {

/// Separation of poly2 from edge `edge1` of poly1 (both in poly1's frame; xf maps poly2's
/// frame into poly1's). Box2D's b2EdgeSeparation. `box2` says whether poly2 is a centred box.
Wide EdgeSeparation(const b2PolygonShape* poly1, int32 edge1, const b2PolygonShape* poly2, bool box2,
                    const b2Transform& xf) {
    const b2Vec2* vertices1 = poly1->m_vertices;
    const b2Vec2* normals1 = poly1->m_normals;
    const int32 count2 = poly2->m_vertexCount;
    const b2Vec2* vertices2 = poly2->m_vertices;

    // Convert normal from poly1's frame into poly2's frame.
    const b2Vec2 normal1 = b2MulT(xf.q, normals1[edge1]);

    // Find support vertex on poly2 for -normal (first minimum on ties, as Box2D). A centred
    // box's is the corner opposite the normal's signs; its dot products are exact and cannot
    // saturate for a normal of unit range, so skipping them changes nothing.
    int32 index = 0;
    if (box2 && shape_detail::InUnitRange(normal1.x) && shape_detail::InUnitRange(normal1.y)) {
        index = shape_detail::CentredBoxSupport(normal1);
    } else {
        Wide minDot = Wide::FromRaw(Wide::kMaxRaw);
        for (int32 i = 0; i < count2; ++i) {
            const Wide dot = b2DotWide(vertices2[i], normal1);
            if (dot < minDot) {
                minDot = dot;
                index = i;
            }
        }
    }

    const b2Vec2 v1 = vertices1[edge1];
    const b2Vec2 v2 = b2Mul(xf, vertices2[index]);
    return b2DotWide(v2 - v1, normals1[edge1]);
}

// Corrected form (Box2D 2.3+): every edge of poly1 is scanned. 2.2.1 starts at the normal facing
// poly2's centroid and hill-climbs to a neighbour while the separation grows; for deep overlaps
// the separation over the edges is not unimodal, the climb stops at a local maximum, and the
// manifold then pushes along a deeper axis than necessary (the differential test against 2.4.1
// found it in 0.1 % of random pairs, all with overlaps of 0.2 m or more). The full scan costs
// count1 * count2 dot products (64 at most) and returns the true maximum; ties keep the lowest
// edge index (strict >), so the choice is a total order on edge ids.
Wide Scan(int32* edgeIndex, const b2PolygonShape* poly1, const b2PolygonShape* poly2, bool box2,
          const b2Transform& xf) {
    const int32 count1 = poly1->m_vertexCount;
    int32 bestEdge = 0;
    Wide maxSeparation = Wide::FromRaw(-Wide::kMaxRaw);
    for (int32 i = 0; i < count1; ++i) {
        const Wide s = EdgeSeparation(poly1, i, poly2, box2, xf);
        if (s > maxSeparation) {
            maxSeparation = s;
            bestEdge = i;
        }
    }
    *edgeIndex = bestEdge;
    return maxSeparation;
}

// The closed form's ranges: a rotation component at most one (raw 2^16), an offset below 2^29
// raw (8192 m), half-extents below 2^27 raw (2048 m). Within them a rotated corner is below 2^28
// raw and every Q16.16 sum and difference of the scan below 2^30, so the scan saturates nowhere
// and its every step is exact but the one rounding of each rotated coordinate.
constexpr int64_t kMaxTurn = Fixed::kOneRaw;
constexpr int64_t kMaxOffset = int64_t{1} << 29;
constexpr int64_t kMaxHalf = int64_t{1} << 27;

/// The scan for two centred boxes, box1 with its axis normals. Edge e of box1 has the unit
/// normal n_e (0,-1), (1,0), (0,1), (-1,0); in box2's frame it is R^T n_e, whose support corner
/// is the one opposite its signs, and that corner sent into box1's frame has, along n_e, the
/// coordinate p.n_e - round(|c| hx2 + |s| hy2) (x edges) or p.n_e - round(|s| hx2 + |c| hy2) (y
/// edges): the rotated corner's products all take the sign that lowers it, and the rounding, ties
/// away from zero, is odd. A zero component ties two corners whose coordinate along n_e is the
/// same, so the scan's choice between them does not matter. The separation is that coordinate
/// less box1's half-extent.
bool BoxPair(int32* edgeIndex, Wide* separation, const shape_detail::CentredBox& box1,
             const shape_detail::CentredBox& box2, const b2Transform& xf) {
    const int64_t c = xf.q.c.Raw(), s = xf.q.s.Raw(), px = xf.p.x.Raw(), py = xf.p.y.Raw();
    if (std::abs(c) > kMaxTurn || std::abs(s) > kMaxTurn || std::abs(px) >= kMaxOffset || std::abs(py) >= kMaxOffset ||
        box1.hx >= kMaxHalf || box1.hy >= kMaxHalf || box2.hx >= kMaxHalf || box2.hy >= kMaxHalf)
        return false;
    const int64_t ac = std::abs(c), as = std::abs(s);
    const int64_t ex = detail::ShiftRound(ac * box2.hx + as * box2.hy, Fixed::kFractionBits);
    const int64_t ey = detail::ShiftRound(as * box2.hx + ac * box2.hy, Fixed::kFractionBits);
    const int64_t seps[4] = {-py - ey - box1.hy, px - ex - box1.hx, py - ey - box1.hy, -px - ex - box1.hx};
    int32 best = 0;
    for (int32 e = 1; e < 4; ++e)
        if (seps[e] > seps[best]) best = e;
    *edgeIndex = best;
    *separation = Wide(Fixed::FromRaw(static_cast<int32_t>(seps[best])));
    return true;
}

}  // namespace

Wide ScannedMaxSeparation(int32* edgeIndex, const b2PolygonShape* poly1, const b2PolygonShape* poly2,
                          const b2Transform& xf) {
    shape_detail::CentredBox box;
    return Scan(edgeIndex, poly1, poly2, shape_detail::AsCentredBox(poly2->m_vertices, poly2->m_vertexCount, &box), xf);
}

Wide MaxSeparation(int32* edgeIndex, const b2PolygonShape* poly1, const b2PolygonShape* poly2, const b2Transform& xf) {
    shape_detail::CentredBox box1, box2;
    const bool isBox2 = shape_detail::AsCentredBox(poly2->m_vertices, poly2->m_vertexCount, &box2);
    if (isBox2 && shape_detail::AsCentredBox(poly1->m_vertices, poly1->m_vertexCount, &box1) &&
        shape_detail::HasAxisNormals(poly1->m_normals)) {
        Wide separation;
        if (BoxPair(edgeIndex, &separation, box1, box2, xf)) return separation;
    }
    return Scan(edgeIndex, poly1, poly2, isBox2, xf);
}

}  // namespace lockbox::collision_detail
