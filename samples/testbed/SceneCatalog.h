#pragma once
/// The testbed's list of scenes: every scene of the scene library (scenes), then the
/// testbed-only scenes in samples/testbed/scenes/. A b2dJson scene file opens by the name
/// "file:PATH" (not in the list).
///
/// Adding a testbed-only scene takes one file: write a scenes::LockboxScene subclass in
/// samples/testbed/scenes/<name>.cpp and register it there with a namespace-scope
/// `SceneRegistration` object named after the scene (k<Name>Registration: a unity build
/// compiles the scene files together). The build globs that folder, so nothing else changes.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/scenes/LockboxScenes.h"

namespace lockbox::testbed {

/// Makes a new, unbuilt testbed-only scene.
using SceneFactory = std::unique_ptr<scenes::LockboxScene> (*)();

/// Registers a testbed-only scene when the program starts (define one per scene file).
struct SceneRegistration {
    /// `name` must be unique among all scenes, library ones included.
    SceneRegistration(std::string_view name, SceneFactory make);
};

/// One entry of the scene list.
struct CatalogEntry {
    std::string name;     ///< command-line name
    std::string summary;  ///< one line from the scene's SceneInfo
    bool library = true;  ///< from the scene library (false: testbed-only)
};

/// Every scene: library scenes in library order, then testbed-only scenes by name.
const std::vector<CatalogEntry>& SceneCatalog();

/// A new scene by name from either source, or a scene file ("file:PATH"); nullptr when unknown
/// or when the file does not load.
std::unique_ptr<scenes::LockboxScene> MakeCatalogScene(std::string_view name);

/// The name prefix of scene files.
inline constexpr std::string_view kSceneFilePrefix = "file:";
/// True for "file:PATH".
inline bool IsSceneFileName(std::string_view name) {
    return name.substr(0, kSceneFilePrefix.size()) == kSceneFilePrefix;
}

/// True when `name` is a scene of the scene library (replays of it use "scene:NAME", which
/// lockbox_replay can play too).
bool IsLibraryScene(std::string_view name);

/// Index of a name in SceneCatalog(), or -1.
int CatalogIndex(std::string_view name);

}  // namespace lockbox::testbed
