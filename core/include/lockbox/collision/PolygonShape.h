#pragma once
/// @file
/// b2PolygonShape: a solid convex polygon of 3 to b2_maxPolygonVertices vertices, with a skin
/// of b2_polygonRadius.
///
/// Contract choice: Set() keeps Box2D 2.2.1's contract (the caller gives a convex polygon in
/// counter-clockwise order) and, instead of asserting, REJECTS anything else with a
/// b2ShapeError; it never reorders, welds or drops points. SetFromHull() is the forgiving entry
/// point (as in Box2D 2.3+): it computes the convex hull of unordered points (gift wrapping,
/// ties broken by coordinates, never by address), drops hull vertices that are within the weld
/// distance of their neighbours' chord, then validates like Set().

#include <memory>

#include "lockbox/Export.h"
#include "lockbox/collision/Shape.h"

namespace lockbox {

/// Checks that points[0..count) form a polygon Set() would accept; ok or the first failure, in
/// this order: tooFewVertices, tooManyVertices, outOfRange, duplicateVertices, collinear,
/// clockwise, notConvex, areaTooSmall. All tests are exact integer arithmetic. `points` may be
/// null only when count <= 0.
LOCKBOX_API b2ShapeError b2ValidatePolygon(const b2Vec2* points, int32 count) noexcept;

/// A solid convex polygon.
class LOCKBOX_API b2PolygonShape : public b2Shape {
public:
    /// An empty polygon (m_vertexCount 0) with the polygon skin radius. Set it before use.
    b2PolygonShape() noexcept : b2Shape(e_polygon, b2_polygonRadius) {}

    std::unique_ptr<b2Shape> Clone() const override;
    int32 GetChildCount() const override { return 1; }

    /// Copies a convex, counter-clockwise polygon (3..8 points, body frame, m) and computes
    /// unit edge normals and the centroid. Rejects as b2ValidatePolygon; on error the shape is
    /// unchanged.
    b2ShapeError Set(const b2Vec2* points, int32 count) noexcept;

    /// Convex hull of `count` unordered points (count >= 3; any count, only the hull must have
    /// <= 8 vertices), then Set(). Points inside the hull or within b2_polygonWeldDistance of it
    /// are dropped. On error the shape is unchanged.
    b2ShapeError SetFromHull(const b2Vec2* points, int32 count);

    /// An axis-aligned box centred on the body origin with half-width hx and half-height hy (m).
    /// Rejects hx <= 0 or hy <= 0 (nonPositiveExtent), extents beyond b2_maxShapeCoordinate
    /// (outOfRange), and boxes that b2ValidatePolygon refuses (too thin or too small).
    b2ShapeError SetAsBox(Fixed hx, Fixed hy) noexcept;

    /// A box of half-extents hx, hy centred at `center` (body frame) and rotated by `angle`
    /// (rad) with b2Rot (SinCos); vertices and normals are rotated as in Box2D 2.2.1. Same
    /// rejections as SetAsBox(hx, hy), checked on the rotated vertices.
    b2ShapeError SetAsBox(Fixed hx, Fixed hy, const b2Vec2& center, Fixed angle) noexcept;

    /// Inside when no edge has the point strictly on its outer side (exact dot products).
    bool TestPoint(const b2Transform& transform, const b2Vec2& p) const override;
    /// 2.2.1's clipping against each face, with every fraction kept as an exact ratio and
    /// compared by cross-multiplication. Ignores the skin radius (as 2.2.1). No hit when p1 is
    /// inside.
    bool RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& transform,
                 int32 childIndex) const override;
    void ComputeAABB(b2AABB* aabb, const b2Transform& transform, int32 childIndex) const override;
    /// Triangle-fan area, centroid and inertia summed exactly in 128 bits, then shifted to the
    /// body origin; one rounding for the mass, the centre, and two (2^-48, then 2^-32) for I.
    void ComputeMass(b2MassData* massData, Fixed density) const override;

    /// Number of vertices (0 before a successful Set).
    int32 GetVertexCount() const noexcept { return m_vertexCount; }
    /// Vertex `index` in [0, m_vertexCount).
    const b2Vec2& GetVertex(int32 index) const noexcept { return m_vertices[index]; }

    /// True when the stored vertices form a strictly convex counter-clockwise polygon (every
    /// vertex strictly inside every other edge's half-plane, exact test). False when empty.
    bool Validate() const noexcept;

    b2Vec2 m_centroid;                         ///< area centroid, body frame, m
    b2Vec2 m_vertices[b2_maxPolygonVertices];  ///< counter-clockwise, body frame, m
    b2Vec2 m_normals[b2_maxPolygonVertices];   ///< unit outward normal of edge i -> i+1
    int32 m_vertexCount = 0;                   ///< 3..8 once set
};

}  // namespace lockbox
