// One "fixture" entry: material and filter (b2dJson's defaults: absent friction is 0, not the
// definition's 0.2), and exactly one shape, built with the engine's own validating setters so
// that a file is refused for the same reasons b2PolygonShape::Set and friends refuse a shape.
#include "Sections.h"
#include "lockbox/scenefile/NumberText.h"

namespace lockbox::scenefile::detail {

namespace {

bool ShapeFail(SceneReader& r, const Path& path, b2ShapeError e) {
    return r.Fail(path, SceneError::e_shape, b2ShapeErrorMessage(e));
}

// Ghost vertices are stored as given; they must lie within the shapes' coordinate range too.
bool GhostInRange(SceneReader& r, const Path& path, const b2Vec2& v) {
    const int32 limit = b2_maxShapeCoordinate.Raw();
    auto in = [&](Fixed c) { return c.Raw() <= limit && c.Raw() >= -limit; };
    if (in(v.x) && in(v.y)) return true;
    return ShapeFail(r, path, b2ShapeError::outOfRange);
}

bool LoadCircle(SceneReader& r, const JsonNode& n, const Path& path, ShapeDesc& out) {
    static constexpr std::array<std::string_view, 2> kNames{"center", "radius"};
    std::array<const JsonNode*, 2> m;
    if (!r.Members(n, path, kNames, m)) return false;
    b2Vec2 center;
    Fixed radius;
    if (!r.ReadVec(m[0], path.Member("center"), center) || !r.ReadFixed(m[1], path.Member("radius"), radius)) {
        return false;
    }
    b2CircleShape circle;
    const b2ShapeError e = circle.Set(center, radius);
    if (e != b2ShapeError::ok) {
        return ShapeFail(r, e == b2ShapeError::nonPositiveRadius ? path.Member("radius") : path, e);
    }
    out = circle;
    return true;
}

bool LoadEdge(SceneReader& r, const JsonNode& n, const Path& path, ShapeDesc& out) {
    static constexpr std::array<std::string_view, 6> kNames{"vertex1",    "vertex2", "hasVertex0",
                                                            "hasVertex3", "vertex0", "vertex3"};
    std::array<const JsonNode*, 6> m;
    if (!r.Members(n, path, kNames, m)) return false;
    b2Vec2 v[4];
    bool has0 = false, has3 = false;
    if (!r.ReadVec(m[0], path.Member(kNames[0]), v[1]) || !r.ReadVec(m[1], path.Member(kNames[1]), v[2]) ||
        !r.ReadBool(m[2], path.Member(kNames[2]), has0) || !r.ReadBool(m[3], path.Member(kNames[3]), has3) ||
        !r.ReadVec(m[4], path.Member(kNames[4]), v[0]) || !r.ReadVec(m[5], path.Member(kNames[5]), v[3])) {
        return false;
    }
    b2EdgeShape edge;
    const b2ShapeError e = edge.Set(v[1], v[2]);
    if (e != b2ShapeError::ok) return ShapeFail(r, path, e);
    // As b2dJson: a ghost vertex counts only with its flag.
    if (has0) {
        if (!GhostInRange(r, path.Member("vertex0"), v[0])) return false;
        edge.m_vertex0 = v[0];
        edge.m_hasVertex0 = true;
    }
    if (has3) {
        if (!GhostInRange(r, path.Member("vertex3"), v[3])) return false;
        edge.m_vertex3 = v[3];
        edge.m_hasVertex3 = true;
    }
    out = edge;
    return true;
}

// "chain" (an open chain, or a loop written with its first vertex repeated and its ghost
// vertices, as b2dJson writes one) and the older "loop" (closed by the loader).
bool LoadChain(SceneReader& r, const JsonNode& n, const Path& path, bool loop, ShapeDesc& out) {
    static constexpr std::array<std::string_view, 5> kNames{"vertices", "hasPrevVertex", "hasNextVertex", "prevVertex",
                                                            "nextVertex"};
    std::array<const JsonNode*, 5> m;
    if (!r.Members(n, path, kNames, m)) return false;
    const Path vp = path.Member("vertices");
    std::vector<b2Vec2> vertices;
    if (!r.ReadVecArray(m[0], vp, r.Limits().maxChainVertices, "vertices", vertices)) return false;
    b2ChainShape chain;
    const auto count = static_cast<int32>(vertices.size());
    const b2ShapeError e = loop ? chain.CreateLoop(vertices.data(), count) : chain.CreateChain(vertices.data(), count);
    if (e != b2ShapeError::ok) return ShapeFail(r, vp, e);
    if (!loop) {
        bool hasPrev = false, hasNext = false;
        b2Vec2 prev, next;
        if (!r.ReadBool(m[1], path.Member(kNames[1]), hasPrev) || !r.ReadBool(m[2], path.Member(kNames[2]), hasNext) ||
            !r.ReadVec(m[3], path.Member(kNames[3]), prev) || !r.ReadVec(m[4], path.Member(kNames[4]), next)) {
            return false;
        }
        if (hasPrev) {
            if (!GhostInRange(r, path.Member(kNames[3]), prev)) return false;
            chain.SetPrevVertex(prev);
        }
        if (hasNext) {
            if (!GhostInRange(r, path.Member(kNames[4]), next)) return false;
            chain.SetNextVertex(next);
        }
    }
    out = std::move(chain);
    return true;
}

// How far a polygon's stored normals and centroid may be from those b2PolygonShape::Set
// computes from its vertices (1/64 in each coordinate). A box made by SetAsBox with an angle
// rotates its normals instead of deriving them from the rounded vertices, which can differ by
// up to about 400 raw units (an edge of the 164-unit weld distance, half a unit off at each
// end); lockbox writes such a polygon's own normals and centroid so that it loads back exactly.
constexpr int32 kDerivedTolerance = Fixed::kOneRaw / 64;

bool Near(const b2Vec2& a, const b2Vec2& b) {
    const int64_t dx = int64_t{a.x.Raw()} - b.x.Raw(), dy = int64_t{a.y.Raw()} - b.y.Raw();
    return dx <= kDerivedTolerance && dx >= -kDerivedTolerance && dy <= kDerivedTolerance && dy >= -kDerivedTolerance;
}

std::string VecText(const b2Vec2& v) {
    std::string s(1, '(');
    s += FormatFixed(v.x);
    s += ", ";
    s += FormatFixed(v.y);
    s += ')';
    return s;
}

bool LoadPolygon(SceneReader& r, const JsonNode& n, const Path& path, ShapeDesc& out) {
    static constexpr std::array<std::string_view, 3> kNames{"vertices", "normals", "centroid"};
    std::array<const JsonNode*, 3> m;
    if (!r.Members(n, path, kNames, m)) return false;
    const Path vp = path.Member("vertices");
    std::vector<b2Vec2> vertices;
    if (!r.ReadVecArray(m[0], vp, r.Limits().maxChainVertices, "vertices", vertices)) return false;
    const auto count = static_cast<int32>(vertices.size());
    if (count > b2_maxPolygonVertices) {
        return r.Fail(vp, SceneError::e_shape,
                      std::to_string(count) + " vertices, at most " + std::to_string(b2_maxPolygonVertices));
    }
    if (count == 2) {
        // b2dJson turns a two-vertex polygon into an edge.
        b2EdgeShape edge;
        const b2ShapeError e = edge.Set(vertices[0], vertices[1]);
        if (e != b2ShapeError::ok) return ShapeFail(r, vp, e);
        out = edge;
        return true;
    }
    b2PolygonShape polygon;
    const b2ShapeError e = polygon.Set(vertices.data(), count);
    if (e != b2ShapeError::ok) return ShapeFail(r, vp, e);
    // lockbox's own optional fields (other loaders ignore them): the normals and centroid the
    // polygon had, when they differ slightly from what Set derives.
    if (!SceneReader::Absent(m[1])) {
        const Path np = path.Member("normals");
        std::vector<b2Vec2> normals;
        if (!r.ReadVecArray(m[1], np, b2_maxPolygonVertices, "normals", normals)) return false;
        if (static_cast<int32>(normals.size()) != count) {
            return r.Fail(np, SceneError::e_shape,
                          std::to_string(normals.size()) + " normals for " + std::to_string(count) + " vertices");
        }
        for (int32 i = 0; i < count; ++i) {
            if (!Near(normals[static_cast<size_t>(i)], polygon.m_normals[i])) {
                return r.Fail(np.Index(i), SceneError::e_shape,
                              VecText(normals[static_cast<size_t>(i)]) + " is more than 1/64 from the normal " +
                                  VecText(polygon.m_normals[i]) + " of the edge");
            }
        }
        for (int32 i = 0; i < count; ++i) polygon.m_normals[i] = normals[static_cast<size_t>(i)];
    }
    if (!SceneReader::Absent(m[2])) {
        const Path cp = path.Member("centroid");
        b2Vec2 centroid;
        if (!r.ReadVec(m[2], cp, centroid)) return false;
        if (!Near(centroid, polygon.m_centroid)) {
            return r.Fail(cp, SceneError::e_shape,
                          VecText(centroid) + " is more than 1/64 m from the centroid " + VecText(polygon.m_centroid) +
                              " of the vertices");
        }
        polygon.m_centroid = centroid;
    }
    out = polygon;
    return true;
}

}  // namespace

bool LoadFixture(SceneReader& r, const JsonNode& n, const Path& path, FixtureDesc& out) {
    static constexpr std::array<std::string_view, 15> kNames{"name",
                                                             "path",
                                                             "friction",
                                                             "restitution",
                                                             "density",
                                                             "sensor",
                                                             "filter-categoryBits",
                                                             "filter-maskBits",
                                                             "filter-groupIndex",
                                                             "circle",
                                                             "edge",
                                                             "chain",
                                                             "loop",
                                                             "polygon",
                                                             "customProperties"};
    std::array<const JsonNode*, 15> m;
    if (!r.Members(n, path, kNames, m)) return false;
    auto at = [&](size_t i) { return path.Member(kNames[i]); };

    b2FixtureDef& def = out.def;
    def = b2FixtureDef();
    def.friction = Fixed();
    int32 category = 0x0001, mask = 0xFFFF, group = 0;
    if (!r.ReadInfo(m[0], m[1], m[14], path, out.info) || !r.ReadFixed(m[2], at(2), def.friction) ||
        !r.NonNegative(def.friction, m[2], at(2)) || !r.ReadFixed(m[3], at(3), def.restitution) ||
        !r.NonNegative(def.restitution, m[3], at(3)) || !r.ReadFixed(m[4], at(4), def.density) ||
        !r.NonNegative(def.density, m[4], at(4)) || !r.ReadBool(m[5], at(5), def.isSensor) ||
        !r.ReadInt(m[6], at(6), 0, 0xFFFF, category) || !r.ReadInt(m[7], at(7), 0, 0xFFFF, mask) ||
        !r.ReadInt(m[8], at(8), -32768, 32767, group)) {
        return false;
    }
    def.filter.categoryBits = static_cast<uint16>(category);
    def.filter.maskBits = static_cast<uint16>(mask);
    def.filter.groupIndex = static_cast<int16>(group);

    size_t shape = 0;
    for (size_t i = 9; i <= 13; ++i) {
        if (SceneReader::Absent(m[i])) continue;
        if (shape != 0) {
            return r.Fail(path, SceneError::e_type,
                          "a fixture has one shape, this one has \"" + std::string(kNames[shape]) + "\" and \"" +
                              std::string(kNames[i]) + "\"");
        }
        shape = i;
    }
    switch (shape) {
        case 9: return LoadCircle(r, *m[9], at(9), out.shape);
        case 10: return LoadEdge(r, *m[10], at(10), out.shape);
        case 11: return LoadChain(r, *m[11], at(11), false, out.shape);
        case 12: return LoadChain(r, *m[12], at(12), true, out.shape);
        case 13: return LoadPolygon(r, *m[13], at(13), out.shape);
        default:
            return r.Fail(path, SceneError::e_type,
                          "a fixture needs a shape: \"circle\", \"polygon\", \"edge\" or \"chain\"");
    }
}

}  // namespace lockbox::scenefile::detail
