// World bounds (ARCHITECTURE §5) and bounded angles.
#include <vector>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"
#include "FixedPrint.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

struct BoundaryRecorder : b2BoundaryListener {
    void Violation(b2Body* body) override { ids.push_back(body->GetId()); }
    std::vector<int32> ids;
};

TEST(Bounds, BodyLeavingTheWorldIsFrozenAndReported) {
    b2World world(b2Vec2(0, -10));
    b2AABB bounds;
    bounds.lowerBound.Set(-100, -100);
    bounds.upperBound.Set(100, 100);
    world.SetWorldBounds(bounds);
    BoundaryRecorder recorder;
    world.SetBoundaryListener(&recorder);
    b2Body* faller = MakeDynamicCircle(world, 0, 0, Fixed(0.5));
    b2Body* stayer = MakeDynamicCircle(world, 10, 0, Fixed(0.5));
    stayer->SetGravityScale(0);
    int n = 0;
    while (recorder.ids.empty() && n < 1000) {
        world.Step(kDt, 8, 3);
        ++n;
    }
    ASSERT_EQ(recorder.ids.size(), 1u);
    EXPECT_EQ(recorder.ids[0], faller->GetId());
    EXPECT_TRUE(faller->IsOutOfBounds());
    EXPECT_FALSE(faller->IsActive());
    EXPECT_EQ(faller->GetLinearVelocity(), b2Vec2());
    EXPECT_LT(faller->GetPosition().y, Fixed(-100));
    EXPECT_GT(faller->GetPosition().y, Fixed(-103));  // at most one step beyond
    EXPECT_FALSE(stayer->IsOutOfBounds());
    // Frozen: no more reports, no motion.
    const b2Vec2 p = faller->GetPosition();
    for (int k = 0; k < 10; ++k) world.Step(kDt, 8, 3);
    EXPECT_EQ(recorder.ids.size(), 1u);
    EXPECT_EQ(faller->GetPosition(), p);
    // The application may bring it back.
    faller->SetTransform(b2Vec2(0, 0), 0);
    faller->SetActive(true);
    EXPECT_FALSE(faller->IsOutOfBounds());
    world.Step(kDt, 8, 3);
    EXPECT_LT(faller->GetLinearVelocity().y, Fixed());
}

TEST(Bounds, DefaultBoundsAre16000Metres) {
    b2World world(b2Vec2(0, 0));
    EXPECT_EQ(world.GetWorldBounds().upperBound, b2Vec2(16000, 16000));
    EXPECT_EQ(world.GetWorldBounds().lowerBound, b2Vec2(-16000, -16000));
}

TEST(Bounds, AnglesStayWrappedAndRelativeMotionIsExact) {
    b2World world(b2Vec2(0, 0));
    b2Body* wheel = MakeDynamicCircle(world, 0, 0, Fixed(0.5));
    wheel->SetSleepingAllowed(false);
    wheel->SetAngularVelocity(50);
    const Fixed pi = Fixed::FromRaw(205887);
    Fixed previous = wheel->GetAngle();
    int wraps = 0;
    for (int n = 0; n < 6000; ++n) {
        world.Step(kDt, 8, 3);
        const Fixed a = wheel->GetAngle();
        EXPECT_GE(a, -pi);
        EXPECT_LE(a, pi);
        // Each step turns by exactly h * w (rounded once), whatever the wrapping.
        Fixed delta = a - previous;
        if (delta < Fixed()) {
            delta += Fixed::FromRaw(411775);
            ++wraps;
        }
        EXPECT_EQ(delta, kDt * Fixed(50)) << n;
        previous = a;
    }
    EXPECT_GT(wraps, 100);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
