// Every shape pair with a collider gets a contact through b2Contact::Evaluate (in the
// registered order), surface/surface pairs get none; kinematic bodies, sub-stepping.
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"
#include "FixedPrint.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

// Attaches a shape of the given type, about 1 m across, centred at the body origin.
void AddShape(b2Body* body, b2Shape::Type type) {
    switch (type) {
        case b2Shape::e_circle: {
            b2CircleShape s;
            s.m_radius = Fixed(0.5);
            body->CreateFixture(&s, 1);
            break;
        }
        case b2Shape::e_polygon: {
            b2PolygonShape s;
            s.SetAsBox(Fixed(0.5), Fixed(0.5));
            body->CreateFixture(&s, 1);
            break;
        }
        case b2Shape::e_edge: {
            b2EdgeShape s;
            s.Set(b2Vec2(-2, 0), b2Vec2(2, 0));
            body->CreateFixture(&s, 0);
            break;
        }
        case b2Shape::e_chain: {
            b2ChainShape s;
            const b2Vec2 vs[3] = {b2Vec2(-2, 0), b2Vec2(0, 0), b2Vec2(2, 0)};
            s.CreateChain(vs, 3);
            body->CreateFixture(&s, 0);
            break;
        }
        default: break;
    }
}

TEST(ShapePairs, EveryColliderPairTouchesAndRests) {
    const b2Shape::Type types[4] = {b2Shape::e_circle, b2Shape::e_edge, b2Shape::e_polygon, b2Shape::e_chain};
    for (b2Shape::Type ground : types) {
        for (b2Shape::Type falling : {b2Shape::e_circle, b2Shape::e_polygon}) {
            b2World world(b2Vec2(0, -10));
            b2BodyDef gd;
            b2Body* g = world.CreateBody(&gd);
            AddShape(g, ground);
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            // Off-centre on flat grounds; exactly centred on a round one (balanced by symmetry).
            bd.position.Set(ground == b2Shape::e_circle ? Fixed() : Fixed(0.25), 2);
            b2Body* b = world.CreateBody(&bd);
            AddShape(b, falling);
            for (int n = 0; n < 120; ++n) world.Step(kDt, 8, 3);
            ASSERT_GE(world.GetContactCount(), 1) << ground << "/" << falling;
            bool touching = false;
            for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) {
                touching = touching || c->IsTouching();
                // Registered order: A is the polygon/edge/chain when B is a circle, and the
                // edge/chain when B is a polygon.
                const b2Shape::Type ta = c->GetFixtureA()->GetType();
                const b2Shape::Type tb = c->GetFixtureB()->GetType();
                auto rank = [](b2Shape::Type t) {
                    return t == b2Shape::e_circle ? 0 : t == b2Shape::e_polygon ? 1 : 2;
                };
                EXPECT_GE(rank(ta), rank(tb)) << ta << "/" << tb;
            }
            EXPECT_TRUE(touching) << ground << "/" << falling;
            // Resting on the ground's top (y = 0 for edges/chains, 0.5 for the 1 m shapes).
            const double top = (ground == b2Shape::e_edge || ground == b2Shape::e_chain) ? 0.0 : 0.5;
            EXPECT_NEAR(b->GetPosition().y.ToDouble(), top + 0.5, 0.05) << ground << "/" << falling;
        }
    }
}

TEST(ShapePairs, SurfacesNeverCollideWithSurfaces) {
    b2World world(b2Vec2(0, 0));
    b2BodyDef gd;
    b2Body* g = world.CreateBody(&gd);
    AddShape(g, b2Shape::e_edge);
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    b2Body* b = world.CreateBody(&bd);
    AddShape(b, b2Shape::e_chain);
    world.Step(kDt, 8, 3);
    EXPECT_EQ(world.GetContactCount(), 0);
}

TEST(ShapePairs, KinematicBodyPushesDynamicAndIgnoresStatic) {
    b2World world(b2Vec2(0, 0));
    MakeStaticBox(world, 0, -3, 10, 1);
    b2BodyDef kd;
    kd.type = b2_kinematicBody;
    kd.position.Set(-3, 0);
    b2Body* pusher = world.CreateBody(&kd);
    b2PolygonShape box;
    box.SetAsBox(Fixed(0.5), Fixed(0.5));
    pusher->CreateFixture(&box, 1);
    pusher->SetLinearVelocity(b2Vec2(2, 0));
    b2Body* crate = MakeDynamicBox(world, 0, 0, Fixed(0.5), Fixed(0.5));
    for (int n = 0; n < 120; ++n) world.Step(kDt, 8, 3);
    // The kinematic body kept its velocity and mass 0; the crate was pushed ahead of it.
    EXPECT_EQ(pusher->GetLinearVelocity(), b2Vec2(2, 0));
    EXPECT_EQ(pusher->GetMass(), Wide());
    EXPECT_GT(crate->GetPosition().x, pusher->GetPosition().x + Fixed(0.9));
}

TEST(ShapePairs, SubSteppingStopsAfterOneTOIEventPerStep) {
    b2World world(b2Vec2(0, 0));
    world.SetSubStepping(true);
    MakeStaticBox(world, 10, 0, Fixed(0.05), 5);
    std::vector<b2Body*> shots;
    for (int i = 0; i < 3; ++i) {
        b2Body* s = MakeDynamicCircle(world, Fixed(0.9), Fixed(-2) + Fixed(2) * Fixed(i), Fixed(0.1));
        s->SetBullet(true);
        s->SetLinearVelocity(b2Vec2(120, 0));
        shots.push_back(s);
    }
    int maxSubSteps = 0;
    for (int n = 0; n < 20; ++n) {
        world.Step(kDt, 8, 3);
        maxSubSteps = std::max(maxSubSteps, world.GetProfile().toiSubSteps);
    }
    EXPECT_EQ(maxSubSteps, 1);
    for (b2Body* s : shots) EXPECT_LT(s->GetPosition().x, Fixed(10));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
