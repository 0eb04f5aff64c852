#pragma once
/// The scene library on lockbox: the registry bound to LockboxEngine, and the world hash the
/// benchmark and the determinism tests print.

#include <cstdint>
#include <memory>
#include <string_view>

#include "lockbox/scenes/LockboxEngine.h"
#include "lockbox/scenes/Registry.h"

namespace lockbox::scenes {

/// A scene on lockbox.
using LockboxScene = Scene<LockboxEngine>;

/// A new lockbox scene by name; nullptr when unknown or not yet available (joints missing).
std::unique_ptr<LockboxScene> MakeLockboxScene(std::string_view name);

/// 64-bit XXH3 of every body's raw state in body-list order: position x, y, angle, linear
/// velocity x, y, angular velocity (six int32 per body, little-endian). Equal hashes mean
/// (with overwhelming probability) bit-identical states.
uint64_t HashWorld(const b2World& world);

}  // namespace lockbox::scenes
