// The scene list: the library's names plus the scenes registered by files in scenes/.
#include "SceneCatalog.h"

#include <algorithm>
#include <utility>

#include "lockbox/scenes/SceneFileScene.h"

namespace lockbox::testbed {

namespace {

struct Registered {
    std::string name;
    SceneFactory make;
};

// A function-local static, so registrations made while other files' statics are being
// initialised always find the vector constructed.
std::vector<Registered>& Registry() {
    static std::vector<Registered> registry;
    return registry;
}

}  // namespace

SceneRegistration::SceneRegistration(std::string_view name, SceneFactory make) {
    Registry().push_back(Registered{std::string(name), make});
}

const std::vector<CatalogEntry>& SceneCatalog() {
    // Built on first use (after every registration ran) and kept: the list never changes.
    static const std::vector<CatalogEntry> catalog = [] {
        std::vector<CatalogEntry> out;
        for (std::string_view name : scenes::AllSceneNames()) {
            auto scene = scenes::MakeLockboxScene(name);
            if (!scene) continue;  // not available on this engine build
            out.push_back(CatalogEntry{std::string(name), std::string(scene->Info().summary), true});
        }
        std::vector<Registered> own = Registry();
        std::sort(own.begin(), own.end(), [](const Registered& a, const Registered& b) { return a.name < b.name; });
        for (const Registered& r : own) {
            auto scene = r.make();
            out.push_back(CatalogEntry{r.name, std::string(scene->Info().summary), false});
        }
        return out;
    }();
    return catalog;
}

std::unique_ptr<scenes::LockboxScene> MakeCatalogScene(std::string_view name) {
    if (IsSceneFileName(name)) {
        return scenes::SceneFileScene::Open(std::string(name.substr(kSceneFilePrefix.size())), nullptr);
    }
    if (auto scene = scenes::MakeLockboxScene(name)) return scene;
    for (const Registered& r : Registry())
        if (r.name == name) return r.make();
    return nullptr;
}

bool IsLibraryScene(std::string_view name) { return scenes::MakeLockboxScene(name) != nullptr; }

int CatalogIndex(std::string_view name) {
    const auto& catalog = SceneCatalog();
    for (size_t i = 0; i < catalog.size(); ++i)
        if (catalog[i].name == name) return static_cast<int>(i);
    return -1;
}

}  // namespace lockbox::testbed
