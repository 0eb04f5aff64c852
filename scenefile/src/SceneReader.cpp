// SceneReader: typed values of a JsonTree, with path-naming errors.
#include "SceneReader.h"

#include "lockbox/scenefile/NumberText.h"

namespace lockbox::scenefile::detail {

std::string Path::ToString() const {
    // Collect the frames root-first, then print keys joined by '.' and indices as [i].
    std::vector<const Path*> frames;
    for (const Path* p = this; p; p = p->parent) frames.push_back(p);
    std::string out;
    for (size_t i = frames.size(); i-- > 0;) {
        const Path& f = *frames[i];
        if (f.index >= 0) {
            out += '[';
            out += std::to_string(f.index);
            out += ']';
        } else if (!f.key.empty()) {
            if (!out.empty()) out += '.';
            out += f.key;
        }
    }
    return out;
}

bool SceneReader::Fail(const Path& path, SceneError error, std::string message) {
    if (m_error.ok()) m_error = {error, path.ToString(), std::move(message)};
    return false;
}

std::string SceneReader::Quote(const JsonNode& n) const {
    constexpr size_t kMax = 40;
    std::string_view t = m_tree.Text(n);
    std::string out = n.kind == JsonKind::e_string ? "\"" : "";
    out += t.substr(0, kMax);
    if (t.size() > kMax) out += "...";
    if (n.kind == JsonKind::e_string) out += '"';
    return out;
}

bool SceneReader::TypeError(const JsonNode& n, const Path& path, const char* expected) {
    return Fail(path, SceneError::e_type, std::string("expected ") + expected + ", found " + JsonKindName(n.kind));
}

bool SceneReader::ExpectObject(const JsonNode& n, const Path& path) {
    return n.kind == JsonKind::e_object || TypeError(n, path, "an object");
}

bool SceneReader::ExpectArray(const JsonNode& n, const Path& path) {
    return n.kind == JsonKind::e_array || TypeError(n, path, "an array");
}

bool SceneReader::NumberText(const JsonNode& n, const Path& path, std::string_view& text, bool& hex) {
    if (n.kind == JsonKind::e_number) {
        text = m_tree.Text(n);
        hex = false;
        return true;
    }
    if (n.kind == JsonKind::e_string) {
        text = m_tree.Text(n);
        hex = true;
        return true;
    }
    return TypeError(n, path, "a number (decimal, or a string of 8 hexadecimal digits)");
}

namespace {
const char* RangeText(bool wide) {
    return wide ? "Q32.32 (magnitude at most 2147483647.9999999998)" : "Q16.16 (magnitude at most 32767.99998)";
}

std::string NumberMessage(NumberError e, const std::string& quoted, bool hex, bool wide) {
    switch (e) {
        case NumberError::e_ok: return "";
        case NumberError::e_malformed:
            return hex ? quoted + " is not a number: give decimal text or 8 hexadecimal digits (a binary32's bits)"
                       : quoted + " is not a number";
        case NumberError::e_notFinite: return quoted + " is an infinite or NaN float";
        case NumberError::e_outOfRange: return quoted + " does not fit " + RangeText(wide);
    }
    return quoted + " is not a number";
}
}  // namespace

bool SceneReader::ReadFixed(const JsonNode* n, const Path& path, Fixed& out) {
    if (Absent(n)) return true;
    std::string_view text;
    bool hex = false;
    if (!NumberText(*n, path, text, hex)) return false;
    const NumberError e = hex ? HexFloatToFixed(text, out) : ParseFixed(text, out);
    if (e == NumberError::e_ok) return true;
    return Fail(path, SceneError::e_number, NumberMessage(e, Quote(*n), hex, false));
}

bool SceneReader::ReadWide(const JsonNode* n, const Path& path, Wide& out) {
    if (Absent(n)) return true;
    std::string_view text;
    bool hex = false;
    if (!NumberText(*n, path, text, hex)) return false;
    const NumberError e = hex ? HexFloatToWide(text, out) : ParseWide(text, out);
    if (e == NumberError::e_ok) return true;
    return Fail(path, SceneError::e_number, NumberMessage(e, Quote(*n), hex, true));
}

bool SceneReader::ReadInt(const JsonNode* n, const Path& path, int64_t lo, int64_t hi, int32& out) {
    if (Absent(n)) return true;
    if (n->kind != JsonKind::e_number) return TypeError(*n, path, "an integer");
    const std::string_view t = m_tree.Text(*n);
    size_t i = 0;
    const bool negative = !t.empty() && t[0] == '-';
    if (negative) ++i;
    int64_t v = 0;
    bool ok = i < t.size() && t.size() - i <= 18;
    for (; ok && i < t.size(); ++i) {
        if (t[i] < '0' || t[i] > '9') ok = false;
        v = v * 10 + (t[i] - '0');
    }
    if (!ok) return Fail(path, SceneError::e_number, Quote(*n) + " is not an integer");
    if (negative) v = -v;
    if (v < lo || v > hi) {
        return Fail(path, SceneError::e_range,
                    Quote(*n) + " is out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    }
    out = static_cast<int32>(v);
    return true;
}

bool SceneReader::ReadBool(const JsonNode* n, const Path& path, bool& out) {
    if (Absent(n)) return true;
    if (n->kind == JsonKind::e_true || n->kind == JsonKind::e_false) {
        out = n->kind == JsonKind::e_true;
        return true;
    }
    return TypeError(*n, path, "true or false");
}

bool SceneReader::ReadString(const JsonNode* n, const Path& path, std::string& out) {
    if (Absent(n)) return true;
    if (n->kind != JsonKind::e_string) return TypeError(*n, path, "a string");
    out.assign(m_tree.Text(*n));
    return true;
}

bool SceneReader::ReadVec(const JsonNode* n, const Path& path, b2Vec2& out) {
    if (Absent(n)) return true;
    if (n->kind == JsonKind::e_number) {
        // R.U.B.E. writes the zero vector as the number 0.
        Fixed v;
        if (ParseFixed(m_tree.Text(*n), v) == NumberError::e_ok && v == Fixed()) {
            out.SetZero();
            return true;
        }
        return Fail(
            path, SceneError::e_type,
            "expected a vector ({\"x\": ..., \"y\": ...}, or 0 for the zero vector), found the number " + Quote(*n));
    }
    if (n->kind != JsonKind::e_object) {
        return TypeError(*n, path, "a vector ({\"x\": ..., \"y\": ...}, or 0 for the zero vector)");
    }
    static constexpr std::array<std::string_view, 2> kNames{"x", "y"};
    std::array<const JsonNode*, 2> m;
    if (!Members(*n, path, kNames, m)) return false;
    b2Vec2 v;
    if (!ReadFixed(m[0], path.Member("x"), v.x) || !ReadFixed(m[1], path.Member("y"), v.y)) return false;
    out = v;
    return true;
}

bool SceneReader::ReadVecArray(const JsonNode* n, const Path& path, int32 maxCount, const char* noun,
                               std::vector<b2Vec2>& out) {
    out.clear();
    if (Absent(n)) return true;
    if (n->kind != JsonKind::e_object) {
        return TypeError(*n, path, "a vector array ({\"x\": [...], \"y\": [...]})");
    }
    static constexpr std::array<std::string_view, 2> kNames{"x", "y"};
    std::array<const JsonNode*, 2> m;
    if (!Members(*n, path, kNames, m)) return false;
    const Path px = path.Member("x"), py = path.Member("y");
    if (Absent(m[0]) || Absent(m[1])) {
        return Fail(Absent(m[0]) ? px : py, SceneError::e_type, "a vector array needs both \"x\" and \"y\" arrays");
    }
    if (!ExpectArray(*m[0], px) || !ExpectArray(*m[1], py)) return false;
    if (m[0]->childCount != m[1]->childCount) {
        return Fail(
            path, SceneError::e_type,
            std::to_string(m[0]->childCount) + " x values and " + std::to_string(m[1]->childCount) + " y values");
    }
    if (m[0]->childCount > static_cast<uint32>(maxCount)) {
        return Fail(path, SceneError::e_limit,
                    std::to_string(m[0]->childCount) + " " + noun + ", at most " + std::to_string(maxCount));
    }
    out.resize(m[0]->childCount);
    const JsonNode* x = m_tree.First(*m[0]);
    const JsonNode* y = m_tree.First(*m[1]);
    for (int32 i = 0; x && y; ++i, x = m_tree.Next(*x), y = m_tree.Next(*y)) {
        b2Vec2& v = out[static_cast<size_t>(i)];
        // An element must be present: null is not a coordinate.
        if (Absent(x)) return TypeError(*x, px.Index(i), "a number");
        if (Absent(y)) return TypeError(*y, py.Index(i), "a number");
        if (!ReadFixed(x, px.Index(i), v.x) || !ReadFixed(y, py.Index(i), v.y)) return false;
    }
    return true;
}

bool SceneReader::ReadFixedArray(const JsonNode* n, const Path& path, int32 maxCount, std::vector<Fixed>& out) {
    out.clear();
    if (Absent(n)) return true;
    if (!ExpectArray(*n, path)) return false;
    if (n->childCount > static_cast<uint32>(maxCount)) {
        return Fail(path, SceneError::e_limit,
                    std::to_string(n->childCount) + " numbers, at most " + std::to_string(maxCount));
    }
    out.resize(n->childCount);
    int32 i = 0;
    for (const JsonNode* c = m_tree.First(*n); c; c = m_tree.Next(*c), ++i) {
        if (Absent(c)) return TypeError(*c, path.Index(i), "a number");
        if (!ReadFixed(c, path.Index(i), out[static_cast<size_t>(i)])) return false;
    }
    return true;
}

bool SceneReader::ReadIntArray(const JsonNode* n, const Path& path, int32 maxCount, int64_t lo, int64_t hi,
                               std::vector<int32>& out) {
    out.clear();
    if (Absent(n)) return true;
    if (!ExpectArray(*n, path)) return false;
    if (n->childCount > static_cast<uint32>(maxCount)) {
        return Fail(path, SceneError::e_limit,
                    std::to_string(n->childCount) + " integers, at most " + std::to_string(maxCount));
    }
    out.resize(n->childCount);
    int32 i = 0;
    for (const JsonNode* c = m_tree.First(*n); c; c = m_tree.Next(*c), ++i) {
        if (Absent(c)) return TypeError(*c, path.Index(i), "an integer");
        if (!ReadInt(c, path.Index(i), lo, hi, out[static_cast<size_t>(i)])) return false;
    }
    return true;
}

bool SceneReader::ReadProperties(const JsonNode* n, const Path& path, CustomProperties& out) {
    if (Absent(n)) return true;
    if (!ExpectArray(*n, path)) return false;
    if (n->childCount > static_cast<uint32>(m_limits.maxProperties)) {
        return Fail(
            path, SceneError::e_limit,
            std::to_string(n->childCount) + " custom properties, at most " + std::to_string(m_limits.maxProperties));
    }
    static constexpr std::array<std::string_view, 7> kNames{"name", "int", "float", "string", "vec2", "bool", "color"};
    int32 i = 0;
    for (const JsonNode* c = m_tree.First(*n); c; c = m_tree.Next(*c), ++i) {
        const Path p = path.Index(i);
        std::array<const JsonNode*, 7> m;
        if (!Members(*c, p, kNames, m)) return false;
        std::string name;
        if (!ReadString(m[0], p.Member("name"), name)) return false;
        int found = 0;
        for (size_t k = 1; k < kNames.size(); ++k) {
            if (Absent(m[k])) continue;
            if (found != 0) {
                return Fail(p, SceneError::e_type,
                            std::string("a custom property holds one value, this one has \"") +
                                std::string(kNames[static_cast<size_t>(found)]) + "\" and \"" + std::string(kNames[k]) +
                                "\"");
            }
            found = static_cast<int>(k);
        }
        const Path pv = found ? p.Member(kNames[static_cast<size_t>(found)]) : p;
        const JsonNode* v = found ? m[static_cast<size_t>(found)] : nullptr;
        switch (found) {
            case 1: {
                int32 value = 0;
                if (!ReadInt(v, pv, INT32_MIN, INT32_MAX, value)) return false;
                out.Set(std::move(name), value);
                break;
            }
            case 2: {
                Fixed value;
                if (!ReadFixed(v, pv, value)) return false;
                out.Set(std::move(name), value);
                break;
            }
            case 3: {
                std::string value;
                if (!ReadString(v, pv, value)) return false;
                out.Set(std::move(name), std::move(value));
                break;
            }
            case 4: {
                b2Vec2 value;
                if (!ReadVec(v, pv, value)) return false;
                out.Set(std::move(name), value);
                break;
            }
            case 5: {
                bool value = false;
                if (!ReadBool(v, pv, value)) return false;
                out.Set(std::move(name), value);
                break;
            }
            case 6: {
                std::vector<int32> rgba;
                if (!ReadIntArray(v, pv, 4, 0, 255, rgba)) return false;
                if (rgba.size() != 4) {
                    return Fail(pv, SceneError::e_type, std::to_string(rgba.size()) + " channels, a colour has 4");
                }
                out.Set(std::move(name), CustomColor{rgba[0], rgba[1], rgba[2], rgba[3]});
                break;
            }
            default:
                return Fail(p, SceneError::e_type,
                            "a custom property needs a value: \"int\", \"float\", \"string\", \"vec2\", \"bool\" or "
                            "\"color\"");
        }
    }
    return true;
}

bool SceneReader::ReadInfo(const JsonNode* name, const JsonNode* objectPath, const JsonNode* properties,
                           const Path& path, ObjectInfo& out) {
    return ReadString(name, path.Member("name"), out.name) && ReadString(objectPath, path.Member("path"), out.path) &&
           ReadProperties(properties, path.Member("customProperties"), out.properties);
}

bool SceneReader::Within(Fixed v, Fixed limit, const JsonNode* n, const Path& path, const char* unit, const char* why) {
    if (v <= limit && v >= -limit) return true;
    return Fail(
        path, SceneError::e_range,
        (n ? Quote(*n) : FormatFixed(v)) + " is beyond +-" + FormatFixed(limit) + " " + unit + " (" + why + ")");
}

bool SceneReader::WithinVec(const b2Vec2& v, Fixed limit, const Path& path, const char* unit, const char* why) {
    if (v.x <= limit && v.x >= -limit && v.y <= limit && v.y >= -limit) return true;
    std::string text(1, '(');
    text += FormatFixed(v.x);
    text += ", ";
    text += FormatFixed(v.y);
    text += ')';
    return Fail(path, SceneError::e_range, text + " is beyond +-" + FormatFixed(limit) + " " + unit + " (" + why + ")");
}

bool SceneReader::NonNegative(Fixed v, const JsonNode* n, const Path& path) {
    if (v >= Fixed()) return true;
    return Fail(path, SceneError::e_range, (n ? Quote(*n) : FormatFixed(v)) + " is negative");
}

}  // namespace lockbox::scenefile::detail
