#pragma once
/// lockbox's own scenes (beyond SCENES.md): the car on wheel-joint suspension over chain
/// terrain, a ragdoll pile, a pulley-and-gear machine, a one-sided platform (PreSolve), and the
/// two analytic scenes of the accuracy study (pendulum, slope).

#include <memory>
#include <string_view>
#include <vector>

#include "lockbox/scenes/Car.h"
#include "lockbox/scenes/OneSidedPlatform.h"
#include "lockbox/scenes/Pendulum.h"
#include "lockbox/scenes/PulleyGear.h"
#include "lockbox/scenes/Ragdolls.h"
#include "lockbox/scenes/Scene.h"
#include "lockbox/scenes/Slope.h"

namespace lockbox::scenes {

/// Names of lockbox's own scenes.
inline std::vector<std::string_view> OwnSceneNames() {
    return {"car", "ragdolls", "pulley_gear", "one_sided_platform", "pendulum", "slope"};
}

/// A new own scene by name; nullptr when unknown or when E lacks a joint type it needs.
template <class E>
std::unique_ptr<Scene<E>> MakeOwnScene(std::string_view name) {
    if (name == "one_sided_platform") return std::make_unique<OneSidedPlatformScene<E>>();
    if (name == "slope") return std::make_unique<SlopeScene<E>>();
    if (name == "car") {
        if constexpr (CarScene<E>::kAvailable) return std::make_unique<CarScene<E>>();
        return nullptr;
    }
    if (name == "ragdolls") {
        if constexpr (RagdollsScene<E>::kAvailable) return std::make_unique<RagdollsScene<E>>();
        return nullptr;
    }
    if (name == "pulley_gear") {
        if constexpr (PulleyGearScene<E>::kAvailable) return std::make_unique<PulleyGearScene<E>>();
        return nullptr;
    }
    if (name == "pendulum") {
        if constexpr (PendulumScene<E>::kAvailable) return std::make_unique<PendulumScene<E>>();
        return nullptr;
    }
    return nullptr;
}

}  // namespace lockbox::scenes
