// The demo's offline mode (`lockbox_demo --offline`): the manual's Hello World, then one scene
// from the library run to its default length in one world, printing the state hash every 60
// steps. The hash is the same on every machine, compiler and architecture.
#include "OfflineRun.h"

#include <cstdio>
#include <string>

#include "lockbox/lockbox.h"
#include "lockbox/scenes/LockboxScenes.h"

using namespace lockbox;

namespace {

void HelloWorld() {
    std::printf("== Hello World (the manual's, on Q16.16) ==\n");
    b2World world(b2Vec2(0.0f, -10.0f));

    b2BodyDef groundBodyDef;
    groundBodyDef.position.Set(0.0f, -10.0f);
    b2Body* groundBody = world.CreateBody(&groundBodyDef);
    b2PolygonShape groundBox;
    groundBox.SetAsBox(50.0f, 10.0f);
    groundBody->CreateFixture(&groundBox, 0.0f);

    b2BodyDef bodyDef;
    bodyDef.type = b2_dynamicBody;
    bodyDef.position.Set(0.0f, 4.0f);
    b2Body* body = world.CreateBody(&bodyDef);
    b2PolygonShape dynamicBox;
    dynamicBox.SetAsBox(1.0f, 1.0f);
    b2FixtureDef fixtureDef;
    fixtureDef.shape = &dynamicBox;
    fixtureDef.density = 1.0f;
    fixtureDef.friction = 0.3f;
    body->CreateFixture(&fixtureDef);

    const Fixed timeStep = 1.0f / 60.0f;  // compile-time conversion: 1092/65536 s
    const int32 velocityIterations = 6;
    const int32 positionIterations = 2;
    for (int32 i = 0; i < 60; ++i) {
        world.Step(timeStep, velocityIterations, positionIterations);
        const b2Vec2 position = body->GetPosition();
        const Fixed angle = body->GetAngle();
        std::printf("%4.2f %4.2f %4.2f\n", position.x.ToDouble(), position.y.ToDouble(), angle.ToDouble());
    }
}

int RunSceneOffline(const std::string& name, int steps) {
    auto scene = scenes::MakeLockboxScene(name);
    if (!scene) {
        std::fprintf(stderr, "lockbox_demo: unknown scene '%s'\n", name.c_str());
        return 2;
    }
    scenes::LockboxEngine engine;
    scenes::RunSettings settings;
    const scenes::Resolved r = scenes::Resolve(scene->Info(), settings);
    if (steps < 0) steps = r.steps;
    scenes::ConfigureWorld(engine, scene->Info(), settings);
    scene->Prepare(r);
    scene->Build(engine);
    std::printf("\n== Scene %s: %d steps at %d Hz, %d/%d iterations ==\n", name.c_str(), steps, r.hz,
                r.velocityIterations, r.positionIterations);
    for (int i = 0; i < steps; ++i) {
        scene->BeforeStep(engine, i);
        engine.Step(r.hz, r.velocityIterations, r.positionIterations);
        scene->AfterStep(engine, i);
        if ((i + 1) % 60 == 0 || i + 1 == steps) {
            std::printf("step %4d  bodies %4d  contacts %5d  hash 0x%016llx\n", i + 1, engine.world().GetBodyCount(),
                        engine.world().GetContactCount(),
                        static_cast<unsigned long long>(scenes::HashWorld(engine.world())));
        }
    }
    std::vector<scenes::Metric> metrics;
    scene->Report(engine, metrics);
    for (const auto& m : metrics) std::printf("  %s = %g\n", m.name.c_str(), m.value);
    return 0;
}

}  // namespace

int RunOffline(const std::string& scene, int steps) {
    HelloWorld();
    return RunSceneOffline(scene, steps);
}
