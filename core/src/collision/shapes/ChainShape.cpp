// b2ChainShape: open chains and closed loops of edges with ghost vertices.

#include "lockbox/collision/ChainShape.h"

#include "ShapeInternal.h"

namespace lockbox {

namespace {

// Range and spacing checks shared by CreateChain and CreateLoop; `closed` also checks the
// closing pair last -> first.
b2ShapeError CheckChain(const b2Vec2* vertices, int32 count, bool closed) noexcept {
    for (int32 i = 0; i < count; ++i) {
        if (!shape_detail::InShapeRange(vertices[i])) return b2ShapeError::outOfRange;
    }
    for (int32 i = 0; i + 1 < count; ++i) {
        if (shape_detail::DistanceSquaredRaw(vertices[i], vertices[i + 1]) < shape_detail::kChainWeldSquared) {
            return b2ShapeError::duplicateVertices;
        }
    }
    if (closed &&
        shape_detail::DistanceSquaredRaw(vertices[count - 1], vertices[0]) < shape_detail::kChainWeldSquared) {
        return b2ShapeError::duplicateVertices;
    }
    return b2ShapeError::ok;
}

}  // namespace

b2ShapeError b2ChainShape::CreateLoop(const b2Vec2* vertices, int32 count) {
    if (count < 3) return b2ShapeError::tooFewVertices;
    const b2ShapeError error = CheckChain(vertices, count, true);
    if (error != b2ShapeError::ok) return error;
    // Build the new vertex list first, so an allocation failure leaves the chain unchanged.
    std::vector<b2Vec2> loop(vertices, vertices + count);
    loop.push_back(vertices[0]);
    m_vertices = std::move(loop);
    m_count = count + 1;
    m_prevVertex = m_vertices[static_cast<size_t>(m_count - 2)];
    m_nextVertex = m_vertices[1];
    m_hasPrevVertex = true;
    m_hasNextVertex = true;
    return b2ShapeError::ok;
}

b2ShapeError b2ChainShape::CreateChain(const b2Vec2* vertices, int32 count) {
    if (count < 2) return b2ShapeError::tooFewVertices;
    const b2ShapeError error = CheckChain(vertices, count, false);
    if (error != b2ShapeError::ok) return error;
    std::vector<b2Vec2> chain(vertices, vertices + count);
    m_vertices = std::move(chain);
    m_count = count;
    m_prevVertex.SetZero();
    m_nextVertex.SetZero();
    m_hasPrevVertex = false;
    m_hasNextVertex = false;
    return b2ShapeError::ok;
}

void b2ChainShape::SetPrevVertex(const b2Vec2& prevVertex) noexcept {
    m_prevVertex = prevVertex;
    m_hasPrevVertex = true;
}

void b2ChainShape::SetNextVertex(const b2Vec2& nextVertex) noexcept {
    m_nextVertex = nextVertex;
    m_hasNextVertex = true;
}

std::unique_ptr<b2Shape> b2ChainShape::Clone() const { return std::make_unique<b2ChainShape>(*this); }

int32 b2ChainShape::GetChildCount() const { return m_count > 0 ? m_count - 1 : 0; }

void b2ChainShape::GetChildEdge(b2EdgeShape* edge, int32 index) const {
    const size_t i = static_cast<size_t>(index);
    edge->m_type = e_edge;
    edge->m_radius = m_radius;
    edge->m_vertex1 = m_vertices[i];
    edge->m_vertex2 = m_vertices[i + 1];
    if (index > 0) {
        edge->m_vertex0 = m_vertices[i - 1];
        edge->m_hasVertex0 = true;
    } else {
        edge->m_vertex0 = m_prevVertex;
        edge->m_hasVertex0 = m_hasPrevVertex;
    }
    if (index < m_count - 2) {
        edge->m_vertex3 = m_vertices[i + 2];
        edge->m_hasVertex3 = true;
    } else {
        edge->m_vertex3 = m_nextVertex;
        edge->m_hasVertex3 = m_hasNextVertex;
    }
}

bool b2ChainShape::TestPoint(const b2Transform& transform, const b2Vec2& p) const {
    (void)transform;
    (void)p;
    return false;
}

bool b2ChainShape::RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& xf,
                           int32 childIndex) const {
    const size_t i1 = static_cast<size_t>(childIndex);
    const size_t i2 = i1 + 1 < m_vertices.size() ? i1 + 1 : 0;
    return shape_detail::RayCastSegment(output, input, xf, m_vertices[i1], m_vertices[i2]);
}

void b2ChainShape::ComputeAABB(b2AABB* aabb, const b2Transform& xf, int32 childIndex) const {
    const size_t i1 = static_cast<size_t>(childIndex);
    const size_t i2 = i1 + 1 < m_vertices.size() ? i1 + 1 : 0;
    // 2.2.1 left the skin radius out here; lockbox includes it for every shape.
    *aabb = shape_detail::SegmentAABB(b2Mul(xf, m_vertices[i1]), b2Mul(xf, m_vertices[i2]), m_radius);
}

void b2ChainShape::ComputeMass(b2MassData* massData, Fixed density) const {
    (void)density;
    massData->mass = Wide();
    massData->center.SetZero();
    massData->I = Wide();
}

}  // namespace lockbox
