#pragma once
/// @file
/// Loading and saving b2dJson world files, the export format of the R.U.B.E. editor
/// (docs/scene-files.md has the fields, the number rules, the error format and the limits).
///
///     lockbox::b2World world(lockbox::b2Vec2(0, -10));
///     lockbox::scenefile::SceneMetadata meta;
///     auto r = lockbox::scenefile::LoadSceneFile("level1.json", world, &meta);
///     if (!r) std::puts(r.Describe().c_str());  // "body[3].angle: ..."; world unchanged
///     lockbox::b2Body* hero = meta.GetBodyByName(world, "hero");
///
/// A load reads and validates the whole file into a SceneDocument first, then builds: on any
/// error the world is left exactly as it was. The built world's state hash is a property of
/// the file (the same on every machine), and a world saved by SaveScene loads back to the same
/// hash.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "lockbox/Export.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/scenefile/SceneDocument.h"
#include "lockbox/scenefile/SceneLimits.h"
#include "lockbox/scenefile/SceneMetadata.h"
#include "lockbox/scenefile/SceneResult.h"

/// The scene-file module: b2dJson (R.U.B.E.) world files loaded into and saved from a world,
/// with the names, custom properties and images they carry.
namespace lockbox::scenefile {

// ---- loading ----

/// Reads and validates JSON text into `out` (replacing its contents); touches no world. On
/// error `out` is unspecified.
LOCKBOX_API SceneResult ReadScene(std::string_view json, SceneDocument& out, const SceneLimits& limits = {});

/// Builds a document into `world`: sets its gravity and switches (as b2dJson does for an
/// existing world), then creates the bodies with their fixtures and mass data, then the joints
/// (a gear joint whose joints come later in the list is created after all the others, as
/// b2dJson's two passes do). Checks everything first (indices, body positions within the
/// world's bounds, the world not inside Step): on error nothing changes. With `metadata`, the
/// names, properties, step settings and images are added to it, keyed by the new objects' ids.
LOCKBOX_API SceneResult BuildScene(const SceneDocument& doc, b2World& world, SceneMetadata* metadata = nullptr);

/// ReadScene, then BuildScene.
LOCKBOX_API SceneResult LoadScene(std::string_view json, b2World& world, SceneMetadata* metadata = nullptr,
                                  const SceneLimits& limits = {});

/// Loads into a new world made with the file's gravity; nullptr on error (then *result, when
/// given, says why).
LOCKBOX_API std::unique_ptr<b2World> LoadSceneWorld(std::string_view json, SceneResult* result = nullptr,
                                                    SceneMetadata* metadata = nullptr, const SceneLimits& limits = {});

/// Reads a whole file into `out`, refusing one larger than limits.maxFileBytes.
LOCKBOX_API SceneResult ReadSceneFileBytes(const std::string& path, std::string& out, const SceneLimits& limits = {});

/// LoadScene on a file's contents.
LOCKBOX_API SceneResult LoadSceneFile(const std::string& path, b2World& world, SceneMetadata* metadata = nullptr,
                                      const SceneLimits& limits = {});

// ---- saving ----

/// Describes a world (and its metadata) as a document: bodies, fixtures and joints in creation
/// order, every field b2dJson writes, read through the public API. Gravity and the switches
/// come from the world; step settings, world properties and images from `metadata`. Images
/// whose body no longer exists are attached to no body.
LOCKBOX_API SceneDocument DescribeWorld(const b2World& world, const SceneMetadata* metadata = nullptr);

/// The document as b2dJson JSON text (two-space indentation, shortest decimals, zero vectors as
/// 0, b2dJson's field names and defaults). The same document always gives the same text.
LOCKBOX_API std::string WriteScene(const SceneDocument& doc);

/// DescribeWorld, then WriteScene.
LOCKBOX_API std::string SaveScene(const b2World& world, const SceneMetadata* metadata = nullptr);

/// SaveScene into a file (replacing it).
LOCKBOX_API SceneResult SaveSceneFile(const std::string& path, const b2World& world,
                                      const SceneMetadata* metadata = nullptr);

/// XXH3-64 of a scene file's bytes: what a replay recorded on the file carries, so a player
/// can tell that it was given the same file.
LOCKBOX_API uint64 SceneFileHash(std::string_view bytes) noexcept;

}  // namespace lockbox::scenefile
