// GJK distance (Box2D 2.2.1's b2Distance.cpp) with exact integer decisions.
//
// Where 2.2.1 computes barycentric weights in float and tests them against 0, this file keeps
// every weight as an exact integer numerator over a common positive denominator:
//   segment:  numerators d12_1, d12_2 (exact Q32.32 dot products), denominator |e12|²;
//   triangle: numerators cross(w2,w3), cross(w3,w1), cross(w1,w2) (exact Q32.32), denominator
//             n123 = cross(e12, e13), which is exactly their sum.
// 2.2.1's d123_i = n123 * cross(...) is an L⁴ quantity (NUMERICS Table 2); only its sign is
// needed, so it is taken as sign(n123) * sign(cross) and never formed. Witness points are one
// exact 128-bit quotient per component, rounded once.

#include "lockbox/collision/Distance.h"

#include <cstdint>

#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {

b2DistanceProxy& b2DistanceProxy::operator=(const b2DistanceProxy& other) noexcept {
    if (this == &other) return *this;
    m_buffer[0] = other.m_buffer[0];
    m_buffer[1] = other.m_buffer[1];
    // A pointer into the other proxy's buffer would dangle once it dies: use our own copy.
    m_vertices = other.m_vertices == other.m_buffer ? m_buffer : other.m_vertices;
    m_count = other.m_count;
    m_radius = other.m_radius;
    return *this;
}

void b2DistanceProxy::Set(const b2Shape* shape, int32 index) {
    switch (shape->GetType()) {
        case b2Shape::e_circle: {
            const auto* circle = static_cast<const b2CircleShape*>(shape);
            m_vertices = &circle->m_p;
            m_count = 1;
            m_radius = circle->m_radius;
            break;
        }
        case b2Shape::e_polygon: {
            const auto* polygon = static_cast<const b2PolygonShape*>(shape);
            m_vertices = polygon->m_vertices;
            m_count = polygon->m_vertexCount;
            m_radius = polygon->m_radius;
            break;
        }
        case b2Shape::e_chain: {
            const auto* chain = static_cast<const b2ChainShape*>(shape);
            m_buffer[0] = chain->m_vertices[static_cast<size_t>(index)];
            // 2.2.1 wraps the last index to vertex 0 (a loop's closing edge).
            m_buffer[1] =
                index + 1 < chain->m_count ? chain->m_vertices[static_cast<size_t>(index + 1)] : chain->m_vertices[0];
            m_vertices = m_buffer;
            m_count = 2;
            m_radius = chain->m_radius;
            break;
        }
        case b2Shape::e_edge: {
            const auto* edge = static_cast<const b2EdgeShape*>(shape);
            m_buffer[0] = edge->m_vertex1;
            m_buffer[1] = edge->m_vertex2;
            m_vertices = m_buffer;
            m_count = 2;
            m_radius = edge->m_radius;
            break;
        }
        default:
            m_vertices = nullptr;
            m_count = 0;
            m_radius = Fixed();
            break;
    }
}

void b2DistanceProxy::Set(const b2Vec2* vertices, int32 count, Fixed radius) noexcept {
    m_vertices = vertices;
    m_count = count;
    m_radius = radius;
}

int32 b2DistanceProxy::GetSupport(const b2Vec2& d) const noexcept {
    int32 bestIndex = 0;
    Wide bestValue = b2DotWide(m_vertices[0], d);
    for (int32 i = 1; i < m_count; ++i) {
        const Wide value = b2DotWide(m_vertices[i], d);
        if (value > bestValue) {
            bestIndex = i;
            bestValue = value;
        }
    }
    return bestIndex;
}

namespace {

using detail::gjk::TransformPoint;

struct SimplexVertex {
    b2Vec2 wA;         // support point of A (world)
    b2Vec2 wB;         // support point of B (world)
    b2Vec2 w;          // wB - wA
    int32 indexA = 0;  // index of wA on A
    int32 indexB = 0;  // index of wB on B
};

// 2 * a < b, exactly (the doubled value may not fit int64).
bool TwiceLess(int64_t a, int64_t b) {
    const detail::S128 diff = detail::SubS128(detail::MulS64(a, 2), detail::MulS64(b, 1));
    return diff.negative;
}

int Sign64(int64_t v) { return (v > 0) - (v < 0); }

class Simplex {
public:
    void ReadCache(const b2SimplexCache* cache, const b2DistanceProxy* proxyA, const b2Transform& xfA,
                   const b2DistanceProxy* proxyB, const b2Transform& xfB) {
        m_count = cache->count <= 3 ? cache->count : 0;
        for (int32 i = 0; i < m_count; ++i) {
            // A cache written for other shapes must not index out of range: start afresh.
            if (cache->indexA[i] >= proxyA->GetVertexCount() || cache->indexB[i] >= proxyB->GetVertexCount()) {
                m_count = 0;
                break;
            }
            SetVertex(&m_v[i], cache->indexA[i], cache->indexB[i], proxyA, xfA, proxyB, xfB);
        }
        // Flush a simplex whose size changed by more than a factor two, or that degenerated.
        // 2.2.1's "metric2 < b2_epsilon" is "metric2 < 1 raw", i.e. <= 0, for an exact metric.
        if (m_count > 1) {
            const int64_t metric1 = cache->metric.Raw();
            const int64_t metric2 = GetMetric().Raw();
            if (TwiceLess(metric2, metric1) || TwiceLess(metric1, metric2) || metric2 <= 0) m_count = 0;
        }
        if (m_count == 0) {
            SetVertex(&m_v[0], 0, 0, proxyA, xfA, proxyB, xfB);
            m_count = 1;
        }
        SetSingle();
    }

    void WriteCache(b2SimplexCache* cache) const {
        cache->metric = GetMetric();
        cache->count = static_cast<uint16>(m_count);
        for (int32 i = 0; i < m_count; ++i) {
            cache->indexA[i] = static_cast<uint8>(m_v[i].indexA);
            cache->indexB[i] = static_cast<uint8>(m_v[i].indexB);
        }
    }

    static void SetVertex(SimplexVertex* v, int32 indexA, int32 indexB, const b2DistanceProxy* proxyA,
                          const b2Transform& xfA, const b2DistanceProxy* proxyB, const b2Transform& xfB) {
        v->indexA = indexA;
        v->indexB = indexB;
        v->wA = TransformPoint(xfA, proxyA->GetVertex(indexA));
        v->wB = TransformPoint(xfB, proxyB->GetVertex(indexB));
        v->w = v->wB - v->wA;
    }

    // Direction towards the origin from the current feature; exact (negations and swaps only).
    b2Vec2 GetSearchDirection() const {
        if (m_count == 1) return -m_v[0].w;
        const b2Vec2 e12 = m_v[1].w - m_v[0].w;
        const Wide sgn = b2CrossWide(e12, -m_v[0].w);
        // Origin left of e12: the left normal; otherwise (also exactly on the line) the right.
        return sgn > Wide() ? b2Cross(Fixed(1), e12) : b2Cross(e12, Fixed(1));
    }

    // Witness points: p = v1 + sum_i num_i (v_i - v1) / den, one rounding per component.
    void GetWitnessPoints(b2Vec2* pA, b2Vec2* pB) const {
        *pA = Combine(&SimplexVertex::wA);
        *pB = m_count == 3 ? *pA : Combine(&SimplexVertex::wB);
    }

    Wide GetMetric() const {
        switch (m_count) {
            case 2: return Wide(b2Distance(m_v[0].w, m_v[1].w));
            case 3: return b2CrossWide(m_v[1].w - m_v[0].w, m_v[2].w - m_v[0].w);
            default: return Wide();
        }
    }

    void Solve2();
    void Solve3();

    SimplexVertex m_v[3];
    int32 m_count = 0;

private:
    void SetSingle() {
        m_num[1] = m_num[2] = 0;
        m_den = 1;
    }
    void KeepOnly(int32 i) {
        m_v[0] = m_v[i];
        m_count = 1;
        SetSingle();
    }
    // Keeps vertices i and j (in that order) with weights numI, numJ over numI + numJ.
    void KeepEdge(int32 i, int32 j, int64_t numI, int64_t numJ) {
        const SimplexVertex vi = m_v[i], vj = m_v[j];
        m_v[0] = vi;
        m_v[1] = vj;
        m_count = 2;
        m_num[1] = numJ;
        m_num[2] = 0;
        m_den = (Wide::FromRaw(numI) + Wide::FromRaw(numJ)).Raw();
    }

    b2Vec2 Combine(b2Vec2 SimplexVertex::*member) const {
        const b2Vec2& p1 = m_v[0].*member;
        if (m_count == 1) return p1;
        b2Vec2 out;
        for (int axis = 0; axis < 2; ++axis) {
            const int64_t base = p1(axis).Raw();
            const int64_t d1 = (m_v[1].*member)(axis).Raw() - base;
            const int64_t d2 = m_count == 3 ? (m_v[2].*member)(axis).Raw() - base : 0;
            // The point is a convex combination of the vertices, so the offset fits.
            const int64_t offset = WeightedOffset(m_num[1], d1, m_num[2], d2, m_den);
            out(axis) = Fixed::FromRaw(detail::NarrowRaw(base + offset, "GJK witness point", base, offset));
        }
        return out;
    }

    // round((n1 d1 + n2 d2) / den), ties away from zero, den > 0. The sum is usually far below
    // 2^63 (metre-scale shapes: about 2^49), so a 64-bit division does; otherwise the same
    // rounding of the same rational is done in 128 bits. Both paths give identical results.
    static int64_t WeightedOffset(int64_t n1, int64_t d1, int64_t n2, int64_t d2, int64_t den) {
        int64_t p1 = 0, p2 = 0, sum = 0;
        if (!__builtin_mul_overflow(n1, d1, &p1) && !__builtin_mul_overflow(n2, d2, &p2) &&
            !__builtin_add_overflow(p1, p2, &sum) && sum != INT64_MIN) {
            const uint64_t mag = detail::AbsU64(sum);
            const uint64_t d = static_cast<uint64_t>(den);
            uint64_t q = mag / d;
            const uint64_t r = mag - q * d;
            if (r >= d - r) ++q;
            return sum < 0 ? -static_cast<int64_t>(q) : static_cast<int64_t>(q);
        }
        const detail::S128 acc = detail::AddS128(detail::MulS64(n1, d1), detail::MulS64(n2, d2));
        const detail::S128 q = detail::DivRoundS128(acc, detail::MulS64(den, 1));
        return detail::FitsS64(q) ? detail::ToS64(q) : 0;
    }

    int64_t m_num[3] = {0, 0, 0};  // weight numerators (Q32.32 raw); m_num[0] is implied
    int64_t m_den = 1;             // common positive denominator
};

// Closest point of segment w1-w2 to the origin (2.2.1's Solve2 with exact signs).
void Simplex::Solve2() {
    const b2Vec2 w1 = m_v[0].w, w2 = m_v[1].w;
    const b2Vec2 e12 = w2 - w1;
    // w1 region: a2 <= 0.
    const int64_t d12_2 = -b2DotWide(w1, e12).Raw();
    if (d12_2 <= 0) return KeepOnly(0);
    // w2 region: a1 <= 0.
    const int64_t d12_1 = b2DotWide(w2, e12).Raw();
    if (d12_1 <= 0) return KeepOnly(1);
    KeepEdge(0, 1, d12_1, d12_2);
}

// Closest feature of triangle w1-w2-w3 to the origin (2.2.1's Solve3 with exact signs).
void Simplex::Solve3() {
    const b2Vec2 w1 = m_v[0].w, w2 = m_v[1].w, w3 = m_v[2].w;
    const b2Vec2 e12 = w2 - w1, e13 = w3 - w1, e23 = w3 - w2;
    const int64_t d12_1 = b2DotWide(w2, e12).Raw(), d12_2 = -b2DotWide(w1, e12).Raw();
    const int64_t d13_1 = b2DotWide(w3, e13).Raw(), d13_2 = -b2DotWide(w1, e13).Raw();
    const int64_t d23_1 = b2DotWide(w3, e23).Raw(), d23_2 = -b2DotWide(w2, e23).Raw();

    const int64_t n123 = b2CrossWide(e12, e13).Raw();
    const int64_t c1 = b2CrossWide(w2, w3).Raw();
    const int64_t c2 = b2CrossWide(w3, w1).Raw();
    const int64_t c3 = b2CrossWide(w1, w2).Raw();
    // Signs of 2.2.1's d123_k = n123 * c_k.
    const int s123_1 = Sign64(n123) * Sign64(c1);
    const int s123_2 = Sign64(n123) * Sign64(c2);
    const int s123_3 = Sign64(n123) * Sign64(c3);

    if (d12_2 <= 0 && d13_2 <= 0) return KeepOnly(0);                                // w1 region
    if (d12_1 > 0 && d12_2 > 0 && s123_3 <= 0) return KeepEdge(0, 1, d12_1, d12_2);  // e12
    if (d13_1 > 0 && d13_2 > 0 && s123_2 <= 0) return KeepEdge(0, 2, d13_1, d13_2);  // e13
    if (d12_1 <= 0 && d23_2 <= 0) return KeepOnly(1);                                // w2 region
    if (d13_1 <= 0 && d23_1 <= 0) return KeepOnly(2);                                // w3 region
    // e23, stored as (w3, w2) like 2.2.1 (m_v1 = m_v3).
    if (d23_1 > 0 && d23_2 > 0 && s123_1 <= 0) return KeepEdge(2, 1, d23_2, d23_1);
    // Inside the triangle. In exact arithmetic the regions above cover every degenerate
    // (collinear) triangle, so n123 != 0 here; keep a guard anyway rather than divide by 0.
    if (n123 == 0) return KeepOnly(0);
    const int sign = n123 > 0 ? 1 : -1;
    m_num[1] = sign * c2;
    m_num[2] = sign * c3;
    m_den = sign * n123;
    m_count = 3;
}

}  // namespace

void b2Distance(b2DistanceOutput* output, b2SimplexCache* cache, const b2DistanceInput* input) {
    const b2DistanceProxy* proxyA = &input->proxyA;
    const b2DistanceProxy* proxyB = &input->proxyB;
    const b2Transform& transformA = input->transformA;
    const b2Transform& transformB = input->transformB;

    Simplex simplex;
    simplex.ReadCache(cache, proxyA, transformA, proxyB, transformB);

    // The vertices of the last simplex, to detect a repeated support point (cycling).
    int32 saveA[3], saveB[3];
    int32 iter = 0;
    while (iter < b2_maxGjkIterations) {
        const int32 saveCount = simplex.m_count;
        for (int32 i = 0; i < saveCount; ++i) {
            saveA[i] = simplex.m_v[i].indexA;
            saveB[i] = simplex.m_v[i].indexB;
        }
        if (simplex.m_count == 2) simplex.Solve2();
        if (simplex.m_count == 3) simplex.Solve3();
        // Three vertices left: the origin is inside the triangle, the shapes overlap.
        if (simplex.m_count == 3) break;
        // (2.2.1's "ensure progress" test on the closest point is a no-op there: its break is
        // commented out. It is left out here.)

        const b2Vec2 d = simplex.GetSearchDirection();
        // 2.2.1 stops when |d|² < FLT_EPSILON², i.e. |d| < 1.2e-7 m. A Q16.16 direction is
        // exactly zero or at least 1 raw (1.5e-5 m) long, so the test becomes d == 0: the
        // origin is on a vertex of the Minkowski difference (the shapes touch at a vertex).
        if (d.x == Fixed() && d.y == Fixed()) break;

        SimplexVertex* vertex = &simplex.m_v[simplex.m_count];
        const b2Vec2 dir = detail::gjk::ScaleDirection(d);
        Simplex::SetVertex(vertex, proxyA->GetSupport(b2MulT(transformA.q, -dir)),
                           proxyB->GetSupport(b2MulT(transformB.q, dir)), proxyA, transformA, proxyB, transformB);
        ++iter;

        // A repeated support point is the main exit: no further progress is possible.
        bool duplicate = false;
        for (int32 i = 0; i < saveCount; ++i) {
            if (vertex->indexA == saveA[i] && vertex->indexB == saveB[i]) {
                duplicate = true;
                break;
            }
        }
        if (duplicate) break;
        ++simplex.m_count;
        // 2.2.1 leaves the loop here after k_maxIters with the new vertex unsolved and reads
        // stale weights; solve it so that the witness points belong to a consistent simplex.
        if (iter == b2_maxGjkIterations) {
            if (simplex.m_count == 2) simplex.Solve2();
            if (simplex.m_count == 3) simplex.Solve3();
        }
    }

    simplex.GetWitnessPoints(&output->pointA, &output->pointB);
    output->distance = b2Distance(output->pointA, output->pointB);
    output->iterations = iter;
    simplex.WriteCache(cache);

    if (input->useRadii) {
        const Fixed rA = proxyA->m_radius;
        const Fixed rB = proxyB->m_radius;
        // 2.2.1 also asks distance > b2_epsilon; a distance above rA + rB >= 0 is >= 1 raw.
        if (output->distance > rA + rB) {
            // Still separated: move the witness points to the surfaces.
            output->distance -= rA + rB;
            b2Vec2 normal = output->pointB - output->pointA;
            normal.Normalize();
            output->pointA += rA * normal;
            output->pointB -= rB * normal;
        } else {
            // Overlapping rounded shapes: both points at the midpoint, formed from the exact
            // difference so that it is translation-invariant.
            const b2Vec2 half = detail::gjk::HalfOf(output->pointB - output->pointA);
            output->pointA += half;
            output->pointB = output->pointA;
            output->distance = Fixed();
        }
    }
}

}  // namespace lockbox
