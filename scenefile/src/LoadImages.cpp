// One "image" entry: kept as data for the game's renderer (physics ignores images), with
// b2dJson's defaults (absent aspectScale is 1, filter 1 (linear), colour tint opaque white).
#include "Sections.h"

namespace lockbox::scenefile::detail {

bool LoadImage(SceneReader& r, const JsonNode& n, const Path& path, int32 bodyCount, ImageDesc& out) {
    static constexpr std::array<std::string_view, 18> kNames{"body",
                                                             "name",
                                                             "path",
                                                             "file",
                                                             "center",
                                                             "angle",
                                                             "scale",
                                                             "aspectScale",
                                                             "flip",
                                                             "opacity",
                                                             "filter",
                                                             "renderOrder",
                                                             "colorTint",
                                                             "corners",
                                                             "glVertexPointer",
                                                             "glTexCoordPointer",
                                                             "glDrawElements",
                                                             "customProperties"};
    std::array<const JsonNode*, 18> m;
    if (!r.Members(n, path, kNames, m)) return false;
    auto at = [&](size_t i) { return path.Member(kNames[i]); };
    out = ImageDesc();
    std::vector<int32> tint;
    const int32 maxValues = r.Limits().maxImageValues;
    if (!r.ReadInt(m[0], at(0), INT32_MIN, INT32_MAX, out.body) || !r.ReadInfo(m[1], m[2], m[17], path, out.info) ||
        !r.ReadString(m[3], at(3), out.file) || !r.ReadVec(m[4], at(4), out.center) ||
        !r.ReadFixed(m[5], at(5), out.angle) || !r.ReadFixed(m[6], at(6), out.scale) ||
        !r.ReadFixed(m[7], at(7), out.aspectScale) || !r.ReadBool(m[8], at(8), out.flip) ||
        !r.ReadFixed(m[9], at(9), out.opacity) || !r.ReadInt(m[10], at(10), 0, 255, out.filter) ||
        !r.ReadFixed(m[11], at(11), out.renderOrder) || !r.ReadIntArray(m[12], at(12), 4, 0, 255, tint) ||
        !r.ReadVecArray(m[13], at(13), 4, "corners", out.corners) ||
        !r.ReadFixedArray(m[14], at(14), maxValues, out.glVertexPointer) ||
        !r.ReadFixedArray(m[15], at(15), maxValues, out.glTexCoordPointer) ||
        !r.ReadIntArray(m[16], at(16), maxValues, 0, 65535, out.glDrawElements)) {
        return false;
    }
    if (out.body < -1 || out.body >= bodyCount) {
        return r.Fail(at(0), SceneError::e_reference, IndexMessage(out.body, bodyCount, "bodies"));
    }
    if (!SceneReader::Absent(m[12])) {
        if (tint.size() != 4)
            return r.Fail(at(12), SceneError::e_type, std::to_string(tint.size()) + " channels, a tint has 4");
        for (size_t i = 0; i < 4; ++i) out.colorTint[i] = tint[i];
    }
    if (out.glVertexPointer.size() != out.glTexCoordPointer.size()) {
        return r.Fail(at(15), SceneError::e_type,
                      std::to_string(out.glTexCoordPointer.size()) + " texture coordinates for " +
                          std::to_string(out.glVertexPointer.size()) + " vertex coordinates");
    }
    return true;
}

}  // namespace lockbox::scenefile::detail
