// b2EdgeShape: a segment with optional ghost vertices. No interior, no mass.

#include "lockbox/collision/EdgeShape.h"

#include "ShapeInternal.h"

namespace lockbox {

b2ShapeError b2EdgeShape::Set(const b2Vec2& v1, const b2Vec2& v2) noexcept {
    if (!shape_detail::InShapeRange(v1) || !shape_detail::InShapeRange(v2)) return b2ShapeError::outOfRange;
    if (shape_detail::DistanceSquaredRaw(v1, v2) < shape_detail::kChainWeldSquared)
        return b2ShapeError::duplicateVertices;
    m_vertex1 = v1;
    m_vertex2 = v2;
    m_hasVertex0 = false;
    m_hasVertex3 = false;
    return b2ShapeError::ok;
}

std::unique_ptr<b2Shape> b2EdgeShape::Clone() const { return std::make_unique<b2EdgeShape>(*this); }

bool b2EdgeShape::TestPoint(const b2Transform& transform, const b2Vec2& p) const {
    (void)transform;
    (void)p;
    return false;
}

bool b2EdgeShape::RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& xf,
                          int32 childIndex) const {
    (void)childIndex;
    return shape_detail::RayCastSegment(output, input, xf, m_vertex1, m_vertex2);
}

void b2EdgeShape::ComputeAABB(b2AABB* aabb, const b2Transform& xf, int32 childIndex) const {
    (void)childIndex;
    *aabb = shape_detail::SegmentAABB(b2Mul(xf, m_vertex1), b2Mul(xf, m_vertex2), m_radius);
}

void b2EdgeShape::ComputeMass(b2MassData* massData, Fixed density) const {
    (void)density;
    massData->mass = Wide();
    // Midpoint formed exactly and rounded once.
    massData->center.Set(
        Fixed::FromRaw(static_cast<int32_t>(detail::ShiftRound(int64_t{m_vertex1.x.Raw()} + m_vertex2.x.Raw(), 1))),
        Fixed::FromRaw(static_cast<int32_t>(detail::ShiftRound(int64_t{m_vertex1.y.Raw()} + m_vertex2.y.Raw(), 1))));
    massData->I = Wide();
}

}  // namespace lockbox
