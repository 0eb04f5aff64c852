#pragma once
/// @file
/// GJK distance between two convex shapes (Box2D 2.2.1's b2Distance.h) on exact integers.
///
/// The algorithm is 2.2.1's: a simplex of at most three Minkowski-difference vertices, the
/// Voronoi-region solves Solve2/Solve3, the "duplicate support point" exit and 20 iterations
/// at most. Every region test is an exact integer sign (no epsilon); the barycentric weights
/// are never rounded: witness points are formed as one exact quotient per component. Results
/// are translation-invariant: moving both shapes by the same whole number of metres moves the
/// witness points by exactly that amount and leaves distance, iterations and cache unchanged
/// (see docs/collision.md).
///
/// Valid range: the two shapes' vertices in world space must lie within 16383 m of each other
/// (so that every Minkowski difference and edge fits Q16.16).

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

class b2Shape;

/// A convex vertex cloud with a radius: the shape as seen by GJK. It refers to the shape's own
/// vertex array (or to its buffer for a chain's child edge), so the shape must outlive it. It
/// is a temporary of the narrow phase and never part of the world state.
struct LOCKBOX_API b2DistanceProxy {
    /// An empty proxy (no vertices).
    b2DistanceProxy() noexcept = default;
    /// Copies keep pointing at valid data: a proxy that used its own buffer uses the copy's.
    b2DistanceProxy(const b2DistanceProxy& other) noexcept { *this = other; }
    /// See the copy constructor.
    b2DistanceProxy& operator=(const b2DistanceProxy& other) noexcept;

    /// Initialises the proxy from a shape: a circle (1 vertex), a polygon (its vertices), an
    /// edge (2 vertices) or the child edge `index` of a chain (0 <= index < m_count - 1; 2.2.1
    /// also accepts m_count - 1 and wraps to vertex 0). The shape must outlive the proxy.
    void Set(const b2Shape* shape, int32 index);

    /// Initialises the proxy from a vertex cloud (1 to b2_maxPolygonVertices convex,
    /// counter-clockwise vertices, metres) and a radius (metres, >= 0). The array must outlive
    /// the proxy.
    void Set(const b2Vec2* vertices, int32 count, Fixed radius) noexcept;

    /// Index of the vertex furthest along direction d (local frame; any length, only the
    /// direction counts; components up to 16384 m keep the comparison exact for any vertex).
    /// Compared exactly; on a tie the lowest index wins, as in 2.2.1.
    int32 GetSupport(const b2Vec2& d) const noexcept;

    /// The vertex furthest along direction d (see GetSupport).
    const b2Vec2& GetSupportVertex(const b2Vec2& d) const noexcept { return m_vertices[GetSupport(d)]; }

    /// Number of vertices (1 to b2_maxPolygonVertices).
    int32 GetVertexCount() const noexcept { return m_count; }

    /// Vertex `index` in the shape's local frame (metres); 0 <= index < GetVertexCount().
    const b2Vec2& GetVertex(int32 index) const noexcept { return m_vertices[index]; }

    b2Vec2 m_buffer[2];                  ///< storage for a chain's child edge
    const b2Vec2* m_vertices = nullptr;  ///< the vertex array (shape's or m_buffer)
    int32 m_count = 0;                   ///< number of vertices
    Fixed m_radius;                      ///< skin radius, metres
};

/// Warm start for b2Distance: the simplex of the previous call. Set count to 0 before the first
/// call. Plain data, so it may be kept between steps and compared bit for bit.
struct b2SimplexCache {
    /// Size of the cached simplex, used to detect that it has changed too much to be reused:
    /// 0 for one vertex, the segment length (metres, widened exactly from the rounded Q16.16
    /// length) for two vertices, the exact signed doubled triangle area (m²) for three. Wide
    /// (Q32.32) because an area at the contact scale (linearSlop², 1.6 raw in Q16.16) does not
    /// survive Q16.16.
    Wide metric;
    uint16 count = 0;      ///< number of cached vertices, 0 to 3
    uint8 indexA[3] = {};  ///< vertex indices on shape A
    uint8 indexB[3] = {};  ///< vertex indices on shape B
};

/// Input of b2Distance. With useRadii the result is the distance between the rounded shapes
/// (core distance minus both radii, clamped at 0); without, between the core vertex clouds.
struct b2DistanceInput {
    b2DistanceProxy proxyA;  ///< shape A
    b2DistanceProxy proxyB;  ///< shape B
    b2Transform transformA;  ///< world frame of A
    b2Transform transformB;  ///< world frame of B
    bool useRadii = false;   ///< subtract the radii from the distance
};

/// Output of b2Distance.
struct b2DistanceOutput {
    b2Vec2 pointA;         ///< closest point on shape A (world, metres)
    b2Vec2 pointB;         ///< closest point on shape B (world, metres)
    Fixed distance;        ///< distance between them (metres, >= 0; 0 when overlapping)
    int32 iterations = 0;  ///< number of GJK iterations (support-point evaluations), 0 to 20
};

/// Computes the closest points between two convex shapes (circle, polygon, edge, chain child)
/// with GJK. The cache is read as a warm start and rewritten; set cache->count = 0 the first
/// time. Deterministic and exact in its decisions: the result depends only on the input bits.
LOCKBOX_API void b2Distance(b2DistanceOutput* output, b2SimplexCache* cache, const b2DistanceInput* input);

/// The largest number of GJK iterations b2Distance performs (2.2.1's k_maxIters).
inline constexpr int32 b2_maxGjkIterations = 20;

namespace detail::gjk {
/// xf * v rounded on the rotated part alone, then translated exactly. Differs from b2Mul(xf, v)
/// only on a half-ULP tie, and makes GJK and TOI exactly translation-invariant: the rounding
/// never sees the (whole-metre) translation.
constexpr b2Vec2 TransformPoint(const b2Transform& xf, const b2Vec2& v) noexcept { return xf.p + b2Mul(xf.q, v); }

/// A support direction scaled by a power of two (exact up to 1 raw when shrinking) so that its
/// largest component lies in [2^29, 2^30) raw. Only the direction matters to GetSupport; a
/// short direction (a few raw units when shapes nearly touch) would lose its angle when
/// rotated into a shape frame, the scaled one keeps 29 significant bits, and a rotation keeps
/// it below 2^30.5 raw, so dot products with any vertex stay exact in int64.
constexpr b2Vec2 ScaleDirection(const b2Vec2& d) noexcept {
    int64_t x = d.x.Raw(), y = d.y.Raw();
    uint64_t m = AbsU64(x) > AbsU64(y) ? AbsU64(x) : AbsU64(y);
    if (m == 0) return d;
    constexpr uint64_t kLow = uint64_t{1} << 29;
    while (m < kLow) {
        m <<= 1;
        x *= 2;
        y *= 2;
    }
    if (m >= 2 * kLow) {
        // Truncation towards zero keeps the result symmetric under negation.
        x /= 2;
        y /= 2;
    }
    return {Fixed::FromRaw(static_cast<int32_t>(x)), Fixed::FromRaw(static_cast<int32_t>(y))};
}

/// v / 2 per component, rounded to nearest (ties away from zero).
constexpr b2Vec2 HalfOf(const b2Vec2& v) noexcept {
    return {Fixed::FromRaw(static_cast<int32_t>(ShiftRound(v.x.Raw(), 1))),
            Fixed::FromRaw(static_cast<int32_t>(ShiftRound(v.y.Raw(), 1)))};
}
}  // namespace detail::gjk

}  // namespace lockbox
