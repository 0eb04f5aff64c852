#pragma once
// A compact read-only JSON tree built from RapidJSON's SAX events. Numbers keep their text
// (kParseNumbersAsStringsFlag), so no number ever passes through a double on its way to a
// Fixed; strings and numbers are views into the (in-situ decoded) input buffer. Every value is
// one 32-byte node; children are linked first-child / next-sibling, in document order.
//
// The parse enforces SceneLimits' size, nesting and value-count bounds as it goes, so a
// hostile file is refused before it costs more than those bounds allow. The handler refuses a
// level deeper than the nesting bound (at most 256) before the parser recurses further, so deep
// nesting cannot overflow the stack.

#include <string>
#include <string_view>
#include <vector>

#include "lockbox/common/Settings.h"
#include "lockbox/scenefile/SceneLimits.h"
#include "lockbox/scenefile/SceneResult.h"

namespace lockbox::scenefile::detail {

/// Kinds of JSON value.
enum class JsonKind : uint8 { e_null, e_false, e_true, e_number, e_string, e_array, e_object };

/// "null", "boolean", "number", "string", "array" or "object".
const char* JsonKindName(JsonKind kind) noexcept;

inline constexpr uint32 kNoNode = 0xFFFFFFFFu;

/// One value. `key` is its member name when its parent is an object.
struct JsonNode {
    uint32 keyOffset = 0;
    uint32 keyLength = 0;
    uint32 textOffset = 0;  ///< number text or decoded string
    uint32 textLength = 0;
    uint32 firstChild = kNoNode;
    uint32 nextSibling = kNoNode;
    uint32 childCount = 0;
    JsonKind kind = JsonKind::e_null;
};

/// The parsed document. Owns the buffer the views point into.
class JsonTree {
public:
    /// Parses `json` (copied, then decoded in place). On error returns it (e_syntax with the
    /// byte offset, or e_limit) and leaves the tree empty.
    SceneResult Parse(std::string_view json, const SceneLimits& limits);

    const JsonNode& Root() const noexcept { return m_nodes.front(); }
    const JsonNode& Node(uint32 index) const noexcept { return m_nodes[index]; }
    std::string_view Key(const JsonNode& n) const noexcept { return {m_buffer.data() + n.keyOffset, n.keyLength}; }
    std::string_view Text(const JsonNode& n) const noexcept { return {m_buffer.data() + n.textOffset, n.textLength}; }
    /// The first child of a container, or nullptr.
    const JsonNode* First(const JsonNode& n) const noexcept {
        return n.firstChild == kNoNode ? nullptr : &m_nodes[n.firstChild];
    }
    /// The next sibling, or nullptr.
    const JsonNode* Next(const JsonNode& n) const noexcept {
        return n.nextSibling == kNoNode ? nullptr : &m_nodes[n.nextSibling];
    }

private:
    friend class TreeBuilder;
    std::string m_buffer;
    std::vector<JsonNode> m_nodes;
};

}  // namespace lockbox::scenefile::detail
