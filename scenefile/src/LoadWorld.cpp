// ReadScene: the JSON tree, then the world's own fields, then the body, joint and image lists
// (Sections.h), into a SceneDocument. Nothing here touches a world.
#include "Sections.h"
#include "lockbox/scenefile/SceneFile.h"

namespace lockbox::scenefile {

namespace detail {

std::string IndexMessage(int64_t index, int64_t count, const char* plural) {
    return "index " + std::to_string(index) + ", the file has " + std::to_string(count) + " " + plural;
}

namespace {

// Reads an optional array member whose entries are loaded by `load`, refusing more than `max`.
template <class T, class Load>
bool LoadList(SceneReader& r, const JsonNode* n, const Path& path, int32 max, const char* noun, std::vector<T>& out,
              Load&& load) {
    out.clear();
    if (SceneReader::Absent(n)) return true;
    if (!r.ExpectArray(*n, path)) return false;
    if (n->childCount > static_cast<uint32>(max)) {
        return r.Fail(path, SceneError::e_limit,
                      std::to_string(n->childCount) + " " + noun + ", at most " + std::to_string(max));
    }
    out.resize(n->childCount);
    int32 i = 0;
    for (const JsonNode* c = r.Tree().First(*n); c; c = r.Tree().Next(*c), ++i) {
        if (!load(*c, path.Index(i), out[static_cast<size_t>(i)])) return false;
    }
    return true;
}

bool LoadDocument(SceneReader& r, SceneDocument& doc) {
    const JsonNode& root = r.Tree().Root();
    const Path top;
    static constexpr std::array<std::string_view, 13> kNames{
        "gravity",     "allowSleep",     "autoClearForces",    "warmStarting",       "continuousPhysics",
        "subStepping", "stepsPerSecond", "velocityIterations", "positionIterations", "body",
        "joint",       "image",          "customProperties"};
    std::array<const JsonNode*, 13> m;
    if (!r.Members(root, top, kNames, m)) return false;
    WorldDesc& w = doc.world;
    w = WorldDesc();
    if (!r.ReadVec(m[0], top.Member(kNames[0]), w.gravity) || !r.ReadBool(m[1], top.Member(kNames[1]), w.allowSleep) ||
        !r.ReadBool(m[2], top.Member(kNames[2]), w.autoClearForces) ||
        !r.ReadBool(m[3], top.Member(kNames[3]), w.warmStarting) ||
        !r.ReadBool(m[4], top.Member(kNames[4]), w.continuousPhysics) ||
        !r.ReadBool(m[5], top.Member(kNames[5]), w.subStepping) ||
        !r.ReadFixed(m[6], top.Member(kNames[6]), w.step.stepsPerSecond) ||
        !r.NonNegative(w.step.stepsPerSecond, m[6], top.Member(kNames[6])) ||
        !r.ReadInt(m[7], top.Member(kNames[7]), 0, 1000000, w.step.velocityIterations) ||
        !r.ReadInt(m[8], top.Member(kNames[8]), 0, 1000000, w.step.positionIterations) ||
        !r.ReadProperties(m[12], top.Member(kNames[12]), w.info.properties)) {
        return false;
    }

    const SceneLimits& limits = r.Limits();
    int32 fixtureBudget = limits.maxFixtures;
    if (!LoadList(r, m[9], top.Member("body"), limits.maxBodies, "bodies", doc.bodies,
                  [&](const JsonNode& n, const Path& p, BodyDesc& b) { return LoadBody(r, n, p, fixtureBudget, b); })) {
        return false;
    }
    const auto bodyCount = static_cast<int32>(doc.bodies.size());
    const Path jointsPath = top.Member("joint");
    if (!LoadList(r, m[10], jointsPath, limits.maxJoints, "joints", doc.joints,
                  [&](const JsonNode& n, const Path& p, JointDesc& j) { return LoadJoint(r, n, p, bodyCount, j); })) {
        return false;
    }
    if (!CheckGearJoints(r, jointsPath, doc.joints)) return false;
    return LoadList(r, m[11], top.Member("image"), limits.maxImages, "images", doc.images,
                    [&](const JsonNode& n, const Path& p, ImageDesc& im) { return LoadImage(r, n, p, bodyCount, im); });
}

}  // namespace
}  // namespace detail

SceneResult ReadScene(std::string_view json, SceneDocument& out, const SceneLimits& limits) {
    detail::JsonTree tree;
    SceneResult parsed = tree.Parse(json, limits);
    if (!parsed) return parsed;
    detail::SceneReader reader(tree, limits);
    if (!detail::LoadDocument(reader, out)) return reader.TakeError();
    return {};
}

}  // namespace lockbox::scenefile
