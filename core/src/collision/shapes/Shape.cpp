// b2ShapeErrorMessage and the segment helpers shared by edges and chains.

#include "lockbox/collision/Shape.h"

#include "ShapeInternal.h"

namespace lockbox {

const char* b2ShapeErrorMessage(b2ShapeError error) noexcept {
    switch (error) {
        case b2ShapeError::ok: return "ok";
        case b2ShapeError::tooFewVertices: return "too few vertices (polygon and loop need 3, chain needs 2)";
        case b2ShapeError::tooManyVertices:
            return "too many vertices (a polygon has at most b2_maxPolygonVertices = 8)";
        case b2ShapeError::duplicateVertices: return "two vertices are closer than the weld distance";
        case b2ShapeError::collinear: return "collinear vertices (all on a line, or a vertex on its neighbours' chord)";
        case b2ShapeError::notConvex: return "the polygon is not convex";
        case b2ShapeError::clockwise: return "the polygon is clockwise; give the vertices counter-clockwise";
        case b2ShapeError::areaTooSmall: return "the polygon area is below b2_minPolygonArea (2^-10 m^2)";
        case b2ShapeError::nonPositiveExtent: return "box half-extents must be positive";
        case b2ShapeError::nonPositiveRadius: return "the circle radius must be positive";
        case b2ShapeError::outOfRange: return "a coordinate is beyond b2_maxShapeCoordinate (4096 m)";
    }
    return "unknown shape error";
}

namespace shape_detail {

b2AABB SegmentAABB(const b2Vec2& v1, const b2Vec2& v2, Fixed radius) noexcept {
    const b2Vec2 r(radius, radius);
    b2AABB aabb;
    aabb.lowerBound = b2Min(v1, v2) - r;
    aabb.upperBound = b2Max(v1, v2) + r;
    return aabb;
}

bool RayCastSegment(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& xf, const b2Vec2& v1,
                    const b2Vec2& v2) {
    // The ray in the segment's frame, as 2.2.1 does; after this everything is exact.
    const b2Vec2 p1 = b2MulT(xf.q, input.p1 - xf.p);
    const b2Vec2 p2 = b2MulT(xf.q, input.p2 - xf.p);
    int64_t dx = int64_t{p2.x.Raw()} - p1.x.Raw(), dy = int64_t{p2.y.Raw()} - p1.y.Raw();
    int64_t ex = int64_t{v2.x.Raw()} - v1.x.Raw(), ey = int64_t{v2.y.Raw()} - v1.y.Raw();
    int64_t qx = int64_t{v1.x.Raw()} - p1.x.Raw(), qy = int64_t{v1.y.Raw()} - p1.y.Raw();
    // Unnormalised normal (e.y, -e.x): the hit fraction t = num / den is scale-free, so no
    // rounding happens before the tests. Every difference must stay below 2^31 raw so each dot
    // product stays below 2^63; only rays starting more than 32768 m from the edge (or edges
    // written directly beyond b2_maxShapeCoordinate) are scaled down, losing bits in proportion.
    uint64_t largest = 0;
    for (int64_t v : {dx, dy, ex, ey, qx, qy}) largest = detail::AbsU64(v) > largest ? detail::AbsU64(v) : largest;
    int shift = 0;
    while ((largest >> shift) >= (uint64_t{1} << 31)) ++shift;
    if (shift > 0) {
        for (int64_t* v : {&dx, &dy, &ex, &ey, &qx, &qy}) *v = detail::ShiftRound(*v, shift);
    }
    const int64_t rr = ex * ex + ey * ey;
    if (rr == 0) return false;  // a degenerate (unset) edge has no line to hit
    const int64_t numerator = ey * qx - ex * qy;
    const int64_t denominator = ey * dx - ex * dy;
    if (denominator == 0) return false;  // parallel (exactly: no epsilon needed)
    // t = numerator / denominator with a positive denominator.
    const int64_t tn = denominator < 0 ? -numerator : numerator;
    const int64_t td = denominator < 0 ? -denominator : denominator;
    if (tn < 0) return false;
    if (CompareProducts(tn, Fixed::kOneRaw, input.maxFraction.Raw(), td) > 0) return false;
    // The hit q = p1 + t d must lie on the segment: s = dot(q - v1, e) / rr in [0, 1].
    // Multiplied by td: s*rr*td = dot(p1 - v1, e) * td + tn * dot(d, e).
    const int64_t pe = -(qx * ex + qy * ey);
    const int64_t de = dx * ex + dy * ey;
    const S128 sNum = detail::AddS128(detail::MulS64(pe, td), detail::MulS64(tn, de));
    if (sNum.negative) return false;
    if (Compare(sNum, detail::MulS64(rr, td)) > 0) return false;

    // |e| < 2^31 raw after the scaling, so the unnormalised normal fits a b2Vec2 (as raws).
    b2Vec2 normal(Fixed::FromRaw(static_cast<int32_t>(ey)), Fixed::FromRaw(static_cast<int32_t>(-ex)));
    normal.Normalize();
    if (numerator > 0) normal = -normal;  // face the side the ray comes from
    output->fraction = Fixed::FromRatio(tn, td);
    // 2.2.1 returned the local normal here; the world normal is what callers need.
    output->normal = b2Mul(xf.q, normal);
    return true;
}

}  // namespace shape_detail
}  // namespace lockbox
