// b2PolygonShape::ComputeMass and the centroid: triangle-fan sums, exact in 128 bits.
//
// With the fan apex s = v0 and e1 = v[i] - s, e2 = v[i+1] - s, D = cross(e1, e2):
//   area              A = sum(D) / 2
//   area * centroid   A c' = sum(D (e1 + e2)) / 6          (c' relative to s)
//   inertia about s   Is = sum(D (ex1^2 + ex1 ex2 + ex2^2 + ey1^2 + ey1 ey2 + ey2^2)) / 12
// and the parallel-axis theorem moves Is to the body origin without the rounded centroid:
//   I0 = Is - A|c'|^2 + A|s + c'|^2 = Is + A|s|^2 + 2 s.(A c')
//      = (sum(D q) + 6 sum(D) |s|^2 + 4 s.sum(D (e1 + e2))) / 12.
// Raw units: D is Q32.32, the centroid sum Q48.48, the inertia sums Q64.64. Vertices within
// b2_maxShapeCoordinate (2^28 raw) give edges < 2^29 raw, D < 2^59, D q < 2^120 and the total
// below 2^125, so nothing is rounded until the final scaling.

#include "ShapeInternal.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {

using shape_detail::S128;

namespace {

struct FanSums {
    int64_t sumD = 0;  // twice the area, Q32.32 raw (< 2^62 for any polygon in range)
    S128 cx, cy;       // sum D (e1 + e2), Q48.48 raw
    S128 inertia;      // sum D q, Q64.64 raw
};

FanSums SumFan(const b2Vec2* v, int32 count) noexcept {
    FanSums sums;
    const int64_t sx = v[0].x.Raw(), sy = v[0].y.Raw();
    for (int32 i = 1; i + 1 < count; ++i) {
        // Triangles (s, v0, v1) and (s, v[n-1], v0) are degenerate with s = v0: skipped.
        const int64_t ex1 = v[i].x.Raw() - sx, ey1 = v[i].y.Raw() - sy;
        const int64_t ex2 = v[i + 1].x.Raw() - sx, ey2 = v[i + 1].y.Raw() - sy;
        const int64_t d = ex1 * ey2 - ey1 * ex2;
        sums.sumD += d;
        sums.cx = detail::AddS128(sums.cx, detail::MulS64(d, ex1 + ex2));
        sums.cy = detail::AddS128(sums.cy, detail::MulS64(d, ey1 + ey2));
        const int64_t q = ex1 * ex1 + ex1 * ex2 + ex2 * ex2 + ey1 * ey1 + ey1 * ey2 + ey2 * ey2;  // < 2^61
        sums.inertia = detail::AddS128(sums.inertia, detail::MulS64(d, q));
    }
    return sums;
}

// round(num / den) for a Q48.48 sum over a Q32.32 divisor: a Q16.16 raw.
Fixed RatioToFixed(const S128& num, int64_t den) noexcept {
    const S128 q = detail::DivRoundS128(num, shape_detail::ToS128(den));
    return Fixed::FromRaw(static_cast<int32_t>(
        detail::NarrowRaw(detail::FitsS64(q) ? detail::ToS64(q) : INT64_MAX, "polygon centroid", den, 0)));
}

}  // namespace

namespace shape_detail {

b2Vec2 ComputePolygonCentroid(const b2Vec2* vertices, int32 count) noexcept {
    if (count < 3) return b2Vec2();
    const FanSums sums = SumFan(vertices, count);
    if (sums.sumD == 0) return vertices[0];  // unreachable for validated polygons
    // c = s + sum(D (e1 + e2)) / (3 sum(D)); the centroid lies inside the polygon, so in range.
    const Fixed cx = RatioToFixed(sums.cx, 3 * sums.sumD);
    const Fixed cy = RatioToFixed(sums.cy, 3 * sums.sumD);
    return vertices[0] + b2Vec2(cx, cy);
}

}  // namespace shape_detail

void b2PolygonShape::ComputeMass(b2MassData* massData, Fixed density) const {
    massData->mass = Wide();
    massData->center.SetZero();
    massData->I = Wide();
    if (m_vertexCount < 3) return;  // an unset polygon has no mass
    for (int32 i = 0; i < m_vertexCount; ++i) {
        if (!shape_detail::InShapeRange(m_vertices[i])) {
            // Only reachable by writing m_vertices directly past the setters: the exact sums
            // would overflow, so report it like any other overflow and leave the mass at 0.
            detail::OnOverflow("b2PolygonShape::ComputeMass: vertex beyond b2_maxShapeCoordinate",
                               m_vertices[i].x.Raw(), m_vertices[i].y.Raw());
            return;
        }
    }
    const FanSums sums = SumFan(m_vertices, m_vertexCount);
    if (sums.sumD <= 0) return;  // unreachable for validated polygons (area >= 2^-10 m^2)

    // mass = density * sum(D) / 2: Q16.16 * Q32.32 -> shift 17 to Q32.32, one rounding.
    massData->mass =
        Wide::FromRaw(detail::NarrowWide(detail::ShrRoundS128(detail::MulS64(density.Raw(), sums.sumD), 17),
                                         "b2PolygonShape::ComputeMass mass", density.Raw(), sums.sumD));

    const Fixed cx = RatioToFixed(sums.cx, 3 * sums.sumD);
    const Fixed cy = RatioToFixed(sums.cy, 3 * sums.sumD);
    massData->center = m_vertices[0] + b2Vec2(cx, cy);

    // 12 * I0 / density in Q64.64 (see the header comment); every term < 2^123.
    const int64_t sx = m_vertices[0].x.Raw(), sy = m_vertices[0].y.Raw();
    const int64_t ss = sx * sx + sy * sy;  // < 2^57
    S128 twelveI = sums.inertia;
    twelveI = detail::AddS128(twelveI, detail::MulS128S64(detail::MulS64(sums.sumD, ss), 6));
    const S128 sDotC = detail::AddS128(detail::MulS128S64(sums.cx, sx), detail::MulS128S64(sums.cy, sy));
    twelveI = detail::AddS128(twelveI, detail::MulS128S64(sDotC, 4));
    // I0 / density as Q?.48 (rounding 2^-49 m^4, negligible), then times density (Q16.16) and
    // down to Q32.32. MulShiftNarrow saturates when I exceeds the Wide range (~2.1e9 kg m^2).
    const S128 unitI = detail::DivRoundS128(twelveI, shape_detail::ToS128(int64_t{12} << 16));
    massData->I =
        Wide::FromRaw(shape_detail::MulShiftNarrow(unitI, density.Raw(), 32, "b2PolygonShape::ComputeMass I"));
}

}  // namespace lockbox
