// Test 4b: the manual's world behaviours: queries and ray casts, the destruction listener,
// the locked world, sleep and wake, SetTransform, inactive bodies, mass rules, ids.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"
#include "FixedPrint.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

TEST(WorldApi, QueryAABBReportsOverlapsAndStopsOnFalse) {
    b2World world(b2Vec2(0, 0));
    for (int i = 0; i < 5; ++i) MakeStaticBox(world, Fixed(3 * i), 0, Fixed(0.5), Fixed(0.5));
    struct Collect : b2QueryCallback {
        bool ReportFixture(b2Fixture* f) override {
            ids.push_back(f->GetId());
            return static_cast<int>(ids.size()) < stopAfter;
        }
        std::vector<int32> ids;
        int stopAfter = 100;
    } all, first;
    b2AABB box;
    box.lowerBound.Set(-1, -1);
    box.upperBound.Set(7, 1);  // covers the boxes at x = 0, 3, 6
    world.QueryAABB(&all, box);
    std::sort(all.ids.begin(), all.ids.end());
    EXPECT_EQ(all.ids, (std::vector<int32>{0, 1, 2}));
    first.stopAfter = 1;
    world.QueryAABB(&first, box);
    EXPECT_EQ(first.ids.size(), 1u);
}

struct RayRecorder : b2RayCastCallback {
    Fixed ReportFixture(b2Fixture* f, const b2Vec2& p, const b2Vec2& n, Fixed fraction) override {
        hits.push_back(f->GetBody()->GetPosition().x.ToDouble());
        if (mode == 3 && f->GetBody()->GetPosition().x == Fixed(2)) return Fixed(-1);
        point = p;
        normal = n;
        if (mode == 0) return Fixed();   // stop at the first hit reported
        if (mode == 1) return fraction;  // clip: ends with the closest
        if (mode == 2) return Fixed(1);  // continue: all hits
        return fraction;                 // mode 3: filtered above, clip the rest
    }
    int mode = 1;
    std::vector<double> hits;
    b2Vec2 point, normal;
};

TEST(WorldApi, RayCastFractionProtocol) {
    b2World world(b2Vec2(0, 0));
    for (int i = 1; i <= 3; ++i) MakeStaticBox(world, Fixed(2 * i), 0, Fixed(0.5), Fixed(0.5));  // x = 2, 4, 6
    const b2Vec2 p1(0, 0), p2(10, 0);

    RayRecorder all;
    all.mode = 2;
    world.RayCast(&all, p1, p2);
    EXPECT_EQ(all.hits.size(), 3u);

    RayRecorder stop;
    stop.mode = 0;
    world.RayCast(&stop, p1, p2);
    EXPECT_EQ(stop.hits.size(), 1u);

    // Clipping: whatever the visiting order, the last reported hit is the closest (x = 2, face
    // at 1.5; polygon ray casts ignore the skin, as 2.2.1) and the normal faces the ray.
    RayRecorder clip;
    clip.mode = 1;
    world.RayCast(&clip, p1, p2);
    ASSERT_FALSE(clip.hits.empty());
    EXPECT_EQ(clip.hits.back(), 2.0);
    EXPECT_NEAR(clip.point.x.ToDouble(), 1.5, 0.02);
    EXPECT_EQ(clip.normal, b2Vec2(-1, 0));

    // Filtering the closest box with -1: the closest remaining hit is x = 4.
    RayRecorder filter;
    filter.mode = 3;
    world.RayCast(&filter, p1, p2);
    ASSERT_FALSE(filter.hits.empty());
    EXPECT_NEAR(filter.point.x.ToDouble(), 3.5, 0.02);
}

TEST(WorldApi, DestructionListenerHearsImplicitFixtureDestruction) {
    struct Listener : b2DestructionListener {
        void SayGoodbye(b2Joint*) override { ++joints; }
        void SayGoodbye(b2Fixture* f) override { fixtures.push_back(f->GetUserData()); }
        int joints = 0;
        std::vector<uint64> fixtures;
    } listener;
    b2World world(b2Vec2(0, 0));
    world.SetDestructionListener(&listener);
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    b2Body* body = world.CreateBody(&bd);
    b2CircleShape c;
    c.m_radius = 1;
    b2FixtureDef fd;
    fd.shape = &c;
    fd.userData = 11;
    body->CreateFixture(&fd);
    fd.userData = 22;
    b2Fixture* second = body->CreateFixture(&fd);
    fd.userData = 33;
    body->CreateFixture(&fd);
    // Explicit destruction is not reported.
    body->DestroyFixture(second);
    EXPECT_TRUE(listener.fixtures.empty());
    world.DestroyBody(body);
    EXPECT_EQ(listener.fixtures, (std::vector<uint64>{33, 11}));  // fixture list order: newest first
    EXPECT_EQ(world.GetBodyCount(), 0);
    EXPECT_EQ(world.GetProxyCount(), 0);
}

std::vector<std::string> g_refusals;
void RecordRefusal(const char*, const char* msg, const char*, int) { g_refusals.emplace_back(msg); }

TEST(WorldApi, LockedWorldRefusesCreateAndDestroyInCallbacks) {
    struct Meddler : b2ContactListener {
        void BeginContact(b2Contact* c) override {
            b2BodyDef bd;
            createdBody = world->CreateBody(&bd);
            b2CircleShape s;
            s.m_radius = 1;
            createdFixture = c->GetFixtureA()->GetBody()->CreateFixture(&s, 1);
            world->DestroyBody(c->GetFixtureB()->GetBody());
            c->GetFixtureA()->GetBody()->DestroyFixture(c->GetFixtureA());
            locked = world->IsLocked();
        }
        b2World* world = nullptr;
        b2Body* createdBody = reinterpret_cast<b2Body*>(1);
        b2Fixture* createdFixture = reinterpret_cast<b2Fixture*>(1);
        bool locked = false;
    } meddler;
    const b2AssertHandler previous = b2SetAssertHandler(&RecordRefusal);
    g_refusals.clear();
    b2World world(b2Vec2(0, -10));
    meddler.world = &world;
    world.SetContactListener(&meddler);
    MakeStaticBox(world, 0, -1, 5, 1);
    MakeDynamicBox(world, 0, 1, Fixed(0.5), Fixed(0.5));
    for (int n = 0; n < 60; ++n) world.Step(kDt, 8, 3);
    b2SetAssertHandler(previous);

    EXPECT_TRUE(meddler.locked);
    EXPECT_EQ(meddler.createdBody, nullptr);
    EXPECT_EQ(meddler.createdFixture, nullptr);
    EXPECT_EQ(world.GetBodyCount(), 2);
    EXPECT_FALSE(world.IsLocked());
    // Debug/checked builds route each refusal through the handler with a clear message.
    if (b2_assertsEnabled) {
        ASSERT_EQ(g_refusals.size(), 4u);
        EXPECT_NE(g_refusals[0].find("locked"), std::string::npos);
    } else {
        EXPECT_TRUE(g_refusals.empty());
    }
    // Unlocked again: creation works.
    b2BodyDef bd;
    EXPECT_NE(world.CreateBody(&bd), nullptr);
}

TEST(WorldApi, SleepAndWake) {
    b2World world(b2Vec2(0, -10));
    MakeStaticBox(world, 0, -1, 10, 1);
    b2Body* box = MakeDynamicBox(world, 0, Fixed(0.52), Fixed(0.5), Fixed(0.5));
    int steps = 0;
    while (box->IsAwake() && steps < 600) {
        world.Step(kDt, 8, 3);
        ++steps;
    }
    ASSERT_FALSE(box->IsAwake());
    EXPECT_EQ(box->GetLinearVelocity(), b2Vec2());

    // A force wakes it.
    box->ApplyForceToCenter(b2Vec2(0, 100));
    EXPECT_TRUE(box->IsAwake());
    world.Step(kDt, 8, 3);
    EXPECT_GT(box->GetLinearVelocity().y, Fixed());

    // SetAwake(false) zeroes velocity; SetAwake(true) resets the counter.
    box->SetAwake(false);
    EXPECT_EQ(box->GetLinearVelocity(), b2Vec2());
    box->SetAwake(true);
    EXPECT_EQ(box->GetSleepSteps(), 0);

    // Sleeping disallowed keeps it awake.
    box->SetSleepingAllowed(false);
    for (int n = 0; n < 120; ++n) world.Step(kDt, 8, 3);
    EXPECT_TRUE(box->IsAwake());
    box->SetSleepingAllowed(true);
    for (int n = 0; n < 120; ++n) world.Step(kDt, 8, 3);
    EXPECT_FALSE(box->IsAwake());

    // Destroying the supporting contact (the ground) wakes it, and it falls.
    b2Body* ground = world.GetBodyList()->GetNext();  // newest first: box, then ground
    ASSERT_EQ(ground->GetType(), b2_staticBody);
    world.DestroyBody(ground);
    EXPECT_TRUE(box->IsAwake());
    world.Step(kDt, 8, 3);
    EXPECT_LT(box->GetLinearVelocity().y, Fixed());
}

TEST(WorldApi, SleepCountsWholeStepsThirtyAt60Hz) {
    b2World world(b2Vec2(0, 0));
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    b2Body* body = world.CreateBody(&bd);
    b2CircleShape c;
    c.m_radius = 1;
    body->CreateFixture(&c, 1);
    int steps = 0;
    while (body->IsAwake()) {
        world.Step(kDt, 8, 3);
        ++steps;
    }
    EXPECT_EQ(steps, 30);
    // The linear threshold is compared exactly: just above it never sleeps, at it sleeps.
    for (const int32 raw : {655, 656}) {
        body->SetAwake(true);
        body->SetLinearVelocity(b2Vec2(Fixed::FromRaw(raw), 0));
        for (int n = 0; n < 40; ++n) world.Step(kDt, 8, 3);
        EXPECT_EQ(body->IsAwake(), raw > 655) << raw;
    }
}

TEST(WorldApi, SetTransformMovesBodyAndContacts) {
    b2World world(b2Vec2(0, 0));
    b2Body* a = MakeDynamicBox(world, 0, 0, Fixed(0.5), Fixed(0.5));
    b2Body* b = MakeDynamicBox(world, 5, 0, Fixed(0.5), Fixed(0.5));
    world.Step(kDt, 8, 3);
    EXPECT_EQ(world.GetContactCount(), 0);
    b->SetTransform(b2Vec2(Fixed(0.5), 0), Fixed(0.25));
    EXPECT_EQ(b->GetPosition(), b2Vec2(Fixed(0.5), 0));
    EXPECT_EQ(b->GetAngle(), Fixed(0.25));
    EXPECT_EQ(world.GetContactCount(), 1);  // SetTransform finds the new pair at once
    (void)a;
}

TEST(WorldApi, InactiveBodiesHaveNoProxiesNoContactsNoMotion) {
    b2World world(b2Vec2(0, -10));
    MakeStaticBox(world, 0, -1, 10, 1);
    b2Body* box = MakeDynamicBox(world, 0, Fixed(0.52), Fixed(0.5), Fixed(0.5));
    world.Step(kDt, 8, 3);
    EXPECT_EQ(world.GetProxyCount(), 2);
    EXPECT_EQ(world.GetContactCount(), 1);
    box->SetActive(false);
    EXPECT_EQ(world.GetProxyCount(), 1);
    EXPECT_EQ(world.GetContactCount(), 0);
    const b2Vec2 p = box->GetPosition();
    for (int n = 0; n < 30; ++n) world.Step(kDt, 8, 3);
    EXPECT_EQ(box->GetPosition(), p);
    box->SetActive(true);
    world.Step(kDt, 8, 3);
    EXPECT_EQ(world.GetProxyCount(), 2);
    EXPECT_EQ(world.GetContactCount(), 1);
}

TEST(WorldApi, MassRules) {
    b2World world(b2Vec2(0, 0));
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    b2Body* body = world.CreateBody(&bd);
    // No fixtures: 1 kg.
    EXPECT_EQ(body->GetMass(), Wide(1));
    // A zero-density fixture: still the 1 kg fallback.
    b2PolygonShape box;
    box.SetAsBox(1, 1);
    body->CreateFixture(&box, 0);
    EXPECT_EQ(body->GetMass(), Wide(1));
    // Density 2 on a 2x2 m box: 8 kg; inertia m (w^2 + h^2) / 12 = 8 * 8 / 12.
    body->GetFixtureList()->SetDensity(2);
    body->ResetMassData();
    EXPECT_NEAR(body->GetMass().ToDouble(), 8.0, 1e-6);
    EXPECT_NEAR(body->GetInertia().ToDouble(), 64.0 / 12.0, 1e-4);
    // SetMassData overrides; a non-positive mass becomes 1 kg.
    b2MassData md;
    md.mass = 3;
    md.center.Set(Fixed(0.5), 0);
    md.I = 10;
    body->SetMassData(&md);
    EXPECT_EQ(body->GetMass(), Wide(3));
    EXPECT_EQ(body->GetLocalCenter(), b2Vec2(Fixed(0.5), 0));
    EXPECT_NEAR(body->GetInertia().ToDouble(), 10.0, 1e-6);
    md.mass = Wide();
    body->SetMassData(&md);
    EXPECT_EQ(body->GetMass(), Wide(1));
    // Static bodies have no mass.
    body->SetType(b2_staticBody);
    EXPECT_EQ(body->GetMass(), Wide());
    // Fixed rotation: zero inverse inertia.
    body->SetType(b2_dynamicBody);
    body->SetFixedRotation(true);
    EXPECT_EQ(body->GetInertia(), Wide());
}

TEST(WorldApi, IdsComeFromPoolsAndAreReusedLifo) {
    b2World world(b2Vec2(0, 0));
    b2BodyDef bd;
    b2Body* a = world.CreateBody(&bd);
    b2Body* b = world.CreateBody(&bd);
    b2Body* c = world.CreateBody(&bd);
    EXPECT_EQ(a->GetId(), 0);
    EXPECT_EQ(b->GetId(), 1);
    EXPECT_EQ(c->GetId(), 2);
    EXPECT_EQ(world.GetBodyList(), c);  // newest first
    world.DestroyBody(a);
    world.DestroyBody(c);
    EXPECT_EQ(world.CreateBody(&bd)->GetId(), 2);  // last freed first
    EXPECT_EQ(world.CreateBody(&bd)->GetId(), 0);
    EXPECT_EQ(world.GetBody(1), b);
    b->SetUserData(0xDEADBEEFCAFEull);
    EXPECT_EQ(world.GetBody(1)->GetUserData(), 0xDEADBEEFCAFEull);
}

TEST(WorldApi, SwitchesAreWorldState) {
    b2World world(b2Vec2(0, -10));
    EXPECT_TRUE(world.GetAllowSleeping());
    EXPECT_TRUE(world.GetWarmStarting());
    EXPECT_TRUE(world.GetContinuousPhysics());
    EXPECT_FALSE(world.GetSubStepping());
    EXPECT_TRUE(world.GetAutoClearForces());
    world.SetWarmStarting(false);
    world.SetContinuousPhysics(false);
    world.SetSubStepping(true);
    world.SetAutoClearForces(false);
    world.SetGravity(b2Vec2(1, 2));
    EXPECT_FALSE(world.GetWarmStarting());
    EXPECT_FALSE(world.GetContinuousPhysics());
    EXPECT_TRUE(world.GetSubStepping());
    EXPECT_FALSE(world.GetAutoClearForces());
    EXPECT_EQ(world.GetGravity(), b2Vec2(1, 2));
    // Forces persist across steps without auto-clear.
    b2Body* body = MakeDynamicCircle(world, 0, 0, 1);
    body->ApplyForceToCenter(b2Vec2(10, 0));
    world.Step(kDt, 8, 3);
    world.Step(kDt, 8, 3);
    world.ClearForces();
    const b2Vec2 v = body->GetLinearVelocity();
    world.SetGravity(b2Vec2());
    world.Step(kDt, 8, 3);
    EXPECT_EQ(body->GetLinearVelocity(), v);
    // Disallowing sleep wakes everything.
    body->SetAwake(false);
    world.SetAllowSleeping(false);
    EXPECT_TRUE(body->IsAwake());
}

// Auto-clear skips the walk of the bodies while no body can hold a force, so every way a force
// arrives must be noticed: the three Apply calls and both kinds of restore. In zero gravity a
// force changes the velocity in the step it was applied before, and in no later one.
TEST(WorldApi, EveryForceIsClearedAfterTheStepThatUsesIt) {
    const auto build = [](b2World& w) {
        b2Body* b = MakeDynamicBox(w, 0, 0, Fixed(0.5), Fixed(0.5));
        w.Step(kDt, 8, 3);  // a step with no force: the world knows none is held
        return b;
    };
    // Steps twice and expects the first step alone to have moved the body on.
    const auto expectUsedOnce = [](b2World& w, b2Body* b, const char* how) {
        const b2Vec2 v0 = b->GetLinearVelocity();
        const Fixed w0 = b->GetAngularVelocity();
        w.Step(kDt, 8, 3);
        const b2Vec2 v1 = b->GetLinearVelocity();
        const Fixed w1 = b->GetAngularVelocity();
        EXPECT_TRUE(v1 != v0 || w1 != w0) << how << ": the force did not act";
        w.Step(kDt, 8, 3);
        EXPECT_EQ(b->GetLinearVelocity(), v1) << how << ": the force acted again";
        EXPECT_EQ(b->GetAngularVelocity(), w1) << how << ": the torque acted again";
    };

    b2World world(b2Vec2(0, 0));
    b2Body* body = build(world);
    body->ApplyForce(b2Vec2(0, 3), body->GetWorldPoint(b2Vec2(Fixed(0.5), 0)));
    expectUsedOnce(world, body, "ApplyForce");
    body->ApplyForceToCenter(b2Vec2(2, 0));
    expectUsedOnce(world, body, "ApplyForceToCenter");
    body->ApplyTorque(Fixed(0.25));
    expectUsedOnce(world, body, "ApplyTorque");

    // A snapshot taken with a force held, restored into a world that holds none.
    body->ApplyForceToCenter(b2Vec2(-4, 1));
    const auto saved = world.Save();
    b2World restored(b2Vec2(0, 0));
    build(restored);
    ASSERT_TRUE(restored.Restore(saved).ok());
    expectUsedOnce(restored, restored.GetBodyList(), "a restored snapshot");

    // A frame taken with a force held, restored after the step that cleared it.
    body->ApplyForceToCenter(b2Vec2(1, 5));
    b2WorldFrame frame;
    world.SaveFrame(frame);
    world.Step(kDt, 8, 3);
    ASSERT_TRUE(world.RestoreFrame(frame).ok());
    expectUsedOnce(world, body, "a restored frame");
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

struct CountingDraw : b2Draw {
    void DrawPolygon(const b2Vec2*, int32, const b2Color&) override { ++polygons; }
    void DrawSolidPolygon(const b2Vec2*, int32 n, const b2Color&) override {
        ++solidPolygons;
        vertices += n;
    }
    void DrawCircle(const b2Vec2&, Fixed, const b2Color&) override { ++circles; }
    void DrawSolidCircle(const b2Vec2&, Fixed, const b2Vec2&, const b2Color&) override { ++solidCircles; }
    void DrawSegment(const b2Vec2&, const b2Vec2&, const b2Color&) override { ++segments; }
    void DrawTransform(const b2Transform&) override { ++transforms; }
    int polygons = 0, solidPolygons = 0, vertices = 0, circles = 0, solidCircles = 0, segments = 0, transforms = 0;
};

TEST(WorldApi, DebugDrawFollowsFlags) {
    b2World world(b2Vec2(0, -10));
    MakeStaticBox(world, 0, -1, 10, 1);
    MakeDynamicBox(world, 0, Fixed(0.52), Fixed(0.5), Fixed(0.5));
    MakeDynamicCircle(world, 3, Fixed(0.52), Fixed(0.5));
    world.Step(kDt, 8, 3);
    CountingDraw draw;
    world.SetDebugDraw(&draw);
    world.DrawDebugData();  // no flags: nothing
    EXPECT_EQ(draw.solidPolygons + draw.solidCircles + draw.polygons + draw.transforms + draw.segments, 0);
    draw.SetFlags(b2Draw::e_shapeBit | b2Draw::e_aabbBit | b2Draw::e_centerOfMassBit | b2Draw::e_pairBit);
    world.DrawDebugData();
    EXPECT_EQ(draw.solidPolygons, 2);
    EXPECT_EQ(draw.vertices, 8);
    EXPECT_EQ(draw.solidCircles, 1);
    EXPECT_EQ(draw.polygons, 3);    // one fat AABB per proxy
    EXPECT_EQ(draw.transforms, 3);  // one frame per body
    EXPECT_EQ(draw.segments, world.GetContactCount());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
