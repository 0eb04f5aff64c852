// lockbox used the way another project uses it (built by this folder's CMakeLists.txt against an
// installed lockbox, the .deb, or the source tree): the manual's Hello World, one snapshot and
// restore, and the state hash. Its last line equals the last line of samples/hello_world.
#include <cinttypes>
#include <cstdio>
#include <vector>

#include "lockbox/Version.h"
#include "lockbox/lockbox.h"

using namespace lockbox;

namespace {

void Step(b2World& world, int32 steps) {
    // 1/60 s rounds to raw 1092 (0.016662598 s).
    for (int32 i = 0; i < steps; ++i) world.Step(Fixed::FromRatio(1, 60), 6, 2);
}

}  // namespace

int main() {
    b2World world(b2Vec2(0, -10));

    b2BodyDef groundBodyDef;
    groundBodyDef.position.Set(0, -10);
    b2Body* groundBody = world.CreateBody(&groundBodyDef);
    b2PolygonShape groundBox;
    groundBox.SetAsBox(50, 10);
    groundBody->CreateFixture(&groundBox, 0);

    b2BodyDef bodyDef;
    bodyDef.type = b2_dynamicBody;
    bodyDef.position.Set(0, 4);
    b2Body* body = world.CreateBody(&bodyDef);
    b2PolygonShape dynamicBox;
    dynamicBox.SetAsBox(1, 1);
    b2FixtureDef fixtureDef;
    fixtureDef.shape = &dynamicBox;
    fixtureDef.density = 1;
    fixtureDef.friction = 0.3;
    body->CreateFixture(&fixtureDef);

    // Half a second, a snapshot, then the second half: the hello world's 60 steps.
    Step(world, 30);
    const std::vector<uint8> snapshot = world.Save();
    Step(world, 30);
    const uint64 hash = world.Hash();
    const b2Vec2 position = body->GetPosition();

    // Roll back to the snapshot and step the second half again: the same bits.
    const b2RestoreResult restored = world.Restore(snapshot);
    if (!restored) {
        std::fprintf(stderr, "consumer: restore refused: %s\n", restored.message.c_str());
        return 1;
    }
    Step(world, 30);
    if (world.Hash() != hash) {
        std::fprintf(stderr, "consumer: restore then step gave hash 0x%016" PRIx64 ", step gave 0x%016" PRIx64 "\n",
                     world.Hash(), hash);
        return 1;
    }

    std::printf("lockbox %s: box at (%4.2f, %4.2f) after 60 steps; restore then step agrees\n", LOCKBOX_VERSION_STRING,
                position.x.ToDouble(), position.y.ToDouble());
    std::printf("hash 0x%016" PRIx64 "\n", hash);
    return 0;
}
