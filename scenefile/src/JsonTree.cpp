// JsonTree: RapidJSON's SAX reader (in situ, numbers as text, iterative, UTF-8 validated)
// feeding a flat node array, with the size, depth and value-count limits checked on the way.
#include "JsonTree.h"

#include <rapidjson/error/en.h>
#include <rapidjson/reader.h>

namespace lockbox::scenefile::detail {

const char* JsonKindName(JsonKind kind) noexcept {
    switch (kind) {
        case JsonKind::e_null: return "null";
        case JsonKind::e_false:
        case JsonKind::e_true: return "a boolean";
        case JsonKind::e_number: return "a number";
        case JsonKind::e_string: return "a string";
        case JsonKind::e_array: return "an array";
        case JsonKind::e_object: return "an object";
    }
    return "a value";
}

// Deepest nesting the parser is allowed, whatever SceneLimits::maxDepth says: RapidJSON's
// recursive parser (faster than its iterative one) uses a few hundred bytes of stack per level.
constexpr int32 kMaxParseDepth = 256;

// The SAX handler. Containers under construction are on `m_open`, each with its last child so
// far, so appending a child is O(1).
class TreeBuilder : public rapidjson::BaseReaderHandler<rapidjson::UTF8<>, TreeBuilder> {
public:
    TreeBuilder(JsonTree& tree, const SceneLimits& limits) : m_tree(tree), m_limits(limits) {}

    bool Null() { return Add(JsonKind::e_null, nullptr, 0); }
    bool Bool(bool b) { return Add(b ? JsonKind::e_true : JsonKind::e_false, nullptr, 0); }
    bool RawNumber(const char* s, rapidjson::SizeType n, bool) { return Add(JsonKind::e_number, s, n); }
    bool String(const char* s, rapidjson::SizeType n, bool) { return Add(JsonKind::e_string, s, n); }
    bool Key(const char* s, rapidjson::SizeType n, bool) {
        m_keyOffset = Offset(s);
        m_keyLength = n;
        return true;
    }
    bool StartObject() { return Open(JsonKind::e_object); }
    bool EndObject(rapidjson::SizeType) { return Close(); }
    bool StartArray() { return Open(JsonKind::e_array); }
    bool EndArray(rapidjson::SizeType) { return Close(); }

    /// Set when a handler call refused to go on (a limit); empty otherwise.
    const SceneResult& LimitError() const noexcept { return m_limitError; }

private:
    struct Open_ {
        uint32 node;
        uint32 lastChild;
    };

    uint32 Offset(const char* s) const noexcept { return static_cast<uint32>(s - m_tree.m_buffer.data()); }

    bool Add(JsonKind kind, const char* text, rapidjson::SizeType length) {
        auto& nodes = m_tree.m_nodes;
        if (nodes.size() >= m_limits.maxValues) {
            m_limitError = {SceneError::e_limit, "",
                            "more than " + std::to_string(m_limits.maxValues) + " JSON values"};
            return false;
        }
        JsonNode node;
        node.kind = kind;
        if (text) {
            node.textOffset = Offset(text);
            node.textLength = length;
        }
        const auto index = static_cast<uint32>(nodes.size());
        if (!m_open.empty()) {
            Open_& parent = m_open.back();
            JsonNode& p = nodes[parent.node];
            if (p.kind == JsonKind::e_object) {
                node.keyOffset = m_keyOffset;
                node.keyLength = m_keyLength;
            }
            if (parent.lastChild == kNoNode) {
                p.firstChild = index;
            } else {
                nodes[parent.lastChild].nextSibling = index;
            }
            parent.lastChild = index;
            ++p.childCount;
        }
        nodes.push_back(node);
        return true;
    }

    bool Open(JsonKind kind) {
        // The parser recurses once per level before it calls here, so this bound (capped at
        // kMaxParseDepth whatever the limits say) is also its stack depth.
        const int32 depth = m_limits.maxDepth < kMaxParseDepth ? m_limits.maxDepth : kMaxParseDepth;
        if (static_cast<int32>(m_open.size()) >= depth) {
            m_limitError = {SceneError::e_limit, "",
                            "nesting deeper than " + std::to_string(depth) + " arrays and objects"};
            return false;
        }
        if (!Add(kind, nullptr, 0)) return false;
        m_open.push_back({static_cast<uint32>(m_tree.m_nodes.size() - 1), kNoNode});
        return true;
    }

    bool Close() {
        m_open.pop_back();
        return true;
    }

    JsonTree& m_tree;
    const SceneLimits& m_limits;
    std::vector<Open_> m_open;
    uint32 m_keyOffset = 0;
    uint32 m_keyLength = 0;
    SceneResult m_limitError;
};

SceneResult JsonTree::Parse(std::string_view json, const SceneLimits& limits) {
    m_nodes.clear();
    m_buffer.clear();
    if (json.size() > limits.maxFileBytes) {
        return {
            SceneError::e_limit, "",
            "the file has " + std::to_string(json.size()) + " bytes, at most " + std::to_string(limits.maxFileBytes)};
    }
    // Offsets are 32-bit; the size limit keeps every file far below that.
    if (json.size() >= 0xFFFFFFFFu) return {SceneError::e_limit, "", "the file is larger than 4 GiB"};
    // The in-situ parser stops at a NUL byte; one inside the text would hide what follows it.
    if (const size_t nul = json.find('\0'); nul != std::string_view::npos) {
        return {SceneError::e_syntax, "", "not JSON at byte " + std::to_string(nul) + ": a NUL byte"};
    }
    m_buffer.assign(json.data(), json.size());
    // The parser's UTF-8 check reads every byte a lead byte announces (up to three more) before
    // it judges them, so a text that ends inside a character would be read past its end: the
    // padding keeps those reads in the buffer (they see NUL bytes, which no character continues
    // with, and the parse fails there).
    m_buffer.append(3, '\0');
    // A rough reservation (a typical file has one value per 12 to 16 bytes) saves most regrowth.
    const size_t guess = json.size() / 16 + 16;
    m_nodes.reserve(guess < limits.maxValues ? guess : limits.maxValues);

    TreeBuilder builder(*this, limits);
    rapidjson::InsituStringStream stream(m_buffer.data());
    rapidjson::Reader reader;
    constexpr unsigned kFlags =
        rapidjson::kParseInsituFlag | rapidjson::kParseNumbersAsStringsFlag | rapidjson::kParseValidateEncodingFlag;
    const rapidjson::ParseResult ok = reader.Parse<kFlags>(stream, builder);
    if (ok.IsError()) {
        SceneResult error = builder.LimitError();
        if (error.ok()) {
            error = {SceneError::e_syntax, "",
                     std::string("not JSON at byte ") + std::to_string(ok.Offset()) + ": " +
                         rapidjson::GetParseError_En(ok.Code())};
        }
        m_nodes.clear();
        m_buffer.clear();
        return error;
    }
    // In-situ parsing needs a terminated buffer; a NUL inside the text ends it early, which the
    // parser reports as trailing data or a missing value: nothing more to check here.
    return {};
}

}  // namespace lockbox::scenefile::detail
