// The hand-written scene files (scenes/files/handmade/) cover every body, fixture,
// shape and joint field of the format, R.U.B.E.'s hexadecimal floats and the gear joint's
// second pass. Each loads, keeps its hash through a save and load, and its step hashes are
// golden (tests/golden/hashes.txt, checked by the golden-hash test on every architecture).
#include <gtest/gtest.h>

#include "SceneFileTestUtil.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::scenefile::test {
namespace LOCKBOX_TEST_FILE {

class HandmadeFiles : public ::testing::TestWithParam<std::string> {};

TEST_P(HandmadeFiles, LoadSaveLoadKeepsTheHash) {
    const std::string text = ReadText(SourcePath("scenes/files/handmade/" + GetParam() + ".json"));
    ASSERT_FALSE(text.empty());
    SceneMetadata meta;
    SceneResult r;
    auto world = LoadSceneWorld(text, &r, &meta);
    ASSERT_TRUE(world) << r.Describe();
    const std::string saved = SaveScene(*world, &meta);
    SceneMetadata again;
    auto reloaded = LoadSceneWorld(saved, &r, &again);
    ASSERT_TRUE(reloaded) << r.Describe();
    EXPECT_EQ(b2WorldHash(*reloaded), b2WorldHash(*world));
    EXPECT_EQ(SaveScene(*reloaded, &again), saved);
    EXPECT_EQ(again.images, meta.images);
    EXPECT_EQ(again.worldInfo, meta.worldInfo);
    // The files are meant as sane scenes: ten seconds without reaching a numeric limit, and
    // every body still inside the world.
    for (int i = 0; i < 600; ++i) {
        world->Step(meta.step.TimeStep(), meta.step.VelocityIterationsOr(), meta.step.PositionIterationsOr());
    }
    EXPECT_EQ(world->GetSaturationCount(), 0u);
    for (const b2Body* b = world->GetBodyList(); b; b = b->GetNext()) EXPECT_FALSE(b->IsOutOfBounds());
}

INSTANTIATE_TEST_SUITE_P(Files, HandmadeFiles, ::testing::Values("bodies", "shapes", "joints", "rube_bridge"),
                         [](const auto& p) { return p.param; });

TEST(HandmadeFiles, FieldsArriveWhereTheyBelong) {
    SceneMetadata meta;
    SceneResult r;
    auto w = LoadSceneWorld(ReadText(SourcePath("scenes/files/handmade/bodies.json")), &r, &meta);
    ASSERT_TRUE(w) << r.Describe();
    using lockbox::literals::operator""_fx;
    EXPECT_EQ(w->GetGravity(), b2Vec2(0, Fixed::FromRaw(-642908)));  // -9.81f, 0xC11CF5C3
    EXPECT_EQ(meta.step, (StepSettings{60, 8, 3}));
    EXPECT_EQ(meta.worldInfo.properties.Get<std::string>("title", ""), "Every body field");
    EXPECT_EQ(meta.worldInfo.properties.Get<CustomColor>("sky", {}), (CustomColor{40, 60, 200, 255}));
    b2Body* crate = meta.GetBodyByName(*w, "crate");
    ASSERT_NE(crate, nullptr);
    EXPECT_EQ(crate->GetAngle(), 0.25_fx);
    EXPECT_EQ(crate->GetLinearDamping(), 0.1_fx);
    EXPECT_EQ(meta.FindBody(*crate)->path, "props/");
    EXPECT_EQ(meta.GetBodyByCustom(*w, "hit points", 30), crate);
    b2Body* sleeper = meta.GetBodyByName(*w, "sleeper");
    EXPECT_FALSE(sleeper->IsAwake());           // absent "awake" is false
    EXPECT_TRUE(sleeper->IsSleepingAllowed());  // absent "allowSleep" is true
    EXPECT_FALSE(meta.GetBodyByName(*w, "ghost")->IsActive());
    EXPECT_TRUE(meta.GetBodyByName(*w, "bullet")->IsBullet());
    EXPECT_TRUE(meta.GetBodyByName(*w, "roller")->IsFixedRotation());
    EXPECT_EQ(meta.GetBodyByName(*w, "balloon")->GetGravityScale(), -0.25_fx);
    EXPECT_EQ(meta.GetBodyByName(*w, "platform")->GetType(), b2_kinematicBody);
    EXPECT_EQ(meta.GetBodyByName(*w, "heavy")->GetMass(), Wide(10));
    b2Body* spinner = meta.GetBodyByName(*w, "spinner");
    EXPECT_EQ(spinner->GetLinearVelocity(), b2Vec2(0.5_fx, 0));  // the file's value, the centre's
    b2Body* hexbox = meta.GetBodyByName(*w, "hexbox");
    EXPECT_EQ(hexbox->GetPosition(), b2Vec2(12, 2));
    EXPECT_EQ(hexbox->GetAngularVelocity(), Fixed::FromRaw(-6554));  // -0.1f
    const b2Fixture* f = hexbox->GetFixtureList();
    EXPECT_EQ(f->GetDensity(), Fixed::FromRaw(19661));  // 0.3f = 0.30000001192...
    EXPECT_EQ(f->GetFriction(), 0.5_fx);
    ASSERT_EQ(meta.images.size(), 2u);
    EXPECT_EQ(meta.images[0].body, crate->GetId());
    EXPECT_EQ(meta.images[1].body, -1);
    EXPECT_TRUE(meta.images[1].flip);
    EXPECT_EQ(meta.GetFixtureByName(*w, "floor")->GetFriction(), 0.8_fx);
}

TEST(HandmadeFiles, JointsInFileOrderWithTheGearLast) {
    SceneMetadata meta;
    SceneResult r;
    auto w = LoadSceneWorld(ReadText(SourcePath("scenes/files/handmade/joints.json")), &r, &meta);
    ASSERT_TRUE(w) << r.Describe();
    EXPECT_EQ(w->GetJointCount(), 11);
    // The gear names joints after it: created last (b2dJson's second pass), so it has the
    // last id and heads the world's joint list.
    const b2Joint* newest = w->GetJointList();
    EXPECT_EQ(newest->GetType(), e_gearJoint);
    EXPECT_EQ(newest->GetId(), 10);
    EXPECT_EQ(meta.GetJointByName(*w, "rail (older axis name)")->GetType(), e_prismaticJoint);
    EXPECT_EQ(meta.GetJointByName(*w, "shoulder")->GetId(), 0);
    EXPECT_EQ(meta.FindJoint(*meta.GetJointByName(*w, "shoulder"))->path, "robot/arm/");
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenefile::test
