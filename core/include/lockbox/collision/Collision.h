#pragma once
/// @file
/// Shared collision types (Box2D's b2Collision.h): contact ids, manifolds, world manifolds,
/// point states, ray-cast input and output, AABBs, and the narrow-phase functions.

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

class b2Shape;
class b2CircleShape;
class b2EdgeShape;
class b2PolygonShape;

/// Null feature index.
inline constexpr uint8 b2_nullFeature = 0xFF;

/// The features that intersect to form a contact point. Plain bytes: the hash and snapshot
/// write the four fields, never the struct.
struct b2ContactFeature {
    /// Kind of a feature: a vertex or a face (edge) of a polygon.
    enum Type : uint8 { e_vertex = 0, e_face = 1 };
    uint8 indexA = 0;  ///< feature index on shape A
    uint8 indexB = 0;  ///< feature index on shape B
    uint8 typeA = 0;   ///< feature type on shape A
    uint8 typeB = 0;   ///< feature type on shape B
};

/// Contact id used to match points between steps for warm starting. Box2D 2.2.1 makes this a
/// union with a `uint32 key`; reading one member of a union through another is undefined in
/// C++, so lockbox keeps the feature and computes the same key on demand.
struct b2ContactID {
    /// The features of the two shapes that produce this point.
    b2ContactFeature cf;
    /// The four feature bytes packed little-end first (the same value on every platform).
    constexpr uint32 Key() const noexcept {
        return uint32{cf.indexA} | (uint32{cf.indexB} << 8) | (uint32{cf.typeA} << 16) | (uint32{cf.typeB} << 24);
    }
};

/// A manifold point: the contact point in the frame that the manifold type names, plus the
/// impulses the solver accumulated for warm starting. Impulses are Wide (Q32.32): an impact
/// impulse of a 1000 kg body at 120 m/s overflows Q16.16 (docs/numerics.md, "Formats").
struct b2ManifoldPoint {
    b2Vec2 localPoint;    ///< usage depends on manifold type
    Wide normalImpulse;   ///< the non-penetration impulse, N*s
    Wide tangentImpulse;  ///< the friction impulse, N*s
    b2ContactID id;       ///< uniquely identifies a contact point between two shapes
};

/// Contact points of two touching convex shapes, in the local frame of one of them so they
/// survive small motions. See the manual's "Contact Manifolds".
struct b2Manifold {
    /// What the manifold's local point and normal mean: e_circles, localPoint is circle A's centre
    /// (normal unused); e_faceA, localPoint and localNormal are on a face of shape A; e_faceB, on a
    /// face of shape B.
    enum Type : uint8 { e_circles, e_faceA, e_faceB };
    /// The contact points (pointCount of them are valid).
    b2ManifoldPoint points[b2_maxManifoldPoints];
    b2Vec2 localNormal;  ///< not used for e_circles
    b2Vec2 localPoint;   ///< usage depends on manifold type
    /// How localPoint and localNormal are read (see Type).
    Type type = e_circles;
    /// Number of valid points, 0 to b2_maxManifoldPoints (2).
    int32 pointCount = 0;
};

/// World-frame contact information computed from a manifold and the two transforms.
struct LOCKBOX_API b2WorldManifold {
    /// Fills normal, points and separations. Radii are the shapes' m_radius.
    void Initialize(const b2Manifold* manifold, const b2Transform& xfA, Fixed radiusA, const b2Transform& xfB,
                    Fixed radiusB);

    b2Vec2 normal;                            ///< world vector pointing from A to B
    b2Vec2 points[b2_maxManifoldPoints];      ///< world contact points (mid-points of overlap)
    Fixed separations[b2_maxManifoldPoints];  ///< negative when overlapping, m (Box2D 2.3+)
};

/// State of a contact point between two manifolds.
enum b2PointState {
    b2_nullState,     ///< point does not exist
    b2_addState,      ///< point was added in the update
    b2_persistState,  ///< point persisted across the update
    b2_removeState    ///< point was removed in the update
};

/// Compares two manifolds to find which points persist, were added or were removed.
LOCKBOX_API void b2GetPointStates(b2PointState state1[b2_maxManifoldPoints], b2PointState state2[b2_maxManifoldPoints],
                                  const b2Manifold* manifold1, const b2Manifold* manifold2);

/// A vertex used to compute contact points by clipping.
struct b2ClipVertex {
    /// The clipped vertex, m.
    b2Vec2 v;
    /// The features it comes from, kept to build the contact id.
    b2ContactID id;
};

/// Ray-cast input: the ray from p1 to p1 + maxFraction * (p2 - p1).
struct b2RayCastInput {
    /// Start and end of the ray (world or shape frame, m).
    ///@{
    b2Vec2 p1, p2;
    ///@}
    /// Fraction of p1->p2 to test, >= 0 (1 tests the whole segment; larger values extend the ray).
    Fixed maxFraction;
};

/// Ray-cast output: hit point p1 + fraction * (p2 - p1) with the surface normal.
struct b2RayCastOutput {
    /// Unit surface normal at the hit point, pointing out of the shape.
    b2Vec2 normal;
    /// Hit position as a fraction of p1->p2, in [0, maxFraction].
    Fixed fraction;
};

/// An axis-aligned bounding box.
struct LOCKBOX_API b2AABB {
    b2Vec2 lowerBound;  ///< lower vertex
    b2Vec2 upperBound;  ///< upper vertex

    /// True when the bounds are sorted (lower <= upper on both axes).
    constexpr bool IsValid() const noexcept { return upperBound.x >= lowerBound.x && upperBound.y >= lowerBound.y; }
    /// Centre, rounded once per axis: (lower + upper) / 2 formed exactly.
    constexpr b2Vec2 GetCenter() const noexcept {
        return {Half(int64_t{lowerBound.x.Raw()} + upperBound.x.Raw()),
                Half(int64_t{lowerBound.y.Raw()} + upperBound.y.Raw())};
    }
    /// Half-widths.
    constexpr b2Vec2 GetExtents() const noexcept {
        return {Half(int64_t{upperBound.x.Raw()} - lowerBound.x.Raw()),
                Half(int64_t{upperBound.y.Raw()} - lowerBound.y.Raw())};
    }
    /// Perimeter 2*(wx + wy) as Q32.32: the tree's cost metric never overflows, whatever the
    /// world size (in Q16.16 it would overflow once wx + wy > 8192 m).
    constexpr Wide GetPerimeterWide() const noexcept {
        const int64_t wx = int64_t{upperBound.x.Raw()} - lowerBound.x.Raw();
        const int64_t wy = int64_t{upperBound.y.Raw()} - lowerBound.y.Raw();
        return Wide::FromRaw((wx + wy) * 2 * 65536);
    }
    /// Perimeter in Q16.16 (saturates beyond 32768 m; prefer GetPerimeterWide).
    constexpr Fixed GetPerimeter() const noexcept { return GetPerimeterWide().ToFixed(); }
    /// Sets this to the union of itself and aabb.
    constexpr void Combine(const b2AABB& aabb) noexcept {
        lowerBound = b2Min(lowerBound, aabb.lowerBound);
        upperBound = b2Max(upperBound, aabb.upperBound);
    }
    /// Sets this to the union of two AABBs.
    constexpr void Combine(const b2AABB& a, const b2AABB& b) noexcept {
        lowerBound = b2Min(a.lowerBound, b.lowerBound);
        upperBound = b2Max(a.upperBound, b.upperBound);
    }
    /// True when this box contains aabb.
    constexpr bool Contains(const b2AABB& aabb) const noexcept {
        return lowerBound.x <= aabb.lowerBound.x && lowerBound.y <= aabb.lowerBound.y &&
               aabb.upperBound.x <= upperBound.x && aabb.upperBound.y <= upperBound.y;
    }
    /// Ray cast against the box (slab method). Returns false when the ray misses or starts
    /// inside.
    bool RayCast(b2RayCastOutput* output, const b2RayCastInput& input) const;

private:
    static constexpr Fixed Half(int64_t twice) noexcept {
        // (a + b) / 2 with ties away from zero, in range by construction for valid boxes.
        return Fixed::FromRaw(detail::NarrowRaw(detail::ShiftRound(twice, 1), "b2AABB", twice, 0));
    }
};

/// True when the two boxes overlap (touching counts).
constexpr bool b2TestOverlap(const b2AABB& a, const b2AABB& b) noexcept {
    if (b.lowerBound.x > a.upperBound.x || b.lowerBound.y > a.upperBound.y) return false;
    if (a.lowerBound.x > b.upperBound.x || a.lowerBound.y > b.upperBound.y) return false;
    return true;
}

/// True when child shapes A and B overlap (GJK distance below the slop-scaled threshold).
LOCKBOX_API bool b2TestOverlap(const b2Shape* shapeA, int32 indexA, const b2Shape* shapeB, int32 indexB,
                               const b2Transform& xfA, const b2Transform& xfB);

/// Manifold of two circles.
LOCKBOX_API void b2CollideCircles(b2Manifold* manifold, const b2CircleShape* circleA, const b2Transform& xfA,
                                  const b2CircleShape* circleB, const b2Transform& xfB);
/// Manifold of a polygon and a circle.
LOCKBOX_API void b2CollidePolygonAndCircle(b2Manifold* manifold, const b2PolygonShape* polygonA, const b2Transform& xfA,
                                           const b2CircleShape* circleB, const b2Transform& xfB);
/// Manifold of two polygons.
LOCKBOX_API void b2CollidePolygons(b2Manifold* manifold, const b2PolygonShape* polygonA, const b2Transform& xfA,
                                   const b2PolygonShape* polygonB, const b2Transform& xfB);
/// Manifold of an edge (with its ghost vertices) and a circle.
LOCKBOX_API void b2CollideEdgeAndCircle(b2Manifold* manifold, const b2EdgeShape* edgeA, const b2Transform& xfA,
                                        const b2CircleShape* circleB, const b2Transform& xfB);
/// Manifold of an edge (with its ghost vertices) and a polygon.
LOCKBOX_API void b2CollideEdgeAndPolygon(b2Manifold* manifold, const b2EdgeShape* edgeA, const b2Transform& xfA,
                                         const b2PolygonShape* polygonB, const b2Transform& xfB);

/// Clips a segment against the half-plane normal . x <= offset; returns the number of output
/// vertices (0, 1 or 2).
LOCKBOX_API int32 b2ClipSegmentToLine(b2ClipVertex vOut[2], const b2ClipVertex vIn[2], const b2Vec2& normal,
                                      Fixed offset, int32 vertexIndexA);

}  // namespace lockbox
