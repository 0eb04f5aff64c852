// One "body" entry: b2dJson's fields and defaults (absent allowSleep and active are true,
// absent gravityScale is 1, every other absent value zero or false), the optional mass-data
// override, and the fixtures.
#include "Sections.h"

namespace lockbox::scenefile::detail {

bool LoadBody(SceneReader& r, const JsonNode& n, const Path& path, int32& fixtureBudget, BodyDesc& out) {
    static constexpr std::array<std::string_view, 20> kNames{"name",
                                                             "path",
                                                             "type",
                                                             "position",
                                                             "angle",
                                                             "linearVelocity",
                                                             "angularVelocity",
                                                             "linearDamping",
                                                             "angularDamping",
                                                             "gravityScale",
                                                             "bullet",
                                                             "allowSleep",
                                                             "awake",
                                                             "active",
                                                             "fixedRotation",
                                                             "massData-mass",
                                                             "massData-center",
                                                             "massData-I",
                                                             "fixture",
                                                             "customProperties"};
    std::array<const JsonNode*, 20> m;
    if (!r.Members(n, path, kNames, m)) return false;
    auto at = [&](size_t i) { return path.Member(kNames[i]); };

    b2BodyDef& def = out.def;
    def = b2BodyDef();
    def.allowSleep = true;
    def.awake = false;
    def.active = true;
    def.gravityScale = 1;
    int32 type = 0;
    if (!r.ReadInfo(m[0], m[1], m[19], path, out.info) || !r.ReadInt(m[2], at(2), 0, 2, type) ||
        !r.ReadVec(m[3], at(3), def.position) || !r.ReadFixed(m[4], at(4), def.angle) ||
        !r.ReadVec(m[5], at(5), def.linearVelocity) || !r.ReadFixed(m[6], at(6), def.angularVelocity) ||
        !r.ReadFixed(m[7], at(7), def.linearDamping) || !r.NonNegative(def.linearDamping, m[7], at(7)) ||
        !r.ReadFixed(m[8], at(8), def.angularDamping) || !r.NonNegative(def.angularDamping, m[8], at(8)) ||
        !r.ReadFixed(m[9], at(9), def.gravityScale) || !r.ReadBool(m[10], at(10), def.bullet) ||
        !r.ReadBool(m[11], at(11), def.allowSleep) || !r.ReadBool(m[12], at(12), def.awake) ||
        !r.ReadBool(m[13], at(13), def.active) || !r.ReadBool(m[14], at(14), def.fixedRotation)) {
        return false;
    }
    def.type = static_cast<b2BodyType>(type);
    if (!r.Within(def.angle, kMaxFileAngle, m[4], at(4), "rad", kAngleWhy)) return false;

    out.massData.reset();
    if (!SceneReader::Absent(m[15]) || !SceneReader::Absent(m[16]) || !SceneReader::Absent(m[17])) {
        b2MassData mass;
        if (!r.ReadWide(m[15], at(15), mass.mass) || !r.ReadVec(m[16], at(16), mass.center) ||
            !r.ReadWide(m[17], at(17), mass.I)) {
            return false;
        }
        if (mass.mass < Wide()) return r.Fail(at(15), SceneError::e_range, r.Quote(*m[15]) + " is negative");
        if (!r.WithinVec(mass.center, b2_maxShapeCoordinate, at(16), "m", kLocalWhy)) return false;
        if (mass.I < Wide()) return r.Fail(at(17), SceneError::e_range, r.Quote(*m[17]) + " is negative");
        out.massData = mass;
    }

    out.fixtures.clear();
    const JsonNode* fixtures = m[18];
    if (SceneReader::Absent(fixtures)) return true;
    const Path fp = at(18);
    if (!r.ExpectArray(*fixtures, fp)) return false;
    if (fixtures->childCount > static_cast<uint32>(fixtureBudget)) {
        return r.Fail(fp, SceneError::e_limit,
                      "more than " + std::to_string(r.Limits().maxFixtures) + " fixtures in the file");
    }
    fixtureBudget -= static_cast<int32>(fixtures->childCount);
    out.fixtures.resize(fixtures->childCount);
    int32 i = 0;
    for (const JsonNode* c = r.Tree().First(*fixtures); c; c = r.Tree().Next(*c), ++i) {
        if (!LoadFixture(r, *c, fp.Index(i), out.fixtures[static_cast<size_t>(i)])) return false;
    }
    return true;
}

}  // namespace lockbox::scenefile::detail
