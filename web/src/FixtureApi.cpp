// The C API of fixtures: a fixture definition with one of the four shape types (circle,
// edge, polygon or box, chain or loop), destroy, read and change the material.
#include <string>
#include <vector>

#include "Bindings.h"
#include "DefReader.h"

using namespace lockbox;
using namespace lockbox::web;

namespace {

/// Shape kinds of a fixture definition.
enum ShapeKind : int32_t { e_circle = 0, e_edge = 1, e_polygon = 2, e_box = 3, e_chain = 4 };

/// The shapes a definition may hold (one of them is used).
struct ShapeSlot {
    b2CircleShape circle;
    b2EdgeShape edge;
    b2PolygonShape polygon;
    b2ChainShape chain;
};

std::string ShapeFail(const char* kind, b2ShapeError e) {
    return std::string("createFixture: ") + kind + " refused: " + b2ShapeErrorMessage(e);
}

/// Builds the shape of `kind` from its fields; returns it, or nullptr after Fail.
const b2Shape* ReadShape(int32_t kind, DefReader& r, ShapeSlot& s) {
    switch (kind) {
        case e_circle: {
            // Fields: center, radius.
            b2Vec2 center;
            Fixed radius;
            r.Vec(center);
            if (!r.Fixed(radius)) return Fail("createFixture: a circle needs a radius"), nullptr;
            if (!r.ok()) break;
            if (const b2ShapeError e = s.circle.Set(center, radius); e != b2ShapeError::ok)
                return Fail(ShapeFail("circle", e)), nullptr;
            return &s.circle;
        }
        case e_edge: {
            // Fields: v1, v2, v0 (ghost before v1), v3 (ghost after v2).
            b2Vec2 v1, v2, v0, v3;
            const bool has1 = r.Vec(v1), has2 = r.Vec(v2);
            const bool has0 = r.Vec(v0), has3 = r.Vec(v3);
            if (!r.ok()) break;
            if (!has1 || !has2) return Fail("createFixture: an edge needs v1 and v2"), nullptr;
            if (const b2ShapeError e = s.edge.Set(v1, v2); e != b2ShapeError::ok)
                return Fail(ShapeFail("edge", e)), nullptr;
            s.edge.m_vertex0 = v0;
            s.edge.m_hasVertex0 = has0;
            s.edge.m_vertex3 = v3;
            s.edge.m_hasVertex3 = has3;
            return &s.edge;
        }
        case e_polygon: {
            // Fields: vertices (counter-clockwise, convex), hull (bool: take their convex hull).
            std::vector<b2Vec2> points;
            bool hull = false;
            r.Points(points);
            r.Bool(hull);
            if (!r.ok()) break;
            const auto n = static_cast<int32>(points.size());
            const b2ShapeError e = hull ? s.polygon.SetFromHull(points.data(), n) : s.polygon.Set(points.data(), n);
            if (e != b2ShapeError::ok) return Fail(ShapeFail("polygon", e)), nullptr;
            return &s.polygon;
        }
        case e_box: {
            // Fields: hx, hy, center, angle (with either of the last two: the rotated form).
            Fixed hx, hy, angle;
            b2Vec2 center;
            if (!r.Fixed(hx) || !r.Fixed(hy)) return Fail("createFixture: a box needs hx and hy"), nullptr;
            const bool hasCenter = r.Vec(center), hasAngle = r.Fixed(angle);
            const bool placed = hasCenter || hasAngle;
            if (!r.ok()) break;
            const b2ShapeError e = placed ? s.polygon.SetAsBox(hx, hy, center, angle) : s.polygon.SetAsBox(hx, hy);
            if (e != b2ShapeError::ok) return Fail(ShapeFail("box", e)), nullptr;
            return &s.polygon;
        }
        case e_chain: {
            // Fields: vertices, loop (bool), prevVertex, nextVertex (ghosts of an open chain).
            std::vector<b2Vec2> points;
            bool loop = false;
            b2Vec2 prev, next;
            r.Points(points);
            r.Bool(loop);
            const bool hasPrev = r.Vec(prev), hasNext = r.Vec(next);
            if (!r.ok()) break;
            const auto n = static_cast<int32>(points.size());
            const b2ShapeError e = loop ? s.chain.CreateLoop(points.data(), n) : s.chain.CreateChain(points.data(), n);
            if (e != b2ShapeError::ok) return Fail(ShapeFail(loop ? "loop" : "chain", e)), nullptr;
            if (hasPrev && !loop) s.chain.SetPrevVertex(prev);
            if (hasNext && !loop) s.chain.SetNextVertex(next);
            return &s.chain;
        }
        default: return Fail("createFixture: unknown shape kind " + std::to_string(kind)), nullptr;
    }
    return Fail("createFixture: malformed shape"), nullptr;
}

}  // namespace

/// Creates a fixture on a body. The words are the fixture's fields (friction, restitution,
/// density, isSensor, categoryBits, maskBits, groupIndex, userData), then the shape kind
/// (one word: 0 circle, 1 edge, 2 polygon, 3 box, 4 chain), then the shape's fields, each part
/// with its own presence mask. Returns the fixture id, or -1.
LOCKBOX_WEB_API int32_t lb_fixture_create(WebWorld* w, int32_t bodyId, const int32_t* words, int32_t count) {
    if (w->world->IsLocked()) return Fail("createFixture: the world is locked (called from inside a step)");
    b2Body* body = FindBody(*w, bodyId, "createFixture");
    if (!body) return -1;
    DefReader r(words, count);
    b2FixtureDef def;
    int32_t category = def.filter.categoryBits, mask = def.filter.maskBits, group = def.filter.groupIndex;
    r.Fixed(def.friction);
    r.Fixed(def.restitution);
    r.Fixed(def.density);
    r.Bool(def.isSensor);
    r.Int(category);
    r.Int(mask);
    r.Int(group);
    r.U64(def.userData);
    if (!r.ok() || r.consumed() >= count) return Fail("createFixture: malformed definition");
    if (def.density < Fixed(0)) return Fail("createFixture: negative density");
    if (category < 0 || category > 0xFFFF || mask < 0 || mask > 0xFFFF || group < -32768 || group > 32767)
        return Fail(
            "createFixture: filter bits out of range (categoryBits and maskBits 0..65535, groupIndex -32768..32767)");
    def.filter.categoryBits = static_cast<uint16>(category);
    def.filter.maskBits = static_cast<uint16>(mask);
    def.filter.groupIndex = static_cast<int16>(group);
    const int32_t at = r.consumed();
    const int32_t kind = words[at];
    DefReader shapeReader(words + at + 1, count - at - 1);
    ShapeSlot slot;
    def.shape = ReadShape(kind, shapeReader, slot);
    if (!def.shape) return -1;
    b2Fixture* f = body->CreateFixture(&def);
    return f ? f->GetId() : Fail("createFixture: refused");
}

/// Destroys a fixture (the body's mass is reset); -1 when there is no such fixture.
LOCKBOX_WEB_API int32_t lb_fixture_destroy(WebWorld* w, int32_t id) {
    if (w->world->IsLocked()) return Fail("destroyFixture: the world is locked (called from inside a step)");
    b2Fixture* f = FindFixture(*w, id, "destroyFixture");
    if (!f) return -1;
    f->GetBody()->DestroyFixture(f);
    return 0;
}

/// Writes the fixture's body id, shape type (b2Shape::Type: 0 circle, 1 edge, 2 polygon,
/// 3 chain), isSensor, density, friction, restitution, categoryBits, maskBits, groupIndex and
/// user data (2 words) into out[0..10]; -1 when there is no such fixture.
LOCKBOX_WEB_API int32_t lb_fixture_state(WebWorld* w, int32_t id, int32_t* out) {
    b2Fixture* f = FindFixture(*w, id, "fixture");
    if (!f) return -1;
    out[0] = f->GetBody()->GetId();
    out[1] = f->GetType();
    out[2] = f->IsSensor() ? 1 : 0;
    out[3] = f->GetDensity().Raw();
    out[4] = f->GetFriction().Raw();
    out[5] = f->GetRestitution().Raw();
    out[6] = f->GetFilterData().categoryBits;
    out[7] = f->GetFilterData().maskBits;
    out[8] = f->GetFilterData().groupIndex;
    PutU64(out + 9, f->GetUserData());
    return 0;
}

/// Fixture settings, by kind: 0 density (raw; takes effect with the body's next mass reset),
/// 1 friction, 2 restitution, 3 sensor, 4 filter (value: categoryBits | maskBits << 16,
/// hi: groupIndex), 5 user data (value low half, hi high half). -1 when refused.
LOCKBOX_WEB_API int32_t lb_fixture_set(WebWorld* w, int32_t id, int32_t kind, int32_t value, int32_t hi) {
    b2Fixture* f = FindFixture(*w, id, "fixture");
    if (!f) return -1;
    switch (kind) {
        case 0:
            if (value < 0) return Fail("setDensity: negative density");
            f->SetDensity(Fx(value));
            break;
        case 1: f->SetFriction(Fx(value)); break;
        case 2: f->SetRestitution(Fx(value)); break;
        case 3: f->SetSensor(value != 0); break;
        case 4: {
            if (hi < -32768 || hi > 32767) return Fail("setFilterData: groupIndex out of -32768..32767");
            b2Filter filter;
            filter.categoryBits = static_cast<uint16>(static_cast<uint32_t>(value) & 0xFFFF);
            filter.maskBits = static_cast<uint16>(static_cast<uint32_t>(value) >> 16);
            filter.groupIndex = static_cast<int16>(hi);
            f->SetFilterData(filter);
            break;
        }
        case 5: f->SetUserData(GetU64(value, hi)); break;
        default: return Fail("unknown fixture setting " + std::to_string(kind));
    }
    return 0;
}

/// 1 when the world point (raw) is inside the fixture, 0 when not, -1 when there is no such
/// fixture.
LOCKBOX_WEB_API int32_t lb_fixture_test_point(WebWorld* w, int32_t id, int32_t x, int32_t y) {
    const b2Fixture* f = FindFixture(*w, id, "testPoint");
    if (!f) return -1;
    return f->TestPoint(b2Vec2(Fx(x), Fx(y))) ? 1 : 0;
}
