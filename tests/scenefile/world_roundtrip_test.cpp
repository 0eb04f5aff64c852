// Round trips of what the scene library does not use: every body flag and setting, the
// mass-data override, rotated boxes, every shape with ghost vertices, every joint type with
// oblique axes and rotated bodies, names, custom properties and images. Saving and loading
// keeps the state hash, the metadata and the text.
#include <gtest/gtest.h>

#include "lockbox/lockbox.h"
#include "lockbox/scenefile/SceneFile.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::scenefile {
namespace LOCKBOX_TEST_FILE {

using lockbox::literals::operator""_fx;

b2Body* Box(b2World& w, b2BodyType type, b2Vec2 p, Fixed angle, Fixed hx, Fixed hy, Fixed boxAngle = Fixed(),
            bool active = true) {
    b2BodyDef bd;
    bd.active = active;
    bd.type = type;
    bd.position = p;
    bd.angle = angle;
    b2Body* b = w.CreateBody(&bd);
    b2PolygonShape shape;
    shape.SetAsBox(hx, hy, b2Vec2(0.1_fx, -0.05_fx), boxAngle);
    b2FixtureDef fd;
    fd.shape = &shape;
    fd.density = 1.5_fx;
    b->CreateFixture(&fd);
    return b;
}

// A world that uses every field the format has.
std::unique_ptr<b2World> MakeEverything(SceneMetadata& meta) {
    auto world = std::make_unique<b2World>(b2Vec2(0.5_fx, -9.81_fx));
    b2World& w = *world;
    w.SetAllowSleeping(false);
    w.SetWarmStarting(false);
    w.SetSubStepping(true);
    w.SetAutoClearForces(false);

    b2BodyDef gd;
    b2Body* ground = w.CreateBody(&gd);
    {
        b2EdgeShape edge;
        edge.Set(b2Vec2(-20, 0), b2Vec2(20, 0));
        edge.m_vertex0.Set(-25, 1);
        edge.m_hasVertex0 = true;
        edge.m_vertex3.Set(25, -1);
        edge.m_hasVertex3 = true;
        b2FixtureDef fd;
        fd.shape = &edge;
        fd.friction = 0.7_fx;
        fd.restitution = 0.1_fx;
        fd.filter.categoryBits = 0x0004;
        fd.filter.maskBits = 0x00F3;
        fd.filter.groupIndex = -3;
        meta.Fixture(*ground->CreateFixture(&fd)).name = "floor";
        const b2Vec2 loop[4] = {b2Vec2(-30, 0), b2Vec2(-30, 30), b2Vec2(30, 30), b2Vec2(30, 0)};
        b2ChainShape walls;
        walls.CreateLoop(loop, 4);
        ground->CreateFixture(&walls, 0);
        const b2Vec2 steps[3] = {b2Vec2(-5, 5), b2Vec2(0, 6), b2Vec2(5, 5)};
        b2ChainShape chain;
        chain.CreateChain(steps, 3);
        chain.SetPrevVertex(b2Vec2(-6, 4));
        chain.SetNextVertex(b2Vec2(6, 4));
        b2FixtureDef sensor;
        sensor.shape = &chain;
        sensor.isSensor = true;
        ground->CreateFixture(&sensor);
    }
    meta.Body(*ground).name = "ground";

    b2Body* a = Box(w, b2_dynamicBody, b2Vec2(-3, 4), 0.3_fx, 0.5_fx, 0.25_fx, 0.4_fx);
    a->SetAngularVelocity(2.5_fx);
    a->SetLinearVelocity(b2Vec2(1.25_fx, -0.5_fx));
    a->SetLinearDamping(0.2_fx);
    a->SetAngularDamping(0.05_fx);
    a->SetGravityScale(-0.5_fx);
    a->SetBullet(true);
    b2Body* b = Box(w, b2_dynamicBody, b2Vec2(-1, 4.5_fx), -1.1_fx, 0.3_fx, 0.6_fx);
    b->SetFixedRotation(true);
    b->SetSleepingAllowed(false);
    b2Body* c = Box(w, b2_dynamicBody, b2Vec2(2, 3), 2.9_fx, 0.4_fx, 0.4_fx);
    b2MassData md;
    md.mass = Wide(3);
    md.center.Set(0.1_fx, 0.2_fx);
    md.I = Wide(2);
    c->SetMassData(&md);
    b2CircleShape circle(0.35_fx, b2Vec2(0.2_fx, 0.1_fx));
    c->CreateFixture(&circle, 2);  // after the override: the fixture's mass resets it
    b2Body* k = Box(w, b2_kinematicBody, b2Vec2(5, 8), 0.5_fx, 1, 0.1_fx);
    k->SetLinearVelocity(b2Vec2(-1, 0));
    k->SetAngularVelocity(0.25_fx);
    b2Body* asleep = Box(w, b2_dynamicBody, b2Vec2(8, 1), 0, 0.5_fx, 0.5_fx);
    asleep->SetAwake(false);
    // Created inactive: deactivating a body later frees its broad-phase nodes, a history the
    // file does not hold (the loaded world's tree would differ).
    b2Body* inactive = Box(w, b2_dynamicBody, b2Vec2(10, 1), 0, 0.5_fx, 0.5_fx, 0, false);
    b2Body* d = Box(w, b2_dynamicBody, b2Vec2(-6, 6), 0.7_fx, 0.2_fx, 0.8_fx);
    b2Body* e = Box(w, b2_dynamicBody, b2Vec2(-8, 6), -0.2_fx, 0.5_fx, 0.3_fx);

    meta.Body(*a).name = "hero";
    meta.Body(*a).properties.Set("lives", 3);
    meta.Body(*a).properties.Set("speed", 2.5_fx);
    meta.Body(*a).properties.Set("speed", 7);
    meta.Body(*a).properties.Set("label", std::string("player \"one\""));
    meta.Body(*a).properties.Set("spawn", b2Vec2(-3, 4));
    meta.Body(*a).properties.Set("boss", false);
    meta.Body(*a).properties.Set("tint", CustomColor{10, 20, 30, 40});
    meta.Body(*b).path = "enemies/";
    meta.Body(*c).name = "tab\there, new\nline, bell\x07, slash\\ and \"quotes\" in UTF-8: \xc3\xa9t\xc3\xa9";
    meta.worldInfo.properties.Set("level", 4);
    meta.step = {60, 8, 3};

    b2RevoluteJointDef rj;
    rj.Initialize(a, b, b2Vec2(-2, 4.2_fx));
    rj.enableLimit = true;
    rj.lowerAngle = -0.5_fx;
    rj.upperAngle = 0.75_fx;
    rj.enableMotor = true;
    rj.motorSpeed = 1.5_fx;
    rj.maxMotorTorque = 10;
    b2Joint* revolute = w.CreateJoint(&rj);
    meta.Joint(*revolute).name = "elbow";
    b2PrismaticJointDef pj;
    pj.Initialize(ground, d, b2Vec2(-6, 6), b2Vec2(3, 4.1_fx));
    pj.enableLimit = true;
    pj.lowerTranslation = -1;
    pj.upperTranslation = 2.5_fx;
    pj.enableMotor = true;
    pj.maxMotorForce = 40;
    pj.motorSpeed = -0.3_fx;
    pj.collideConnected = true;
    b2Joint* prismatic = w.CreateJoint(&pj);
    b2GearJointDef gj;
    gj.bodyA = a;
    gj.bodyB = d;
    gj.joint1 = revolute;
    gj.joint2 = prismatic;
    gj.ratio = -0.7_fx;
    w.CreateJoint(&gj);
    b2DistanceJointDef dj;
    dj.Initialize(c, e, b2Vec2(2.1_fx, 3), b2Vec2(-8, 6.3_fx));
    dj.frequencyHz = 4;
    dj.dampingRatio = 0.5_fx;
    w.CreateJoint(&dj);
    b2PulleyJointDef puj;
    puj.Initialize(b, e, b2Vec2(-1, 12), b2Vec2(-8, 12), b2Vec2(-1.1_fx, 4.9_fx), b2Vec2(-8, 6.2_fx), 1.5_fx);
    w.CreateJoint(&puj);
    b2MouseJointDef mj;
    mj.bodyA = ground;
    mj.bodyB = c;
    mj.target.Set(2.1_fx, 3.1_fx);
    mj.maxForce = Wide(500);
    mj.frequencyHz = 3;
    mj.dampingRatio = 0.9_fx;
    auto* mouse = static_cast<b2MouseJoint*>(w.CreateJoint(&mj));
    mouse->SetTarget(b2Vec2(2.5_fx, 4));
    b2WheelJointDef wj;
    wj.Initialize(k, asleep, b2Vec2(8, 1), b2Vec2(0.6_fx, 0.8_fx));
    wj.enableMotor = true;
    wj.motorSpeed = 3;
    wj.maxMotorTorque = 20;
    wj.frequencyHz = 4.5_fx;
    wj.dampingRatio = 0.8_fx;
    w.CreateJoint(&wj);
    b2WeldJointDef weld;
    weld.Initialize(d, e, b2Vec2(-7, 6));
    weld.frequencyHz = 2;
    weld.dampingRatio = 0.3_fx;
    w.CreateJoint(&weld);
    b2FrictionJointDef fj;
    fj.Initialize(ground, b, b2Vec2(-1, 4));
    fj.maxForce = 5;
    fj.maxTorque = 1.5_fx;
    w.CreateJoint(&fj);
    b2RopeJointDef rope;
    rope.bodyA = a;
    rope.bodyB = inactive;
    rope.localAnchorA.Set(0.1_fx, 0.2_fx);
    rope.localAnchorB.Set(-0.3_fx, 0);
    rope.maxLength = 14;
    w.CreateJoint(&rope);

    ImageDesc image;
    image.body = a->GetId();
    image.file = "hero.png";
    image.center.Set(0.1_fx, 0);
    image.angle = 0.2_fx;
    image.scale = 1.25_fx;
    image.aspectScale = 0.5_fx;
    image.flip = true;
    image.opacity = 0.8_fx;
    image.filter = 0;
    image.renderOrder = 3;
    image.colorTint = {255, 128, 0, 200};
    image.corners = {b2Vec2(-1, -1), b2Vec2(1, -1), b2Vec2(1, 1), b2Vec2(-1, 1)};
    image.glVertexPointer = {-1, -1, 1, -1, 1, 1};
    image.glTexCoordPointer = {0, 0, 1, 0, 1, 1};
    image.glDrawElements = {0, 1, 2};
    image.info.name = "hero image";
    image.info.properties.Set("layer", std::string("front"));
    meta.images.push_back(image);
    return world;
}

TEST(WorldRoundTrip, EveryFieldKeepsTheHash) {
    SceneMetadata meta;
    auto world = MakeEverything(meta);
    const std::string text = SaveScene(*world, &meta);

    SceneMetadata loadedMeta;
    SceneResult r;
    auto loaded = LoadSceneWorld(text, &r, &loadedMeta);
    ASSERT_TRUE(loaded) << r.Describe();
    const b2HashMismatch diff = b2CompareHashReports(b2WorldHashDetailed(*loaded), b2WorldHashDetailed(*world));
    EXPECT_EQ(diff.category, b2HashCategory::e_count)
        << "first difference: " << b2HashCategoryName(diff.category) << ", body " << diff.bodyId;
    EXPECT_EQ(SaveScene(*loaded, &loadedMeta), text);
    EXPECT_EQ(loadedMeta.images, meta.images);
    EXPECT_EQ(loadedMeta.worldInfo, meta.worldInfo);
    EXPECT_EQ(loadedMeta.step, meta.step);

    for (int i = 0; i < 30; ++i) {
        world->Step(Fixed::FromRatio(1, 60), 8, 3);
        loaded->Step(Fixed::FromRatio(1, 60), 8, 3);
    }
    EXPECT_EQ(b2WorldHash(*loaded), b2WorldHash(*world));
}

TEST(WorldRoundTrip, LookupsByNameAndProperty) {
    SceneMetadata meta;
    auto world = MakeEverything(meta);
    SceneMetadata m;
    SceneResult r;
    auto w = LoadSceneWorld(SaveScene(*world, &meta), &r, &m);
    ASSERT_TRUE(w) << r.Describe();
    b2Body* hero = m.GetBodyByName(*w, "hero");
    ASSERT_NE(hero, nullptr);
    EXPECT_EQ(hero->GetPosition(), b2Vec2(-3, 4));
    EXPECT_EQ(m.GetBodyName(*hero), "hero");
    EXPECT_EQ(m.GetBodyByCustom(*w, "lives", 3), hero);
    EXPECT_EQ(m.GetBodyByCustom(*w, "lives", 4), nullptr);
    EXPECT_EQ(m.GetBodyByCustom(*w, "speed", 2.5_fx), hero);
    EXPECT_EQ(m.GetBodyByCustom(*w, "speed", 7), hero);
    EXPECT_EQ(m.GetBodiesByCustom(*w, "tint", CustomColor{10, 20, 30, 40}).size(), 1u);
    const ObjectInfo* info = m.FindBody(*hero);
    ASSERT_NE(info, nullptr);
    EXPECT_EQ(info->properties.Get<std::string>("label", ""), "player \"one\"");
    EXPECT_EQ(info->properties.Get<bool>("boss", true), false);
    EXPECT_EQ(info->properties.Get<b2Vec2>("spawn", b2Vec2()), b2Vec2(-3, 4));
    EXPECT_EQ(m.GetJointByName(*w, "elbow")->GetType(), e_revoluteJoint);
    EXPECT_EQ(m.GetFixtureByName(*w, "floor")->GetBody(), m.GetBodyByName(*w, "ground"));
    EXPECT_EQ(m.GetBodiesByName(*w, "nobody").size(), 0u);
    ASSERT_EQ(m.GetImagesByName("hero image").size(), 1u);
    EXPECT_EQ(m.GetImagesByName("hero image")[0]->body, hero->GetId());
}

TEST(WorldRoundTrip, LoadingAddsToAWorldThatHasBodies) {
    SceneMetadata meta;
    auto source = MakeEverything(meta);
    const std::string text = SaveScene(*source, &meta);
    b2World w(b2Vec2(0, -10));
    b2BodyDef bd;
    w.CreateBody(&bd);
    SceneMetadata m;
    ASSERT_TRUE(LoadScene(text, w, &m));
    EXPECT_EQ(w.GetBodyCount(), source->GetBodyCount() + 1);
    EXPECT_EQ(w.GetJointCount(), source->GetJointCount());
    EXPECT_EQ(w.GetGravity(), source->GetGravity());
    ASSERT_NE(m.GetBodyByName(w, "hero"), nullptr);
    EXPECT_EQ(m.GetBodyByName(w, "hero")->GetPosition(), b2Vec2(-3, 4));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenefile
