// b2PolygonShape: setters, point test, exact ray cast and AABB. Validation and the hull live
// in PolygonValidate.cpp, the mass properties in PolygonMass.cpp.

#include "lockbox/collision/PolygonShape.h"

#include <cstdlib>

#include "CentredBox.h"
#include "ShapeInternal.h"

namespace lockbox {

std::unique_ptr<b2Shape> b2PolygonShape::Clone() const { return std::make_unique<b2PolygonShape>(*this); }

b2ShapeError b2PolygonShape::Set(const b2Vec2* points, int32 count) noexcept {
    const b2ShapeError error = b2ValidatePolygon(points, count);
    if (error != b2ShapeError::ok) return error;
    m_vertexCount = count;
    for (int32 i = 0; i < count; ++i) m_vertices[i] = points[i];
    for (int32 i = 0; i < count; ++i) {
        const b2Vec2 edge = m_vertices[i + 1 < count ? i + 1 : 0] - m_vertices[i];
        // Exact (e.y, -e.x); Normalize keeps the direction to 2 ULP even for short edges.
        m_normals[i] = b2Cross(edge, Fixed(1));
        m_normals[i].Normalize();
    }
    m_centroid = shape_detail::ComputePolygonCentroid(m_vertices, m_vertexCount);
    return b2ShapeError::ok;
}

namespace {
// Shared front half of both SetAsBox overloads: the extent checks.
b2ShapeError CheckBoxExtents(Fixed hx, Fixed hy) noexcept {
    if (hx.Raw() <= 0 || hy.Raw() <= 0) return b2ShapeError::nonPositiveExtent;
    if (hx > b2_maxShapeCoordinate || hy > b2_maxShapeCoordinate) return b2ShapeError::outOfRange;
    return b2ShapeError::ok;
}
}  // namespace

b2ShapeError b2PolygonShape::SetAsBox(Fixed hx, Fixed hy) noexcept {
    const b2ShapeError extents = CheckBoxExtents(hx, hy);
    if (extents != b2ShapeError::ok) return extents;
    const b2Vec2 v[4] = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
    const b2ShapeError error = b2ValidatePolygon(v, 4);
    if (error != b2ShapeError::ok) return error;
    m_vertexCount = 4;
    for (int32 i = 0; i < 4; ++i) m_vertices[i] = v[i];
    m_normals[0].Set(0, -1);
    m_normals[1].Set(1, 0);
    m_normals[2].Set(0, 1);
    m_normals[3].Set(-1, 0);
    m_centroid.SetZero();
    return b2ShapeError::ok;
}

b2ShapeError b2PolygonShape::SetAsBox(Fixed hx, Fixed hy, const b2Vec2& center, Fixed angle) noexcept {
    const b2ShapeError extents = CheckBoxExtents(hx, hy);
    if (extents != b2ShapeError::ok) return extents;
    // Rejecting far centres first also keeps b2Mul below from saturating: |center| + hx + hy
    // stays under 3 * 4096 m.
    if (!shape_detail::InShapeRange(center)) return b2ShapeError::outOfRange;
    const b2Transform xf(center, b2Rot(angle));
    const b2Vec2 local[4] = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
    b2Vec2 v[4];
    for (int32 i = 0; i < 4; ++i) v[i] = b2Mul(xf, local[i]);
    const b2ShapeError error = b2ValidatePolygon(v, 4);
    if (error != b2ShapeError::ok) return error;
    m_vertexCount = 4;
    for (int32 i = 0; i < 4; ++i) m_vertices[i] = v[i];
    const b2Vec2 normals[4] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    for (int32 i = 0; i < 4; ++i) m_normals[i] = b2Mul(xf.q, normals[i]);
    m_centroid = center;
    return b2ShapeError::ok;
}

bool b2PolygonShape::Validate() const noexcept {
    if (m_vertexCount < 3 || m_vertexCount > b2_maxPolygonVertices) return false;
    for (int32 i = 0; i < m_vertexCount; ++i) {
        if (!shape_detail::InShapeRange(m_vertices[i])) return false;  // keeps Cross3Raw exact
    }
    for (int32 i = 0; i < m_vertexCount; ++i) {
        const int32 i2 = i + 1 < m_vertexCount ? i + 1 : 0;
        for (int32 j = 0; j < m_vertexCount; ++j) {
            if (j == i || j == i2) continue;
            if (shape_detail::Cross3Raw(m_vertices[i], m_vertices[i2], m_vertices[j]) <= 0) return false;
        }
    }
    return true;
}

bool b2PolygonShape::TestPoint(const b2Transform& xf, const b2Vec2& p) const {
    const b2Vec2 pLocal = b2MulT(xf.q, p - xf.p);
    for (int32 i = 0; i < m_vertexCount; ++i) {
        // Exact dot(n, pLocal - v): |n| <= 2^17 raw, |pLocal - v| < 2^33 raw.
        const int64_t dx = int64_t{pLocal.x.Raw()} - m_vertices[i].x.Raw();
        const int64_t dy = int64_t{pLocal.y.Raw()} - m_vertices[i].y.Raw();
        if (int64_t{m_normals[i].x.Raw()} * dx + int64_t{m_normals[i].y.Raw()} * dy > 0) return false;
    }
    return m_vertexCount > 0;
}

bool b2PolygonShape::RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& xf,
                             int32 childIndex) const {
    (void)childIndex;
    // The ray in the polygon's frame of reference (rounded once per component, as 2.2.1).
    const b2Vec2 p1 = b2MulT(xf.q, input.p1 - xf.p);
    const b2Vec2 p2 = b2MulT(xf.q, input.p2 - xf.p);
    const int64_t dx = int64_t{p2.x.Raw()} - p1.x.Raw();
    const int64_t dy = int64_t{p2.y.Raw()} - p1.y.Raw();
    // lower = lowerNum / lowerDen and upper = upperNum / upperDen, denominators > 0. Keeping
    // exact ratios replaces 2.2.1's divisions: no 1/0, no rounding inside the clipping loop.
    int64_t lowerNum = 0, lowerDen = 1;
    int64_t upperNum = input.maxFraction.Raw(), upperDen = Fixed::kOneRaw;
    int32 index = -1;
    for (int32 i = 0; i < m_vertexCount; ++i) {
        const int64_t nx = m_normals[i].x.Raw(), ny = m_normals[i].y.Raw();
        // p = p1 + a d on the face line: dot(n, v - p1) = a dot(n, d). Both < 2^51 raw.
        const int64_t numerator =
            nx * (int64_t{m_vertices[i].x.Raw()} - p1.x.Raw()) + ny * (int64_t{m_vertices[i].y.Raw()} - p1.y.Raw());
        const int64_t denominator = nx * dx + ny * dy;
        if (denominator == 0) {
            // Parallel to this face: outside its half-plane means no hit at all.
            if (numerator < 0) return false;
        } else if (denominator < 0) {
            // The segment enters this half-space at numerator / denominator; raise lower.
            if (shape_detail::CompareProducts(lowerNum, -denominator, -numerator, lowerDen) < 0) {
                lowerNum = -numerator;
                lowerDen = -denominator;
                index = i;
            }
        } else {
            // The segment leaves this half-space; lower upper.
            if (shape_detail::CompareProducts(numerator, upperDen, upperNum, denominator) < 0) {
                upperNum = numerator;
                upperDen = denominator;
            }
        }
        if (shape_detail::CompareProducts(upperNum, lowerDen, lowerNum, upperDen) < 0) return false;
    }
    if (index < 0) return false;  // p1 inside (or on) the polygon: no hit
    // 0 <= lower <= maxFraction exactly, and rounding to nearest cannot leave that interval.
    output->fraction = Fixed::FromRatio(lowerNum, lowerDen);
    output->normal = b2Mul(xf.q, m_normals[index]);
    return true;
}

namespace {

// The box of a SetAsBox(hx, hy) polygon (centred on its body, edges along its axes; the
// commonest shape) without rotating its four corners. A corner (+-hx, +-hy) turns to
// round(+-c hx -+ s hy) and round(+-s hx +- c hy), each one exact sum of products rounded once;
// the rounding is monotonic and odd, so the least and greatest of the four are
// -+round(|c hx| + |s hy|) and -+round(|s hx| + |c hy|): the loop's very values. Taken only
// where no corner can saturate (so the overflow reports are the loop's too, none), and only for
// a rotation's range of c and s, where the sums cannot leave 64 bits.
bool CentredBoxAABB(const b2Vec2* v, int32 count, Fixed radius, const b2Transform& xf, b2AABB* aabb) noexcept {
    shape_detail::CentredBox box;
    if (!shape_detail::AsCentredBox(v, count, &box)) return false;
    if (!shape_detail::InUnitRange(xf.q.c) || !shape_detail::InUnitRange(xf.q.s)) return false;
    const int64_t hx = box.hx, hy = box.hy;
    const int64_t c = xf.q.c.Raw(), s = xf.q.s.Raw();
    // Q32.32 sums below 2^49, rounded to Q16.16 as Wide::ToFixed rounds.
    const int64_t ex = detail::ShiftRound(std::abs(c * hx) + std::abs(s * hy), 16);
    const int64_t ey = detail::ShiftRound(std::abs(s * hx) + std::abs(c * hy), 16);
    const int64_t r = radius.Raw();
    const int64_t px = xf.p.x.Raw(), py = xf.p.y.Raw();
    constexpr int64_t kMax = Fixed::kMaxRaw;
    if (r < 0 || std::abs(px) + ex + r > kMax || std::abs(py) + ey + r > kMax) return false;
    aabb->lowerBound =
        b2Vec2(Fixed::FromRaw(static_cast<int32>(px - ex - r)), Fixed::FromRaw(static_cast<int32>(py - ey - r)));
    aabb->upperBound =
        b2Vec2(Fixed::FromRaw(static_cast<int32>(px + ex + r)), Fixed::FromRaw(static_cast<int32>(py + ey + r)));
    return true;
}

}  // namespace

void b2PolygonShape::ComputeAABB(b2AABB* aabb, const b2Transform& xf, int32 childIndex) const {
    (void)childIndex;
    if (CentredBoxAABB(m_vertices, m_vertexCount, m_radius, xf, aabb)) return;
    b2Vec2 lower = b2Mul(xf, m_vertices[0]);
    b2Vec2 upper = lower;
    for (int32 i = 1; i < m_vertexCount; ++i) {
        const b2Vec2 v = b2Mul(xf, m_vertices[i]);
        lower = b2Min(lower, v);
        upper = b2Max(upper, v);
    }
    const b2Vec2 r(m_radius, m_radius);
    aabb->lowerBound = lower - r;
    aabb->upperBound = upper + r;
}

}  // namespace lockbox
