#pragma once
/// A b2dJson scene file (lockbox/scenefile) as a scene of the library's kind, so the tools that
/// run scenes (the testbed, lockbox_bench, lockbox_replay) run files too. Its name is the
/// file's stem; its step rate and iterations are the file's (R.U.B.E.'s stepsPerSecond,
/// velocityIterations, positionIterations), or 60 Hz, 8 and 3 when it gives none; it runs 600
/// steps by default and has no pre-step action. Build sets the world's switches from the file,
/// so the file, not the run settings, decides them.

#include <memory>
#include <string>
#include <string_view>

#include "lockbox/scenefile/SceneFile.h"
#include "lockbox/scenes/LockboxEngine.h"
#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A scene read from a b2dJson file.
class SceneFileScene : public Scene<LockboxEngine> {
public:
    /// Reads and checks a scene file; nullptr on error (then *error says why).
    static std::unique_ptr<SceneFileScene> Open(const std::string& path, scenefile::SceneResult* error) {
        std::string bytes;
        scenefile::SceneResult r = scenefile::ReadSceneFileBytes(path, bytes);
        if (!r) {
            if (error) *error = std::move(r);
            return nullptr;
        }
        return FromText(StemOf(path), std::move(bytes), error);
    }

    /// The same from a file's text; `name` becomes the scene's name.
    static std::unique_ptr<SceneFileScene> FromText(std::string name, std::string bytes,
                                                    scenefile::SceneResult* error) {
        auto scene = std::unique_ptr<SceneFileScene>(new SceneFileScene(std::move(name), std::move(bytes)));
        scenefile::SceneResult r = scenefile::ReadScene(scene->bytes_, scene->doc_);
        if (r) {
            // The checks that need a world (bounds, the lock) are done once on a scratch world,
            // so that Build cannot fail later.
            b2World scratch(scene->doc_.world.gravity);
            r = scenefile::BuildScene(scene->doc_, scratch);
        }
        if (!r) {
            if (error) *error = std::move(r);
            return nullptr;
        }
        scene->SetInfo();
        return scene;
    }

    const SceneInfo& Info() const override { return info_; }

    /// Loads the file into the engine's world (its gravity, switches, bodies and joints).
    void Build(LockboxEngine& e) override {
        metadata_.Clear();
        (void)scenefile::BuildScene(doc_, e.world(), &metadata_);
    }

    /// The file's text, and its hash (scenefile::SceneFileHash), which a replay carries.
    const std::string& Bytes() const noexcept { return bytes_; }
    uint64 FileHash() const noexcept { return scenefile::SceneFileHash(bytes_); }
    /// Names, properties and images of the last Build.
    const scenefile::SceneMetadata& Metadata() const noexcept { return metadata_; }
    /// The world settings (gravity, switches, step settings) the file gives.
    const scenefile::WorldDesc& FileWorld() const noexcept { return doc_.world; }

    /// "level1" for "maps/level1.json".
    static std::string StemOf(const std::string& path) {
        const size_t slash = path.find_last_of("/\\");
        std::string stem = slash == std::string::npos ? path : path.substr(slash + 1);
        const size_t dot = stem.rfind('.');
        if (dot != std::string::npos && dot > 0) stem.resize(dot);
        return stem;
    }

private:
    SceneFileScene(std::string name, std::string bytes) : name_(std::move(name)), bytes_(std::move(bytes)) {}

    void SetInfo() {
        const scenefile::StepSettings& s = doc_.world.step;
        // Only a whole number of steps per second gives the library's dt = round(65536 / hz).
        const int32 raw = s.stepsPerSecond.Raw();
        const bool whole = raw > 0 && raw % Fixed::kOneRaw == 0 && raw / Fixed::kOneRaw <= 1000;
        info_.name = name_;
        info_.steps = 600;
        info_.velocityIterations = s.VelocityIterationsOr();
        info_.positionIterations = s.PositionIterationsOr();
        info_.hz = whole ? raw / Fixed::kOneRaw : 60;
        info_.allowSleep = doc_.world.allowSleep;
        info_.summary = "scene file";
    }

    std::string name_;
    std::string bytes_;
    scenefile::SceneDocument doc_;
    scenefile::SceneMetadata metadata_;
    SceneInfo info_;
};

}  // namespace lockbox::scenes
