// WriteScene: a document as b2dJson text. Fields follow b2dJson's writer (names, which values
// are left out at their defaults, zero vectors as 0, vertices as {"x": [...], "y": [...]}),
// keys in byte order within each object (as the JSON library R.U.B.E. and b2dJson use writes
// them), numbers as the shortest decimal that reads back to the same value.
#include <algorithm>
#include <memory>

#include "lockbox/scenefile/NumberText.h"
#include "lockbox/scenefile/SceneFile.h"

namespace lockbox::scenefile {

namespace {

// A JSON value to be written: objects are sorted by key when written.
struct Out {
    enum Kind : uint8 { e_number, e_string, e_bool, e_array, e_object } kind = e_object;
    std::string text;  // number text or string
    bool flag = false;
    std::vector<Out> items;  // array elements
    // Object members as parallel lists (a vector of an incomplete type is allowed, a pair of
    // one is not).
    std::vector<std::string> keys;
    std::vector<Out> values;

    static Out Number(std::string t) {
        Out o;
        o.kind = e_number;
        o.text = std::move(t);
        return o;
    }
    static Out Num(Fixed v) { return Number(FormatFixed(v)); }
    static Out Num(Wide v) { return Number(FormatWide(v)); }
    static Out Int(int64_t v) { return Number(std::to_string(v)); }
    static Out Str(std::string s) {
        Out o;
        o.kind = e_string;
        o.text = std::move(s);
        return o;
    }
    static Out Bool(bool b) {
        Out o;
        o.kind = e_bool;
        o.flag = b;
        return o;
    }
    static Out Array() {
        Out o;
        o.kind = e_array;
        return o;
    }
    // b2dJson's vector: the number 0 for the zero vector, else {"x", "y"}.
    static Out Vec(const b2Vec2& v) {
        if (v.x == Fixed() && v.y == Fixed()) return Int(0);
        Out o;
        o.Add("x", Num(v.x));
        o.Add("y", Num(v.y));
        return o;
    }
    static Out VecArray(const std::vector<b2Vec2>& vs) {
        Out o, xs = Array(), ys = Array();
        for (const b2Vec2& v : vs) {
            xs.items.push_back(Num(v.x));
            ys.items.push_back(Num(v.y));
        }
        o.Add("x", std::move(xs));
        o.Add("y", std::move(ys));
        return o;
    }
    void Add(std::string key, Out value) {
        keys.push_back(std::move(key));
        values.push_back(std::move(value));
    }
};

// A string as a JSON string literal: quotes, backslashes and control characters escaped, every
// other byte as it is (strings are UTF-8; those read from a file were checked to be). Written
// here rather than with RapidJSON's writer, whose buffer does arithmetic on a null pointer
// before its first allocation (undefined behaviour, reported by UBSan).
void AppendString(std::string& out, const std::string& text) {
    static constexpr char kHex[] = "0123456789abcdef";
    out += '"';
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            case '\b': out += "\\b"; break;
            case '\f': out += "\\f"; break;
            default:
                if (u < 0x20) {
                    out += "\\u00";
                    out += kHex[u >> 4];
                    out += kHex[u & 15];
                } else {
                    out += c;
                }
        }
    }
    out += '"';
}

bool Scalar(const Out& v) { return v.kind != Out::e_array && v.kind != Out::e_object; }

// Two-space indentation; an array of scalars and an object of scalars stay on one line (vertex
// coordinates read as rows, a vector as {"x": 1, "y": 2}), other arrays and objects put one
// element per line.
void Emit(std::string& out, Out& v, int depth) {
    const std::string indent(static_cast<size_t>(2 * (depth + 1)), ' ');
    const std::string close(static_cast<size_t>(2 * depth), ' ');
    switch (v.kind) {
        case Out::e_number: out += v.text; break;
        case Out::e_string: AppendString(out, v.text); break;
        case Out::e_bool: out += v.flag ? "true" : "false"; break;
        case Out::e_array: {
            if (v.items.empty()) {
                out += "[]";
                break;
            }
            const bool flat = std::all_of(v.items.begin(), v.items.end(), Scalar);
            out += flat ? "[" : "[\n";
            for (size_t i = 0; i < v.items.size(); ++i) {
                if (!flat) out += indent;
                Emit(out, v.items[i], depth + 1);
                if (i + 1 < v.items.size()) out += flat ? ", " : ",\n";
            }
            if (!flat) out += "\n" + close;
            out += ']';
            break;
        }
        case Out::e_object: {
            if (v.keys.empty()) {
                out += "{}";
                break;
            }
            std::vector<size_t> order(v.keys.size());
            for (size_t i = 0; i < order.size(); ++i) order[i] = i;
            std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v.keys[a] < v.keys[b]; });
            // A small all-scalar object ({"x": 1, "y": 2}) stays on one line.
            const bool flat = std::all_of(v.values.begin(), v.values.end(), Scalar);
            out += flat ? "{" : "{\n";
            for (size_t k = 0; k < order.size(); ++k) {
                const size_t i = order[k];
                if (!flat) out += indent;
                AppendString(out, v.keys[i]);
                out += ": ";
                Emit(out, v.values[i], depth + 1);
                if (k + 1 < order.size()) out += flat ? ", " : ",\n";
            }
            if (!flat) out += "\n" + close;
            out += '}';
            break;
        }
    }
}

Out Properties(const CustomProperties& props) {
    Out list = Out::Array();
    for (const CustomProperty& p : props.Items()) {
        Out o;
        o.Add("name", Out::Str(p.name));
        Out value = std::visit(
            [](const auto& v) -> Out {
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, int32>) return Out::Int(v);
                if constexpr (std::is_same_v<T, std::string>) return Out::Str(v);
                if constexpr (std::is_same_v<T, bool>) return Out::Bool(v);
                if constexpr (std::is_same_v<T, Fixed>) return Out::Num(v);
                if constexpr (std::is_same_v<T, b2Vec2>) return Out::Vec(v);
                if constexpr (std::is_same_v<T, CustomColor>) {
                    Out c = Out::Array();
                    for (int32 ch : {v.r, v.g, v.b, v.a}) c.items.push_back(Out::Int(ch));
                    return c;
                }
            },
            p.value);
        o.Add(CustomTypeName(p.value), std::move(value));
        list.items.push_back(std::move(o));
    }
    return list;
}

void AddInfo(Out& o, const ObjectInfo& info) {
    if (!info.name.empty()) o.Add("name", Out::Str(info.name));
    if (!info.path.empty()) o.Add("path", Out::Str(info.path));
    if (!info.properties.Empty()) o.Add("customProperties", Properties(info.properties));
}

Out Shape(const ShapeDesc& shape, std::string& key) {
    Out o;
    if (const auto* c = std::get_if<b2CircleShape>(&shape)) {
        key = "circle";
        o.Add("center", Out::Vec(c->m_p));
        o.Add("radius", Out::Num(c->m_radius));
    } else if (const auto* e = std::get_if<b2EdgeShape>(&shape)) {
        key = "edge";
        o.Add("vertex1", Out::Vec(e->m_vertex1));
        o.Add("vertex2", Out::Vec(e->m_vertex2));
        if (e->m_hasVertex0) {
            o.Add("hasVertex0", Out::Bool(true));
            o.Add("vertex0", Out::Vec(e->m_vertex0));
        }
        if (e->m_hasVertex3) {
            o.Add("hasVertex3", Out::Bool(true));
            o.Add("vertex3", Out::Vec(e->m_vertex3));
        }
    } else if (const auto* p = std::get_if<b2PolygonShape>(&shape)) {
        key = "polygon";
        std::vector<b2Vec2> vs(p->m_vertices, p->m_vertices + p->m_vertexCount);
        o.Add("vertices", Out::VecArray(vs));
        // Normals and centroid that differ from what the vertices give (a box rotated by
        // SetAsBox) are written too, so the polygon loads back exactly; other loaders ignore them.
        b2PolygonShape derived;
        if (derived.Set(vs.data(), p->m_vertexCount) == b2ShapeError::ok) {
            if (!std::equal(p->m_normals, p->m_normals + p->m_vertexCount, derived.m_normals)) {
                o.Add("normals", Out::VecArray(std::vector<b2Vec2>(p->m_normals, p->m_normals + p->m_vertexCount)));
            }
            if (derived.m_centroid != p->m_centroid) o.Add("centroid", Out::Vec(p->m_centroid));
        }
    } else {
        const auto& ch = std::get<b2ChainShape>(shape);
        key = "chain";
        o.Add("vertices", Out::VecArray(ch.m_vertices));
        if (ch.m_hasPrevVertex) {
            o.Add("hasPrevVertex", Out::Bool(true));
            o.Add("prevVertex", Out::Vec(ch.m_prevVertex));
        }
        if (ch.m_hasNextVertex) {
            o.Add("hasNextVertex", Out::Bool(true));
            o.Add("nextVertex", Out::Vec(ch.m_nextVertex));
        }
    }
    return o;
}

Out Fixture(const FixtureDesc& f) {
    Out o;
    AddInfo(o, f.info);
    const b2FixtureDef& d = f.def;
    if (d.restitution != Fixed()) o.Add("restitution", Out::Num(d.restitution));
    if (d.friction != Fixed()) o.Add("friction", Out::Num(d.friction));
    if (d.density != Fixed()) o.Add("density", Out::Num(d.density));
    if (d.isSensor) o.Add("sensor", Out::Bool(true));
    if (d.filter.categoryBits != 0x0001) o.Add("filter-categoryBits", Out::Int(d.filter.categoryBits));
    if (d.filter.maskBits != 0xFFFF) o.Add("filter-maskBits", Out::Int(d.filter.maskBits));
    if (d.filter.groupIndex != 0) o.Add("filter-groupIndex", Out::Int(d.filter.groupIndex));
    std::string key;
    Out shape = Shape(f.shape, key);
    o.Add(key, std::move(shape));
    return o;
}

Out Body(const BodyDesc& b) {
    Out o;
    AddInfo(o, b.info);
    const b2BodyDef& d = b.def;
    o.Add("type", Out::Int(d.type));
    o.Add("position", Out::Vec(d.position));
    o.Add("angle", Out::Num(d.angle));
    o.Add("linearVelocity", Out::Vec(d.linearVelocity));
    o.Add("angularVelocity", Out::Num(d.angularVelocity));
    if (d.linearDamping != Fixed()) o.Add("linearDamping", Out::Num(d.linearDamping));
    if (d.angularDamping != Fixed()) o.Add("angularDamping", Out::Num(d.angularDamping));
    if (d.gravityScale != Fixed(1)) o.Add("gravityScale", Out::Num(d.gravityScale));
    if (d.bullet) o.Add("bullet", Out::Bool(true));
    if (!d.allowSleep) o.Add("allowSleep", Out::Bool(false));
    if (d.awake) o.Add("awake", Out::Bool(true));
    if (!d.active) o.Add("active", Out::Bool(false));
    if (d.fixedRotation) o.Add("fixedRotation", Out::Bool(true));
    if (b.massData) {
        // The mass is written even when zero: its presence is what asks for the override.
        o.Add("massData-mass", Out::Num(b.massData->mass));
        if (b.massData->center.x != Fixed() || b.massData->center.y != Fixed()) {
            o.Add("massData-center", Out::Vec(b.massData->center));
        }
        if (b.massData->I != Wide()) o.Add("massData-I", Out::Num(b.massData->I));
    }
    if (!b.fixtures.empty()) {
        Out list = Out::Array();
        for (const FixtureDesc& f : b.fixtures) list.items.push_back(Fixture(f));
        o.Add("fixture", std::move(list));
    }
    return o;
}

void AddJointFields(Out& o, const JointDesc& j) {
    std::visit(
        [&](const auto& d) {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, b2RevoluteJointDef>) {
                o.Add("anchorA", Out::Vec(d.localAnchorA));
                o.Add("anchorB", Out::Vec(d.localAnchorB));
                o.Add("refAngle", Out::Num(d.referenceAngle));
                o.Add("enableLimit", Out::Bool(d.enableLimit));
                o.Add("lowerLimit", Out::Num(d.lowerAngle));
                o.Add("upperLimit", Out::Num(d.upperAngle));
                o.Add("enableMotor", Out::Bool(d.enableMotor));
                o.Add("motorSpeed", Out::Num(d.motorSpeed));
                o.Add("maxMotorTorque", Out::Num(d.maxMotorTorque));
            } else if constexpr (std::is_same_v<T, b2PrismaticJointDef>) {
                o.Add("anchorA", Out::Vec(d.localAnchorA));
                o.Add("anchorB", Out::Vec(d.localAnchorB));
                o.Add("localAxisA", Out::Vec(d.localAxisA));
                o.Add("refAngle", Out::Num(d.referenceAngle));
                o.Add("enableLimit", Out::Bool(d.enableLimit));
                o.Add("lowerLimit", Out::Num(d.lowerTranslation));
                o.Add("upperLimit", Out::Num(d.upperTranslation));
                o.Add("enableMotor", Out::Bool(d.enableMotor));
                o.Add("maxMotorForce", Out::Num(d.maxMotorForce));
                o.Add("motorSpeed", Out::Num(d.motorSpeed));
            } else if constexpr (std::is_same_v<T, b2DistanceJointDef>) {
                o.Add("anchorA", Out::Vec(d.localAnchorA));
                o.Add("anchorB", Out::Vec(d.localAnchorB));
                o.Add("length", Out::Num(d.length));
                o.Add("frequency", Out::Num(d.frequencyHz));
                o.Add("dampingRatio", Out::Num(d.dampingRatio));
            } else if constexpr (std::is_same_v<T, b2PulleyJointDef>) {
                o.Add("groundAnchorA", Out::Vec(d.groundAnchorA));
                o.Add("groundAnchorB", Out::Vec(d.groundAnchorB));
                o.Add("anchorA", Out::Vec(d.localAnchorA));
                o.Add("anchorB", Out::Vec(d.localAnchorB));
                o.Add("lengthA", Out::Num(d.lengthA));
                o.Add("lengthB", Out::Num(d.lengthB));
                o.Add("ratio", Out::Num(d.ratio));
            } else if constexpr (std::is_same_v<T, b2MouseJointDef>) {
                o.Add("target", Out::Vec(j.mouseTarget));
                o.Add("anchorB", Out::Vec(d.target));
                o.Add("maxForce", Out::Num(d.maxForce));
                o.Add("frequency", Out::Num(d.frequencyHz));
                o.Add("dampingRatio", Out::Num(d.dampingRatio));
            } else if constexpr (std::is_same_v<T, b2GearJointDef>) {
                o.Add("joint1", Out::Int(j.joint1));
                o.Add("joint2", Out::Int(j.joint2));
                o.Add("ratio", Out::Num(d.ratio));
            } else if constexpr (std::is_same_v<T, b2WheelJointDef>) {
                o.Add("anchorA", Out::Vec(d.localAnchorA));
                o.Add("anchorB", Out::Vec(d.localAnchorB));
                o.Add("localAxisA", Out::Vec(d.localAxisA));
                o.Add("enableMotor", Out::Bool(d.enableMotor));
                o.Add("motorSpeed", Out::Num(d.motorSpeed));
                o.Add("maxMotorTorque", Out::Num(d.maxMotorTorque));
                o.Add("springFrequency", Out::Num(d.frequencyHz));
                o.Add("springDampingRatio", Out::Num(d.dampingRatio));
            } else if constexpr (std::is_same_v<T, b2WeldJointDef>) {
                o.Add("anchorA", Out::Vec(d.localAnchorA));
                o.Add("anchorB", Out::Vec(d.localAnchorB));
                o.Add("refAngle", Out::Num(d.referenceAngle));
                o.Add("frequency", Out::Num(d.frequencyHz));
                o.Add("dampingRatio", Out::Num(d.dampingRatio));
            } else if constexpr (std::is_same_v<T, b2FrictionJointDef>) {
                o.Add("anchorA", Out::Vec(d.localAnchorA));
                o.Add("anchorB", Out::Vec(d.localAnchorB));
                o.Add("maxForce", Out::Num(d.maxForce));
                o.Add("maxTorque", Out::Num(d.maxTorque));
            } else {
                o.Add("anchorA", Out::Vec(d.localAnchorA));
                o.Add("anchorB", Out::Vec(d.localAnchorB));
                o.Add("maxLength", Out::Num(d.maxLength));
            }
            if (d.collideConnected) o.Add("collideConnected", Out::Bool(true));
        },
        j.def);
}

Out Joint(const JointDesc& j) {
    Out o;
    AddInfo(o, j.info);
    o.Add("type", Out::Str(JointTypeName(JointDescType(j.def))));
    o.Add("bodyA", Out::Int(j.bodyA));
    o.Add("bodyB", Out::Int(j.bodyB));
    AddJointFields(o, j);
    return o;
}

Out Image(const ImageDesc& im) {
    Out o;
    AddInfo(o, im.info);
    o.Add("body", Out::Int(im.body));
    if (!im.file.empty()) o.Add("file", Out::Str(im.file));
    o.Add("center", Out::Vec(im.center));
    o.Add("angle", Out::Num(im.angle));
    o.Add("scale", Out::Num(im.scale));
    o.Add("aspectScale", Out::Num(im.aspectScale));
    if (im.flip) o.Add("flip", Out::Bool(true));
    o.Add("opacity", Out::Num(im.opacity));
    o.Add("filter", Out::Int(im.filter));
    o.Add("renderOrder", Out::Num(im.renderOrder));
    if (im.colorTint != std::array<int32, 4>{255, 255, 255, 255}) {
        Out tint = Out::Array();
        for (int32 c : im.colorTint) tint.items.push_back(Out::Int(c));
        o.Add("colorTint", std::move(tint));
    }
    if (!im.corners.empty()) o.Add("corners", Out::VecArray(im.corners));
    if (!im.glVertexPointer.empty() || !im.glTexCoordPointer.empty()) {
        Out vp = Out::Array(), tp = Out::Array();
        for (Fixed v : im.glVertexPointer) vp.items.push_back(Out::Num(v));
        for (Fixed v : im.glTexCoordPointer) tp.items.push_back(Out::Num(v));
        o.Add("glVertexPointer", std::move(vp));
        o.Add("glTexCoordPointer", std::move(tp));
    }
    if (!im.glDrawElements.empty()) {
        Out el = Out::Array();
        for (int32 i : im.glDrawElements) el.items.push_back(Out::Int(i));
        o.Add("glDrawElements", std::move(el));
    }
    return o;
}

}  // namespace

std::string WriteScene(const SceneDocument& doc) {
    Out root;
    const WorldDesc& w = doc.world;
    root.Add("gravity", Out::Vec(w.gravity));
    root.Add("allowSleep", Out::Bool(w.allowSleep));
    root.Add("autoClearForces", Out::Bool(w.autoClearForces));
    root.Add("warmStarting", Out::Bool(w.warmStarting));
    root.Add("continuousPhysics", Out::Bool(w.continuousPhysics));
    root.Add("subStepping", Out::Bool(w.subStepping));
    if (w.step.stepsPerSecond != Fixed()) root.Add("stepsPerSecond", Out::Num(w.step.stepsPerSecond));
    if (w.step.velocityIterations != 0) root.Add("velocityIterations", Out::Int(w.step.velocityIterations));
    if (w.step.positionIterations != 0) root.Add("positionIterations", Out::Int(w.step.positionIterations));
    if (!w.info.properties.Empty()) root.Add("customProperties", Properties(w.info.properties));
    if (!doc.bodies.empty()) {
        Out list = Out::Array();
        for (const BodyDesc& b : doc.bodies) list.items.push_back(Body(b));
        root.Add("body", std::move(list));
    }
    if (!doc.joints.empty()) {
        Out list = Out::Array();
        for (const JointDesc& j : doc.joints) list.items.push_back(Joint(j));
        root.Add("joint", std::move(list));
    }
    if (!doc.images.empty()) {
        Out list = Out::Array();
        for (const ImageDesc& im : doc.images) list.items.push_back(Image(im));
        root.Add("image", std::move(list));
    }

    std::string text;
    Emit(text, root, 0);
    text += '\n';
    return text;
}

std::string SaveScene(const b2World& world, const SceneMetadata* metadata) {
    return WriteScene(DescribeWorld(world, metadata));
}

}  // namespace lockbox::scenefile
