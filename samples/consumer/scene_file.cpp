// The scenefile component used from another project: a world saved as b2dJson text, loaded back
// into a new world, and both stepped on. Built when the scenefile component is available; its
// calls go through the library's exported symbols, so a shared build missing one fails to link.
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>

#include "lockbox/lockbox.h"
#include "lockbox/scenefile/SceneFile.h"

using namespace lockbox;

namespace {

void Step(b2World& world, int32 steps) {
    for (int32 i = 0; i < steps; ++i) world.Step(Fixed::FromRatio(1, 60), 8, 3);
}

}  // namespace

int main() {
    b2World world(b2Vec2(0, -10));

    b2BodyDef groundDef;
    b2Body* ground = world.CreateBody(&groundDef);
    b2EdgeShape floor;
    floor.Set(b2Vec2(-20, 0), b2Vec2(20, 0));
    ground->CreateFixture(&floor, 0);

    b2BodyDef ballDef;
    ballDef.type = b2_dynamicBody;
    ballDef.position.Set(0, 3);
    ballDef.linearVelocity.Set(1, 0);
    b2Body* ball = world.CreateBody(&ballDef);
    b2CircleShape circle;
    circle.m_radius = 0.5f;
    ball->CreateFixture(&circle, 1);

    // A file holds what a level is made of, not what stepping adds (contacts, sleep timers), so
    // the world is saved before its first step.
    const std::string text = scenefile::SaveScene(world);
    scenefile::SceneResult result;
    const std::unique_ptr<b2World> loaded = scenefile::LoadSceneWorld(text, &result);
    if (!loaded) {
        std::fprintf(stderr, "consumer_scene_file: the saved scene does not load: %s\n", result.Describe().c_str());
        return 1;
    }
    if (loaded->Hash() != world.Hash()) {
        std::fprintf(stderr, "consumer_scene_file: loaded hash 0x%016" PRIx64 ", saved world 0x%016" PRIx64 "\n",
                     loaded->Hash(), world.Hash());
        return 1;
    }
    Step(world, 60);
    Step(*loaded, 60);
    if (loaded->Hash() != world.Hash()) {
        std::fprintf(stderr, "consumer_scene_file: after 60 steps the loaded world differs\n");
        return 1;
    }
    std::printf("scenefile: %zu bytes of b2dJson load back to the same world; 60 steps later both hash 0x%016" PRIx64
                "\n",
                text.size(), world.Hash());
    return 0;
}
