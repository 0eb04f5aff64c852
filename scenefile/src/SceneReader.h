#pragma once
// Typed reading of a JsonTree with errors that name the JSON path: the building blocks of the
// section loaders (LoadWorld.cpp, LoadBodies.cpp, LoadFixtures.cpp, LoadJoints.cpp,
// LoadImages.cpp). Every Read* takes the node of a member (nullptr or JSON null when the
// member is absent: `out` keeps its default, as R.U.B.E. defines absent values) and returns
// false after recording the first error.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "JsonTree.h"
#include "lockbox/fixed/Vec2.h"
#include "lockbox/scenefile/CustomProperties.h"
#include "lockbox/scenefile/SceneDocument.h"
#include "lockbox/scenefile/SceneLimits.h"
#include "lockbox/scenefile/SceneResult.h"

namespace lockbox::scenefile::detail {

/// A JSON path as a chain of frames on the stack ("body" -> [3] -> "angle"); it is formatted
/// only when an error is reported, so reading a valid file builds no strings.
struct Path {
    const Path* parent = nullptr;
    std::string_view key;  ///< member name; empty for an array index
    int32 index = -1;      ///< array index, or -1 for a member

    /// The member `name` of this value.
    Path Member(std::string_view name) const noexcept { return {this, name, -1}; }
    /// The element `i` of this array.
    Path Index(int32 i) const noexcept { return {this, {}, i}; }
    /// "body[3].fixture[1].polygon.vertices"; "" for the document itself.
    std::string ToString() const;
};

/// Reads values of one tree, keeping the first error.
class SceneReader {
public:
    SceneReader(const JsonTree& tree, const SceneLimits& limits) : m_tree(tree), m_limits(limits) {}

    const JsonTree& Tree() const noexcept { return m_tree; }
    const SceneLimits& Limits() const noexcept { return m_limits; }
    /// The first error (ok while none).
    SceneResult TakeError() { return std::move(m_error); }

    /// Records an error at `path` and returns false.
    bool Fail(const Path& path, SceneError error, std::string message);

    /// True for an absent member (nullptr or JSON null).
    static bool Absent(const JsonNode* n) noexcept { return n == nullptr || n->kind == JsonKind::e_null; }

    /// Checks that `n` is an object (or array); fails with a type error otherwise.
    bool ExpectObject(const JsonNode& n, const Path& path);
    bool ExpectArray(const JsonNode& n, const Path& path);

    /// Finds the members of object `n` named in `names` (others are ignored); a name given twice
    /// is an error.
    template <size_t N>
    bool Members(const JsonNode& n, const Path& path, const std::array<std::string_view, N>& names,
                 std::array<const JsonNode*, N>& out) {
        out.fill(nullptr);
        if (!ExpectObject(n, path)) return false;
        for (const JsonNode* c = m_tree.First(n); c; c = m_tree.Next(*c)) {
            const std::string_view key = m_tree.Key(*c);
            for (size_t i = 0; i < N; ++i) {
                if (key != names[i]) continue;
                if (out[i]) return Fail(path.Member(key), SceneError::e_syntax, "the key appears twice");
                out[i] = c;
                break;
            }
        }
        return true;
    }

    /// A number: JSON decimal text, or a string of 8 hex digits (a binary32's bits).
    bool ReadFixed(const JsonNode* n, const Path& path, Fixed& out);
    /// The same into Q32.32 (mass, rotational inertia, the mouse joint's force).
    bool ReadWide(const JsonNode* n, const Path& path, Wide& out);
    /// A JSON integer (no fraction, no exponent) within [lo, hi].
    bool ReadInt(const JsonNode* n, const Path& path, int64_t lo, int64_t hi, int32& out);
    bool ReadBool(const JsonNode* n, const Path& path, bool& out);
    bool ReadString(const JsonNode* n, const Path& path, std::string& out);
    /// A vector: {"x": ..., "y": ...} (an absent coordinate is 0) or the number 0.
    bool ReadVec(const JsonNode* n, const Path& path, b2Vec2& out);
    /// A vector array {"x": [...], "y": [...]} of at most `maxCount` entries; `noun` names
    /// them in the count error ("9 vertices, at most 8" comes from the caller's own check).
    bool ReadVecArray(const JsonNode* n, const Path& path, int32 maxCount, const char* noun, std::vector<b2Vec2>& out);
    /// A plain array of numbers, or of integers within [lo, hi].
    bool ReadFixedArray(const JsonNode* n, const Path& path, int32 maxCount, std::vector<Fixed>& out);
    bool ReadIntArray(const JsonNode* n, const Path& path, int32 maxCount, int64_t lo, int64_t hi,
                      std::vector<int32>& out);
    /// "customProperties": an array of {"name": ..., <type>: value}.
    bool ReadProperties(const JsonNode* n, const Path& path, CustomProperties& out);
    /// A name, a path and custom properties (any of them absent).
    bool ReadInfo(const JsonNode* name, const JsonNode* objectPath, const JsonNode* properties, const Path& path,
                  ObjectInfo& out);
    /// Fails with "<text> is negative" unless v >= 0.
    bool NonNegative(Fixed v, const JsonNode* n, const Path& path);
    /// Fails unless |v| <= limit: "<text> is beyond +-<limit> <unit> (<why>)".
    bool Within(Fixed v, Fixed limit, const JsonNode* n, const Path& path, const char* unit, const char* why);
    /// Fails unless both coordinates are within +-limit.
    bool WithinVec(const b2Vec2& v, Fixed limit, const Path& path, const char* unit, const char* why);

    /// The text of a number or string node, cut to a readable length for messages.
    std::string Quote(const JsonNode& n) const;

private:
    bool TypeError(const JsonNode& n, const Path& path, const char* expected);
    bool NumberText(const JsonNode& n, const Path& path, std::string_view& text, bool& hex);

    const JsonTree& m_tree;
    const SceneLimits& m_limits;
    SceneResult m_error;
};

}  // namespace lockbox::scenefile::detail
