// The C API of the scene library (the samples module only): list the scenes, build one into
// a world, and step it the way the golden hashes are made (the scene's own pre-step action,
// then a step at 1/hz).
#include <memory>
#include <string>
#include <vector>

#include "Bindings.h"
#include "lockbox/scenes/LockboxScenes.h"

using namespace lockbox;
using namespace lockbox::web;

namespace {

/// A built scene and the world view JavaScript steps and reads.
struct WebScene {
    std::unique_ptr<scenes::LockboxScene> scene;
    scenes::LockboxEngine engine;
    WebWorld view;
    int32_t steps = 0;  ///< steps taken (the next BeforeStep's step number)
};

const std::vector<std::string>& Names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (std::string_view n : scenes::AllSceneNames())
            if (scenes::MakeLockboxScene(n)) out.emplace_back(n);
        return out;
    }();
    return names;
}

}  // namespace

/// Number of scenes lockbox can build.
LOCKBOX_WEB_API int32_t lb_scene_count() { return static_cast<int32_t>(Names().size()); }

/// Name of scene `index` (0 .. count - 1), or "" out of range.
LOCKBOX_WEB_API const char* lb_scene_name(int32_t index) {
    if (index < 0 || index >= lb_scene_count()) return "";
    return Names()[static_cast<size_t>(index)].c_str();
}

/// Builds scene `name` with its default settings into a new world; nullptr (lb_last_error)
/// when unknown. Writes its defaults into out[0..5]: steps, velocity iterations, position
/// iterations, Hz, sleep allowed, heavy.
LOCKBOX_WEB_API WebScene* lb_scene_create(const char* name, int32_t* out) {
    auto scene = scenes::MakeLockboxScene(name);
    if (!scene) {
        Fail(std::string("no scene named '") + name + "'");
        return nullptr;
    }
    auto* s = new WebScene;
    s->scene = std::move(scene);
    const scenes::SceneInfo& info = s->scene->Info();
    scenes::RunSettings settings;
    settings.trackMetrics = false;
    scenes::ConfigureWorld(s->engine, info, settings);
    s->scene->Prepare(scenes::Resolve(info, settings));
    s->scene->Build(s->engine);
    s->view.world = &s->engine.world();
    out[0] = info.steps;
    out[1] = info.velocityIterations;
    out[2] = info.positionIterations;
    out[3] = info.hz;
    out[4] = info.allowSleep ? 1 : 0;
    out[5] = info.heavy ? 1 : 0;
    return s;
}

/// The scene's world, for every lb_world_* and lb_body_* call (no contact events recorded).
LOCKBOX_WEB_API WebWorld* lb_scene_world(WebScene* s) { return &s->view; }

/// The scene's pre-step action for the next step number, then one step at 1/hz (rounded to
/// Q16.16 as the scenes do) with the given iterations. Returns the steps taken so far, or -1.
LOCKBOX_WEB_API int32_t lb_scene_step(WebScene* s, int32_t hz, int32_t velocityIterations, int32_t positionIterations) {
    if (hz < 1 || hz > 65536) return Fail("scene step: Hz outside 1..65536");
    if (velocityIterations < 0 || positionIterations < 0 || velocityIterations > 1000 || positionIterations > 1000)
        return Fail("scene step: iteration counts outside 0..1000");
    s->scene->BeforeStep(s->engine, s->steps);
    s->engine.Step(hz, velocityIterations, positionIterations);
    return ++s->steps;
}

/// Destroys a scene and its world.
LOCKBOX_WEB_API void lb_scene_destroy(WebScene* s) { delete s; }
