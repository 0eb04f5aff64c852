#pragma once
/// @file
/// b2EdgeShape: a line segment with optional ghost (adjacent) vertices for smooth collision
/// along chains. Edges have no interior and no mass.

#include <memory>

#include "lockbox/Export.h"
#include "lockbox/collision/Shape.h"

namespace lockbox {

/// A line segment from m_vertex1 to m_vertex2 with a skin of b2_polygonRadius.
class LOCKBOX_API b2EdgeShape : public b2Shape {
public:
    /// A degenerate edge at the origin without ghost vertices. Set it before use.
    b2EdgeShape() noexcept : b2Shape(e_edge, b2_polygonRadius) {}

    /// Sets an isolated edge (clears the ghost vertices). Rejects end points closer than
    /// b2_chainWeldDistance (duplicateVertices) and coordinates beyond b2_maxShapeCoordinate
    /// (outOfRange); on error the shape is unchanged.
    b2ShapeError Set(const b2Vec2& v1, const b2Vec2& v2) noexcept;

    std::unique_ptr<b2Shape> Clone() const override;
    int32 GetChildCount() const override { return 1; }
    /// Always false: an edge has no interior (the manual).
    bool TestPoint(const b2Transform& transform, const b2Vec2& p) const override;
    /// Two-sided segment test with exact ratios; the normal faces the ray's origin side.
    bool RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& transform,
                 int32 childIndex) const override;
    void ComputeAABB(b2AABB* aabb, const b2Transform& transform, int32 childIndex) const override;
    /// Zero mass and inertia; the centre is the midpoint (as 2.2.1).
    void ComputeMass(b2MassData* massData, Fixed density) const override;

    b2Vec2 m_vertex1;           ///< first end point, body frame, m
    b2Vec2 m_vertex2;           ///< second end point, body frame, m
    b2Vec2 m_vertex0;           ///< ghost vertex before m_vertex1 (valid when m_hasVertex0)
    b2Vec2 m_vertex3;           ///< ghost vertex after m_vertex2 (valid when m_hasVertex3)
    bool m_hasVertex0 = false;  ///< m_vertex0 is set
    bool m_hasVertex3 = false;  ///< m_vertex3 is set
};

}  // namespace lockbox
