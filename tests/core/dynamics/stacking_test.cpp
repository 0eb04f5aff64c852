// Test 3: a 10-box stack settles and sleeps, a base-20 pyramid holds, and a bullet at the
// speed cap does not pass a thin static wall.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"
#include "FixedPrint.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

TEST(Stacking, TenBoxStackSettlesAndSleeps) {
    b2World world(b2Vec2(0, -10));
    MakeStaticBox(world, 0, -1, 20, 1);
    std::vector<b2Body*> boxes;
    for (int i = 0; i < 10; ++i) {
        // 1 m boxes with a small gap (the polygon skins touch at 0.02 m).
        boxes.push_back(
            MakeDynamicBox(world, 0, Fixed(0.5) + Fixed(1.02) * Fixed(i), Fixed(0.5), Fixed(0.5), 1, Fixed(0.6)));
    }
    std::vector<b2Vec2> start;
    for (b2Body* b : boxes) start.push_back(b->GetPosition());

    int sleptAt = -1;
    for (int n = 1; n <= 1200 && sleptAt < 0; ++n) {
        world.Step(kDt, 8, 3);
        bool allAsleep = true;
        for (b2Body* b : boxes) allAsleep = allAsleep && !b->IsAwake();
        if (allAsleep) sleptAt = n;
    }
    ASSERT_GT(sleptAt, 0) << "stack never went to sleep in 20 s";
    std::printf("10-box stack asleep after %d steps\n", sleptAt);
    double worstDrift = 0;
    for (size_t i = 0; i < boxes.size(); ++i) {
        const b2Vec2 p = boxes[i]->GetPosition();
        // Horizontal drift and rotation must stay tiny. Vertically each contact layer rests at
        // the two polygon skins (0.02 m) minus the allowed penetration (linearSlop 0.005 m).
        const double dx = std::fabs((p.x - start[i].x).ToDouble());
        worstDrift = std::max(worstDrift, dx);
        EXPECT_LT(dx, 0.01) << "box " << i;
        EXPECT_LT(std::fabs(boxes[i]->GetAngle().ToDouble()), 0.01) << "box " << i;
        // Each contact layer rests between (skins - slop) and the skins: 0.015..0.02 m.
        const double restLow = 0.5 + static_cast<double>(i) + 0.015 * static_cast<double>(i + 1);
        const double restHigh = 0.5 + static_cast<double>(i) + 0.020 * static_cast<double>(i + 1);
        EXPECT_GT(p.y.ToDouble(), restLow - 0.01) << "box " << i;
        EXPECT_LT(p.y.ToDouble(), restHigh + 0.01) << "box " << i;
    }
    std::printf("10-box stack worst horizontal drift %.6f m\n", worstDrift);
    // Asleep means nothing moves any more.
    const b2Vec2 top = boxes.back()->GetPosition();
    for (int n = 0; n < 60; ++n) world.Step(kDt, 8, 3);
    EXPECT_EQ(boxes.back()->GetPosition(), top);
}

TEST(Stacking, Base20PyramidHoldsFor600Steps) {
    b2World world(b2Vec2(0, -10));
    MakeStaticBox(world, 0, -1, 40, 1);
    std::vector<b2Body*> boxes;
    const Fixed half = Fixed(0.5);
    for (int row = 0; row < 20; ++row) {
        const int count = 20 - row;
        for (int i = 0; i < count; ++i) {
            const Fixed x = Fixed(1.05) * Fixed(i) - Fixed::FromRatio(105 * (count - 1), 200);
            const Fixed y = half + Fixed(1.02) * Fixed(row);
            boxes.push_back(MakeDynamicBox(world, x, y, half, half, 1, Fixed(0.6)));
        }
    }
    ASSERT_EQ(boxes.size(), 210u);
    std::vector<b2Vec2> start;
    for (b2Body* b : boxes) start.push_back(b->GetPosition());
    std::vector<b2Vec2> mid;
    for (int n = 0; n < 600; ++n) {
        world.Step(kDt, 8, 3);
        if (n == 299) {
            for (b2Body* b : boxes) mid.push_back(b->GetPosition());
        }
    }
    double worstLate = 0;
    for (size_t i = 0; i < boxes.size(); ++i) {
        worstLate = std::max(worstLate, (boxes[i]->GetPosition() - mid[i]).Length().ToDouble());
    }
    std::printf("pyramid: worst motion between steps 300 and 600: %.5f m\n", worstLate);
    // Holding means settled: nothing moves more than 1 cm in the second half.
    EXPECT_LT(worstLate, 0.01);
    double worstX = 0, worstY = 0;
    for (size_t i = 0; i < boxes.size(); ++i) {
        const b2Vec2 d = boxes[i]->GetPosition() - start[i];
        worstX = std::max(worstX, std::fabs(d.x.ToDouble()));
        worstY = std::max(worstY, std::fabs(d.y.ToDouble()));
    }
    std::printf("pyramid after 600 steps: worst |dx| %.4f m, worst |dy| %.4f m\n", worstX, worstY);
    // Holding: no box moved sideways by more than 10 cm (the initial 5 cm gaps may close) and no
    // row collapsed (settling through 20 layers of skins and slop stays below 0.5 m).
    EXPECT_LT(worstX, 0.1);
    EXPECT_LT(worstY, 0.5);
}

// Fires a small box at the speed cap (maxTranslation per step, 2 m * 60 Hz = 120 m/s) at a
// 0.1 m thick static wall and returns the largest x reached by its centre.
double FireAtWall(bool bullet, bool continuous) {
    b2World world(b2Vec2(0, 0));
    world.SetContinuousPhysics(continuous);
    MakeStaticBox(world, 10, 0, Fixed(0.05), 5);  // wall faces at x = 9.95 and 10.05
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.bullet = bullet;
    // From x = 0.9 the discrete positions are 8.9 then 10.9: straight over the wall.
    bd.position.Set(Fixed(0.9), Fixed(0.3));
    b2Body* shot = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(Fixed(0.1), Fixed(0.1));
    shot->CreateFixture(&box, 1);
    shot->SetLinearVelocity(b2Vec2(120, 0));
    double maxX = -100;
    for (int n = 0; n < 60; ++n) {
        world.Step(kDt, 8, 3);
        maxX = std::max(maxX, shot->GetPosition().x.ToDouble());
    }
    return maxX;
}

TEST(Stacking, BulletAtMaxSpeedDoesNotPassThinWall) {
    // The shot's right face must stay left of the wall's far face (10.05) - it may not even
    // reach the middle of the wall.
    const double bulletMax = FireAtWall(true, true);
    const double dynamicMax = FireAtWall(false, true);
    std::printf("shot max x: bullet %.4f, plain dynamic %.4f, no CCD %.4f\n", bulletMax, dynamicMax,
                FireAtWall(false, false));
    EXPECT_LT(bulletMax + 0.1, 10.0);
    EXPECT_LT(dynamicMax + 0.1, 10.0);
    // Control: without continuous collision the same shot does pass.
    EXPECT_GT(FireAtWall(false, false), 10.5);
}

TEST(Stacking, BulletDoesNotTunnelThroughThinDynamicBody) {
    b2World world(b2Vec2(0, 0));
    // A thin dynamic plank held in place by its huge mass.
    b2Body* plank = MakeDynamicBox(world, 10, 0, Fixed(0.05), 3, 1000);
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.bullet = true;
    bd.position.Set(0, 0);
    b2Body* shot = world.CreateBody(&bd);
    b2CircleShape c;
    c.m_radius = Fixed(0.1);
    shot->CreateFixture(&c, 1);
    shot->SetLinearVelocity(b2Vec2(120, 0));
    double maxX = -100;
    for (int n = 0; n < 30; ++n) {
        world.Step(kDt, 8, 3);
        maxX = std::max(maxX, (shot->GetPosition().x - plank->GetPosition().x).ToDouble());
    }
    EXPECT_LT(maxX, 0.0);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
