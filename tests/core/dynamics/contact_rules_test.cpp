// Test 4a: the manual's contact behaviours: body-type rules, the filter truth table, sensors,
// listener events (order and counts), PreSolve (one-sided platform), SetFilterData timing.
#include <cstdio>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"
#include "FixedPrint.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

int TouchingContacts(b2World& world) {
    int n = 0;
    for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) n += c->IsTouching() ? 1 : 0;
    return n;
}

b2Body* MakeBox(b2World& world, b2BodyType type, Fixed x, Fixed y) {
    b2BodyDef bd;
    bd.type = type;
    bd.position.Set(x, y);
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(Fixed(0.5), Fixed(0.5));
    body->CreateFixture(&box, 1);
    return body;
}

TEST(ContactRules, BodyTypeCollisionMatrix) {
    // Only pairs with at least one dynamic body get a contact (the manual's table).
    const b2BodyType types[3] = {b2_staticBody, b2_kinematicBody, b2_dynamicBody};
    for (b2BodyType a : types) {
        for (b2BodyType b : types) {
            b2World world(b2Vec2(0, 0));
            MakeBox(world, a, 0, 0);
            MakeBox(world, b, Fixed(0.5), 0);  // overlapping
            world.Step(kDt, 8, 3);
            const bool expected = a == b2_dynamicBody || b == b2_dynamicBody;
            EXPECT_EQ(world.GetContactCount() > 0, expected) << a << " vs " << b;
            EXPECT_EQ(TouchingContacts(world) > 0, expected) << a << " vs " << b;
        }
    }
}

bool FiltersCollide(const b2Filter& fa, const b2Filter& fb) {
    b2World world(b2Vec2(0, 0));
    b2Body* a = MakeBox(world, b2_dynamicBody, 0, 0);
    b2Body* b = MakeBox(world, b2_dynamicBody, Fixed(0.5), 0);
    a->GetFixtureList()->SetFilterData(fa);
    b->GetFixtureList()->SetFilterData(fb);
    world.Step(kDt, 8, 3);
    return TouchingContacts(world) > 0;
}

b2Filter Filter(uint16 category, uint16 mask, int16 group) {
    b2Filter f;
    f.categoryBits = category;
    f.maskBits = mask;
    f.groupIndex = group;
    return f;
}

TEST(ContactRules, FilterTruthTable) {
    struct Row {
        b2Filter a, b;
        bool collide;
        const char* why;
    };
    const Row rows[] = {
        {Filter(1, 0xFFFF, 0), Filter(1, 0xFFFF, 0), true, "defaults"},
        {Filter(1, 0xFFFF, 0), Filter(2, 0xFFFF, 0), true, "masks accept all"},
        {Filter(1, 0x0002, 0), Filter(2, 0x0001, 0), true, "each mask accepts the other"},
        {Filter(1, 0x0002, 0), Filter(2, 0x0002, 0), false, "B rejects A's category"},
        {Filter(1, 0x0004, 0), Filter(2, 0x0001, 0), false, "A rejects B's category"},
        {Filter(1, 0x0000, 0), Filter(1, 0xFFFF, 0), false, "empty mask"},
        {Filter(1, 0x0000, 3), Filter(1, 0x0000, 3), true, "same positive group overrides masks"},
        {Filter(1, 0xFFFF, -3), Filter(1, 0xFFFF, -3), false, "same negative group overrides masks"},
        {Filter(1, 0xFFFF, -3), Filter(1, 0xFFFF, -4), true, "different groups fall back to masks"},
        {Filter(1, 0x0000, -3), Filter(1, 0xFFFF, 4), false, "different groups, mask rejects"},
        {Filter(1, 0xFFFF, 2), Filter(1, 0xFFFF, 0), true, "group vs none uses masks"},
    };
    for (const Row& r : rows) EXPECT_EQ(FiltersCollide(r.a, r.b), r.collide) << r.why;
}

TEST(ContactRules, CustomContactFilterIsConsulted) {
    struct NeverFilter : b2ContactFilter {
        bool ShouldCollide(b2Fixture*, b2Fixture*) override {
            ++calls;
            return false;
        }
        int calls = 0;
    } filter;
    b2World world(b2Vec2(0, 0));
    world.SetContactFilter(&filter);
    MakeBox(world, b2_dynamicBody, 0, 0);
    MakeBox(world, b2_dynamicBody, Fixed(0.5), 0);
    world.Step(kDt, 8, 3);
    EXPECT_EQ(world.GetContactCount(), 0);
    EXPECT_GE(filter.calls, 1);
}

TEST(ContactRules, SensorReportsBeginEndWithoutPointsOrResponse) {
    b2World world(b2Vec2(0, -10));
    RecordingListener listener;
    world.SetContactListener(&listener);
    // A static sensor zone between y = -1 and 1; a ball falls through it.
    MakeStaticSensorBox(world, 0, 0, 2, 1);
    b2Body* ball = MakeDynamicCircle(world, 0, 3, Fixed(0.25));

    bool sawTouching = false;
    for (int n = 0; n < 120; ++n) {
        world.Step(kDt, 8, 3);
        for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) {
            EXPECT_EQ(c->GetManifold()->pointCount, 0);  // sensors make no points
            sawTouching = sawTouching || c->IsTouching();
        }
    }
    EXPECT_TRUE(sawTouching);
    EXPECT_EQ(listener.begins, 1);
    EXPECT_EQ(listener.ends, 1);
    EXPECT_EQ(listener.preSolves, 0);
    EXPECT_EQ(listener.postSolves, 0);
    // No response: the ball fell freely through.
    EXPECT_LT(ball->GetPosition().y, Fixed(-5));
    EXPECT_EQ(listener.log, "BE");
}

TEST(ContactRules, ListenerEventOrderAndCounts) {
    b2World world(b2Vec2(0, -10));
    RecordingListener listener;
    world.SetContactListener(&listener);
    MakeStaticBox(world, 0, -1, 10, 1);
    b2Body* box = MakeDynamicBox(world, 0, 2, Fixed(0.5), Fixed(0.5));
    int firstBegin = -1;
    for (int n = 0; n < 120; ++n) {
        const int before = listener.begins;
        world.Step(kDt, 8, 3);
        if (before == 0 && listener.begins == 1) firstBegin = n;
    }
    ASSERT_GE(firstBegin, 0);
    // Exactly one Begin; every step after it gives one PreSolve and one PostSolve until sleep.
    EXPECT_EQ(listener.begins, 1);
    EXPECT_EQ(listener.ends, 0);
    EXPECT_EQ(listener.log[0], 'B');
    EXPECT_EQ(listener.log[1], 'P');
    EXPECT_EQ(listener.preSolves, listener.postSolves);
    for (size_t i = 1; i + 1 < listener.log.size(); i += 2) {
        EXPECT_EQ(listener.log[i], 'P') << i;
        EXPECT_EQ(listener.log[i + 1], 'S') << i;
    }
    // Lifting the box off ends the contact once its fat AABB separates. SetTransform does not
    // wake a sleeping body (as 2.2.1), and contacts of sleeping bodies are not updated.
    EXPECT_FALSE(box->IsAwake());
    box->SetTransform(b2Vec2(0, 10), 0);
    world.Step(kDt, 8, 3);
    EXPECT_EQ(listener.ends, 0);
    box->SetAwake(true);
    world.Step(kDt, 8, 3);
    EXPECT_EQ(listener.ends, 1);
    EXPECT_EQ(listener.log.back(), 'E');
}

// The manual's one-sided platform: PreSolve disables the contact while the body is below.
class OneSidedPlatform : public b2ContactListener {
public:
    void PreSolve(b2Contact* contact, const b2Manifold*) override {
        b2Fixture* other = contact->GetFixtureA() == platform ? contact->GetFixtureB() : contact->GetFixtureA();
        if (contact->GetFixtureA() != platform && contact->GetFixtureB() != platform) return;
        // Disable unless the body's bottom is above the platform's top (with slop).
        const Fixed bottom = other->GetBody()->GetPosition().y - Fixed(0.25);
        if (bottom < top - Fixed(0.05)) contact->SetEnabled(false);
    }
    b2Fixture* platform = nullptr;
    Fixed top;
};

TEST(ContactRules, PreSolveDisablingMakesAOneSidedPlatform) {
    b2World world(b2Vec2(0, -10));
    b2Body* plat = MakeStaticBox(world, 0, 5, 3, Fixed(0.25));
    OneSidedPlatform listener;
    listener.platform = plat->GetFixtureList();
    listener.top = Fixed(5.25);
    world.SetContactListener(&listener);
    // A ball launched upward from below passes through, then lands on top.
    b2Body* ball = MakeDynamicCircle(world, 0, 2, Fixed(0.25));
    ball->SetLinearVelocity(b2Vec2(0, 12));
    Fixed maxY;
    for (int n = 0; n < 300; ++n) {
        world.Step(kDt, 8, 3);
        maxY = b2Max(maxY, ball->GetPosition().y);
    }
    EXPECT_GT(maxY, Fixed(6));                                 // went through from below
    EXPECT_NEAR(ball->GetPosition().y.ToDouble(), 5.5, 0.03);  // resting on top
}

TEST(ContactRules, SetFilterDataTakesEffectNextStep) {
    b2World world(b2Vec2(0, 0));
    b2Body* a = MakeBox(world, b2_dynamicBody, 0, 0);
    MakeBox(world, b2_dynamicBody, Fixed(0.5), 0);
    world.Step(kDt, 8, 3);
    ASSERT_EQ(TouchingContacts(world), 1);
    // Reject: the contact survives until the next Step re-filters it.
    a->GetFixtureList()->SetFilterData(Filter(1, 0, 0));
    EXPECT_EQ(world.GetContactCount(), 1);
    world.Step(kDt, 8, 3);
    EXPECT_EQ(world.GetContactCount(), 0);
    // Accept again: the touched proxies form the pair at the next Step.
    a->GetFixtureList()->SetFilterData(Filter(1, 0xFFFF, 0));
    EXPECT_EQ(world.GetContactCount(), 0);
    world.Step(kDt, 8, 3);
    EXPECT_EQ(world.GetContactCount(), 1);
}

TEST(ContactRules, FixturesOfOneBodyNeverCollide) {
    b2World world(b2Vec2(0, 0));
    b2Body* a = MakeBox(world, b2_dynamicBody, 0, 0);
    b2CircleShape c;
    c.m_radius = Fixed(0.5);
    a->CreateFixture(&c, 1);
    world.Step(kDt, 8, 3);
    EXPECT_EQ(world.GetContactCount(), 0);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
