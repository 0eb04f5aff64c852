#pragma once
/// The scene registry: every scene by name, for one engine adapter. The SCENES.md scenes come
/// first (with bullet as its six variants), then lockbox's own.

#include <memory>
#include <string_view>
#include <vector>

#include "lockbox/scenes/Bullet.h"
#include "lockbox/scenes/Chain60.h"
#include "lockbox/scenes/Hello.h"
#include "lockbox/scenes/JointGrid.h"
#include "lockbox/scenes/LargePyramid.h"
#include "lockbox/scenes/ManyPyramids.h"
#include "lockbox/scenes/OwnScenes.h"
#include "lockbox/scenes/Pyramid20.h"
#include "lockbox/scenes/Rain.h"
#include "lockbox/scenes/Scene.h"
#include "lockbox/scenes/Tumbler.h"
#include "lockbox/scenes/VerticalStack.h"

namespace lockbox::scenes {

/// Names of the SCENES.md scenes, in SCENES.md order (bullet as its six variants).
inline std::vector<std::string_view> SharedSceneNames() {
    return {"hello",
            "vertical_stack",
            "pyramid20",
            "large_pyramid",
            "many_pyramids",
            "rain",
            "joint_grid",
            "tumbler",
            "chain60",
            "bullet_wall_dynamic",
            "bullet_wall_bullet",
            "bullet_wall_nocontinuous",
            "bullet_stack_dynamic",
            "bullet_stack_bullet",
            "bullet_stack_nocontinuous"};
}

/// Names of every scene: the shared ones, then lockbox's own.
inline std::vector<std::string_view> AllSceneNames() {
    auto names = SharedSceneNames();
    for (auto n : OwnSceneNames()) names.push_back(n);
    return names;
}

/// A new scene by name for engine E; nullptr when the name is unknown or the scene needs a
/// joint type E does not have yet.
template <class E>
std::unique_ptr<Scene<E>> MakeScene(std::string_view name) {
    if (name == "hello") return std::make_unique<HelloScene<E>>();
    if (name == "vertical_stack") return std::make_unique<VerticalStackScene<E>>();
    if (name == "pyramid20") return std::make_unique<Pyramid20Scene<E>>();
    if (name == "large_pyramid") return std::make_unique<LargePyramidScene<E>>();
    if (name == "many_pyramids") return std::make_unique<ManyPyramidsScene<E>>();
    if (name == "rain") return std::make_unique<RainScene<E>>();
    if (name == "joint_grid") {
        if constexpr (JointGridScene<E>::kAvailable) return std::make_unique<JointGridScene<E>>();
        return nullptr;
    }
    if (name == "tumbler") {
        if constexpr (TumblerScene<E>::kAvailable) return std::make_unique<TumblerScene<E>>();
        return nullptr;
    }
    if (name == "chain60") {
        if constexpr (Chain60Scene<E>::kAvailable) return std::make_unique<Chain60Scene<E>>();
        return nullptr;
    }
    const BulletTarget targets[2] = {BulletTarget::wall, BulletTarget::stack};
    const BulletMode modes[3] = {BulletMode::dynamic, BulletMode::bullet, BulletMode::noContinuous};
    for (int t = 0; t < 2; ++t)
        for (int m = 0; m < 3; ++m)
            if (name == BulletScene<E>::kInfos[3 * t + m].name)
                return std::make_unique<BulletScene<E>>(targets[t], modes[m]);
    return MakeOwnScene<E>(name);
}

}  // namespace lockbox::scenes
