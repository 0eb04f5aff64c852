// Test 1: the manual's Hello World against float Box2D 2.4.1 at lockbox's real time step.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "Box2DFloat.h"  // float Box2D without its constant macros
#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

struct Pose {
    double x, y, angle;
};

std::vector<Pose> RunFloatHelloWorld() {
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

    std::vector<Pose> out;
    const float dt = static_cast<float>(lockbox::test::kDtDouble);  // 1092/65536 exactly
    for (int i = 0; i < 60; ++i) {
        world.Step(dt, 6, 2);
        out.push_back({body->GetPosition().x, body->GetPosition().y, body->GetAngle()});
    }
    return out;
}

}  // namespace LOCKBOX_TEST_FILE

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

std::vector<Pose> RunLockboxHelloWorld() {
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

    std::vector<Pose> out;
    for (int i = 0; i < 60; ++i) {
        world.Step(kDt, 6, 2);
        out.push_back(
            {body->GetPosition().x.ToDouble(), body->GetPosition().y.ToDouble(), body->GetAngle().ToDouble()});
    }
    return out;
}

TEST(HelloWorld, MatchesFloatBox2DWithinOneCentimetrePerValue) {
    const std::vector<Pose> ref = RunFloatHelloWorld();
    const std::vector<Pose> got = RunLockboxHelloWorld();
    ASSERT_EQ(ref.size(), 60u);
    ASSERT_EQ(got.size(), 60u);
    double worst = 0;
    for (size_t i = 0; i < ref.size(); ++i) {
        EXPECT_NEAR(got[i].x, ref[i].x, 0.01) << "step " << i;
        EXPECT_NEAR(got[i].y, ref[i].y, 0.01) << "step " << i;
        EXPECT_NEAR(got[i].angle, ref[i].angle, 0.01) << "step " << i;
        worst = std::max({worst, std::fabs(got[i].x - ref[i].x), std::fabs(got[i].y - ref[i].y),
                          std::fabs(got[i].angle - ref[i].angle)});
    }
    // The manual's last line.
    EXPECT_NEAR(got.back().y, 1.01, 0.005);
    RecordProperty("worst_abs_diff_um", static_cast<int>(worst * 1e6));
    std::printf("hello world worst |lockbox - float| = %.6f\n", worst);
}

TEST(HelloWorld, IsBitReproducible) {
    const std::vector<Pose> a = RunLockboxHelloWorld();
    const std::vector<Pose> b = RunLockboxHelloWorld();
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].x, b[i].x);
        EXPECT_EQ(a[i].y, b[i].y);
        EXPECT_EQ(a[i].angle, b[i].angle);
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
