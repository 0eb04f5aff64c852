#pragma once
/// @file
/// b2ChainShape: a free-form sequence of line segments (an open chain or a closed loop) whose
/// children are b2EdgeShapes carrying their neighbours as ghost vertices. No interior, no mass.

#include <memory>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/collision/EdgeShape.h"

namespace lockbox {

/// A chain of edges. Copyable (the vertices are a std::vector).
class LOCKBOX_API b2ChainShape : public b2Shape {
public:
    /// An empty chain (no children). Create it before use.
    b2ChainShape() noexcept : b2Shape(e_chain, b2_polygonRadius) {}

    /// A closed loop through `count` (>= 3) vertices; the first vertex is repeated at the end
    /// (m_count = count + 1) and the ghost vertices wrap around. Rejects fewer than 3 vertices,
    /// consecutive vertices (including last -> first) closer than b2_chainWeldDistance, and
    /// coordinates beyond b2_maxShapeCoordinate; on error the shape is unchanged.
    b2ShapeError CreateLoop(const b2Vec2* vertices, int32 count);

    /// An open chain through `count` (>= 2) vertices, without ghost end vertices. Same
    /// rejections as CreateLoop (except the closing pair, and 2 vertices suffice).
    b2ShapeError CreateChain(const b2Vec2* vertices, int32 count);

    /// Ghost vertex before the first vertex, for smooth joins with other chains.
    void SetPrevVertex(const b2Vec2& prevVertex) noexcept;
    /// Ghost vertex after the last vertex.
    void SetNextVertex(const b2Vec2& nextVertex) noexcept;

    std::unique_ptr<b2Shape> Clone() const override;
    /// Number of edges: m_count - 1 (0 when empty).
    int32 GetChildCount() const override;
    /// Child edge `index` in [0, GetChildCount()) with its ghost vertices.
    void GetChildEdge(b2EdgeShape* edge, int32 index) const;
    /// Always false: a chain has no interior (the manual).
    bool TestPoint(const b2Transform& transform, const b2Vec2& p) const override;
    /// Ray cast against child edge `childIndex`.
    bool RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& transform,
                 int32 childIndex) const override;
    /// AABB of child edge `childIndex`, including the skin radius.
    void ComputeAABB(b2AABB* aabb, const b2Transform& transform, int32 childIndex) const override;
    /// Zero mass, centre and inertia (as 2.2.1).
    void ComputeMass(b2MassData* massData, Fixed density) const override;

    std::vector<b2Vec2> m_vertices;  ///< body frame, m; a loop repeats vertex 0 at the end
    int32 m_count = 0;               ///< m_vertices.size()
    b2Vec2 m_prevVertex;             ///< ghost before m_vertices[0] (valid when m_hasPrevVertex)
    b2Vec2 m_nextVertex;             ///< ghost after the last vertex (valid when m_hasNextVertex)
    bool m_hasPrevVertex = false;    ///< m_prevVertex is set
    bool m_hasNextVertex = false;    ///< m_nextVertex is set
};

}  // namespace lockbox
