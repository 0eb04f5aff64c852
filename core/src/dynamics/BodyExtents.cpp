// b2Body extents: the cheap test that decides whether a body needs continuous collision.
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/Body.h"

namespace lockbox {

namespace {
// Half-thickness of a shape: the radius of the largest disc around its centroid that the
// shape contains (a lower bound is enough: the test stays conservative).
Fixed MinExtent(const b2Shape* shape) {
    switch (shape->GetType()) {
        case b2Shape::e_polygon: {
            const auto* poly = static_cast<const b2PolygonShape*>(shape);
            Fixed minExtent = Fixed::FromRaw(Fixed::kMaxRaw);
            for (int32 i = 0; i < poly->m_vertexCount; ++i) {
                const Fixed d = b2Dot(poly->m_normals[i], poly->m_vertices[i] - poly->m_centroid);
                minExtent = b2Min(minExtent, d);
            }
            return minExtent + poly->m_radius;
        }
        default:
            // Circles: the radius. Edges and chains: only their skin radius.
            return shape->m_radius;
    }
}

// Largest distance from a body-frame point to any point of the shape.
Fixed MaxExtent(const b2Shape* shape, const b2Vec2& center) {
    Fixed maxDist;
    auto visit = [&](const b2Vec2& v) { maxDist = b2Max(maxDist, b2Distance(v, center)); };
    switch (shape->GetType()) {
        case b2Shape::e_circle: visit(static_cast<const b2CircleShape*>(shape)->m_p); break;
        case b2Shape::e_polygon: {
            const auto* poly = static_cast<const b2PolygonShape*>(shape);
            for (int32 i = 0; i < poly->m_vertexCount; ++i) visit(poly->m_vertices[i]);
            break;
        }
        case b2Shape::e_edge: {
            const auto* edge = static_cast<const b2EdgeShape*>(shape);
            visit(edge->m_vertex1);
            visit(edge->m_vertex2);
            break;
        }
        case b2Shape::e_chain: {
            const auto* chain = static_cast<const b2ChainShape*>(shape);
            for (int32 i = 0; i < chain->m_count; ++i) visit(chain->m_vertices[static_cast<size_t>(i)]);
            break;
        }
        default: break;
    }
    return maxDist + shape->m_radius;
}
}  // namespace

void b2Body::UpdateExtents() {
    m_minExtent = Fixed::FromRaw(Fixed::kMaxRaw);
    m_maxExtent = Fixed();
    for (const b2Fixture* f = m_fixtureList; f; f = f->GetNext()) {
        m_minExtent = b2Min(m_minExtent, MinExtent(f->GetShape()));
        m_maxExtent = b2Max(m_maxExtent, MaxExtent(f->GetShape(), m_sweep.localCenter));
    }
    if (m_fixtureList == nullptr) m_minExtent = Fixed();
}

Wide b2Body::SweptDistanceBound() const noexcept {
    // Formed in Q32.32 so that a huge body (a long chain) cannot overflow the bound.
    const Wide linear = Wide((m_sweep.c - m_sweep.c0).Length());
    const Wide angular = MulWide(b2Abs(m_sweep.a - m_sweep.a0), m_maxExtent);
    return linear + angular;
}

bool b2Body::IsFastThisStep() const noexcept {
    const Wide motion = SweptDistanceBound();
    // Two thresholds, the smaller wins:
    // - half the thinnest extent (Box2D v3): below it the centre cannot cross a surface in
    //   one step, so skipping continuous collision can never tunnel;
    // - linearSlop (m, raw 328): 2.2.1 raises a TOI event only when the skins come closer
    //   than -(3 - 0.25) linearSlop (target + tolerance), while a resting contact is held
    //   at -linearSlop, so a body moving less than 1.75 linearSlop cannot produce an event
    //   from rest; linearSlop keeps a margin. Skipping such bodies keeps 2.2.1's results
    //   and makes TOI free for resting and slow scenes.
    const Fixed threshold = b2Min(b2_linearSlop, Fixed::FromRaw(m_minExtent.Raw() / 2));
    return motion > Wide(threshold);
}

}  // namespace lockbox
