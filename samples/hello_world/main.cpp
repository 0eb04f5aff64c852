// The manual's Hello World on lockbox: a 1x1 m box falls onto a static ground box.
// Literals become Q16.16 at compile time; printing converts to double for display only. The last
// line is the world's state hash.
#include <cinttypes>
#include <cstdio>

#include "lockbox/lockbox.h"

using namespace lockbox;

int main() {
    // Define the gravity vector and construct a world object.
    b2Vec2 gravity(0, -10);
    b2World world(gravity);

    // Define the ground body.
    b2BodyDef groundBodyDef;
    groundBodyDef.position.Set(0, -10);
    b2Body* groundBody = world.CreateBody(&groundBodyDef);

    // The extents are the half-widths of the box: 50 x 10 m.
    b2PolygonShape groundBox;
    groundBox.SetAsBox(50, 10);
    groundBody->CreateFixture(&groundBox, 0);

    // Define the dynamic body and set its initial position.
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

    // 1/60 s rounds to raw 1092 (0.016662598 s).
    const Fixed timeStep = Fixed::FromRatio(1, 60);
    const int32 velocityIterations = 6;
    const int32 positionIterations = 2;

    for (int32 i = 0; i < 60; ++i) {
        world.Step(timeStep, velocityIterations, positionIterations);
        const b2Vec2 position = body->GetPosition();
        const Fixed angle = body->GetAngle();
        std::printf("%4.2f %4.2f %4.2f\n", position.x.ToDouble(), position.y.ToDouble(), angle.ToDouble());
    }
    // The state hash after 60 steps: the same on every machine (samples/consumer prints it too).
    std::printf("hash 0x%016" PRIx64 "\n", world.Hash());
    return 0;
}
