// The C API of queries: fixtures in a box, ray casts, and the world's geometry for drawing.
#include <string>

#include "Bindings.h"

using namespace lockbox;
using namespace lockbox::web;

namespace {

class BoxCollector : public b2QueryCallback {
public:
    explicit BoxCollector(std::vector<int32_t>& out) : m_out(out) {}
    bool ReportFixture(b2Fixture* fixture) override {
        m_out.push_back(fixture->GetId());
        return true;
    }

private:
    std::vector<int32_t>& m_out;
};

/// Ray-cast modes: the closest hit, every hit, or any one hit.
enum RayMode : int32_t { e_closest = 0, e_all = 1, e_any = 2 };

class RayCollector : public b2RayCastCallback {
public:
    RayCollector(std::vector<int32_t>& out, int32_t mode) : m_out(out), m_mode(mode) {}
    Fixed ReportFixture(b2Fixture* fixture, const b2Vec2& point, const b2Vec2& normal, Fixed fraction) override {
        const int32_t hit[6] = {fixture->GetId(), point.x.Raw(),  point.y.Raw(),
                                normal.x.Raw(),   normal.y.Raw(), fraction.Raw()};
        if (m_mode == e_closest)
            m_out.assign(hit, hit + 6);
        else
            m_out.insert(m_out.end(), hit, hit + 6);
        // Clip to this hit (closest), go on unclipped (all), or stop (any).
        return m_mode == e_closest ? fraction : m_mode == e_all ? Fixed(1) : Fixed(0);
    }

private:
    std::vector<int32_t>& m_out;
    int32_t m_mode;
};

}  // namespace

/// The ids of the fixtures whose broad-phase boxes overlap [lower, upper] (raw), in the tree's
/// order, into the result buffer; returns the count, or -1 for an inverted box.
LOCKBOX_WEB_API int32_t lb_world_query_aabb(WebWorld* w, int32_t lx, int32_t ly, int32_t ux, int32_t uy) {
    b2AABB box;
    box.lowerBound = b2Vec2(Fx(lx), Fx(ly));
    box.upperBound = b2Vec2(Fx(ux), Fx(uy));
    if (!box.IsValid()) return Fail("queryAABB: lower bound above upper bound");
    w->results.clear();
    BoxCollector collector(w->results);
    w->world->QueryAABB(&collector, box);
    return static_cast<int32_t>(w->results.size());
}

/// Casts the ray p1 -> p2 (raw) in `mode` (0 closest hit, 1 all hits, 2 any hit) and writes
/// the hits into the result buffer, 6 words each: fixture id, point x, y, normal x, y, fraction.
/// Returns the number of hits, or -1 for an unknown mode.
LOCKBOX_WEB_API int32_t lb_world_ray_cast(WebWorld* w, int32_t x1, int32_t y1, int32_t x2, int32_t y2, int32_t mode) {
    if (mode < e_closest || mode > e_any) return Fail("rayCast: unknown mode " + std::to_string(mode));
    w->results.clear();
    RayCollector collector(w->results, mode);
    w->world->RayCast(&collector, b2Vec2(Fx(x1), Fx(y1)), b2Vec2(Fx(x2), Fx(y2)));
    return static_cast<int32_t>(w->results.size() / 6);
}

/// The world's geometry in world coordinates (raw), for drawing, into the result buffer;
/// returns the word count. One record per fixture: shape type (0 circle, 1 edge, 2 polygon,
/// 3 chain), body id, body type, flags (1 awake, 2 sensor, 4 active), point count n, then
/// the n points (x, y); a circle adds its radius and a point on its rim along the body's x
/// axis. Then one record per joint: 10 + joint type, anchor A (x, y), anchor B (x, y).
LOCKBOX_WEB_API int32_t lb_world_draw(WebWorld* w) {
    std::vector<int32_t>& out = w->results;
    out.clear();
    auto put = [&out](const b2Vec2& p) {
        out.push_back(p.x.Raw());
        out.push_back(p.y.Raw());
    };
    for (const b2Body* b = w->world->GetBodyList(); b; b = b->GetNext()) {
        const b2Transform& xf = b->GetTransform();
        for (const b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) {
            const b2Shape* shape = f->GetShape();
            const int32_t flags = (b->IsAwake() ? 1 : 0) | (f->IsSensor() ? 2 : 0) | (b->IsActive() ? 4 : 0);
            out.insert(out.end(),
                       {static_cast<int32_t>(shape->GetType()), b->GetId(), static_cast<int32_t>(b->GetType()), flags});
            switch (shape->GetType()) {
                case b2Shape::e_circle: {
                    const auto* c = static_cast<const b2CircleShape*>(shape);
                    out.push_back(1);
                    put(b2Mul(xf, c->m_p));
                    out.push_back(c->m_radius.Raw());
                    put(b2Mul(xf, c->m_p + b2Vec2(c->m_radius, 0)));
                    break;
                }
                case b2Shape::e_edge: {
                    const auto* e = static_cast<const b2EdgeShape*>(shape);
                    out.push_back(2);
                    put(b2Mul(xf, e->m_vertex1));
                    put(b2Mul(xf, e->m_vertex2));
                    break;
                }
                case b2Shape::e_polygon: {
                    const auto* p = static_cast<const b2PolygonShape*>(shape);
                    out.push_back(p->GetVertexCount());
                    for (int32 i = 0; i < p->GetVertexCount(); ++i) put(b2Mul(xf, p->GetVertex(i)));
                    break;
                }
                case b2Shape::e_chain: {
                    const auto* c = static_cast<const b2ChainShape*>(shape);
                    out.push_back(c->m_count);
                    for (const b2Vec2& v : c->m_vertices) put(b2Mul(xf, v));
                    break;
                }
                default: out.push_back(0); break;
            }
        }
    }
    for (b2Joint* j = w->world->GetJointList(); j; j = j->GetNext()) {
        out.push_back(10 + j->GetType());
        put(j->GetAnchorA());
        put(j->GetAnchorB());
    }
    return static_cast<int32_t>(out.size());
}
