// Scene files on disk, and the file hash a replay carries.
#include <xxhash.h>

#include <cstdio>
#include <memory>

#include "lockbox/scenefile/SceneFile.h"

namespace lockbox::scenefile {

namespace {
struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;
}  // namespace

SceneResult ReadSceneFileBytes(const std::string& path, std::string& out, const SceneLimits& limits) {
    out.clear();
    File f(std::fopen(path.c_str(), "rb"));
    if (!f) return {SceneError::e_io, "", "cannot open " + path};
    char chunk[1 << 16];
    size_t n = 0;
    while ((n = std::fread(chunk, 1, sizeof chunk, f.get())) > 0) {
        // Stop reading as soon as the file is too large: a hostile file may be huge.
        if (out.size() + n > limits.maxFileBytes) {
            out.clear();
            return {SceneError::e_limit, "",
                    path + " is larger than " + std::to_string(limits.maxFileBytes) + " bytes"};
        }
        out.append(chunk, n);
    }
    if (std::ferror(f.get())) {
        out.clear();
        return {SceneError::e_io, "", "cannot read " + path};
    }
    return {};
}

SceneResult LoadSceneFile(const std::string& path, b2World& world, SceneMetadata* metadata, const SceneLimits& limits) {
    std::string bytes;
    SceneResult r = ReadSceneFileBytes(path, bytes, limits);
    if (!r) return r;
    return LoadScene(bytes, world, metadata, limits);
}

SceneResult SaveSceneFile(const std::string& path, const b2World& world, const SceneMetadata* metadata) {
    const std::string text = SaveScene(world, metadata);
    File f(std::fopen(path.c_str(), "wb"));
    if (!f) return {SceneError::e_io, "", "cannot open " + path + " for writing"};
    if (std::fwrite(text.data(), 1, text.size(), f.get()) != text.size()) {
        return {SceneError::e_io, "", "cannot write " + path};
    }
    if (std::fclose(f.release()) != 0) return {SceneError::e_io, "", "cannot write " + path};
    return {};
}

uint64 SceneFileHash(std::string_view bytes) noexcept { return XXH3_64bits(bytes.data(), bytes.size()); }

}  // namespace lockbox::scenefile
