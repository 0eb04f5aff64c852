// Test 7 (heavy): a box resting on the ground, kept awake, for 10 simulated minutes drifts less
// than 1 ULP per minute (NUMERICS stability test 7: catches rounding bias such as floor-mul).
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "../DynamicsTestUtil.h"
#include "FixedPrint.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

void RunCreep(Fixed x0, Fixed angle) {
    b2World world(b2Vec2(0, -10));
    MakeStaticBox(world, 0, -1, 20, 1);
    b2Body* box = MakeDynamicBox(world, x0, Fixed(0.52), Fixed(0.5), Fixed(0.5), 1, Fixed(0.6), 0, angle);
    box->SetSleepingAllowed(false);  // sleeping would hide any creep
    constexpr int kStepsPerMinute = 3600;
    // One minute to settle, then ten measured minutes.
    for (int n = 0; n < kStepsPerMinute; ++n) world.Step(kDt, 8, 3);
    const b2Vec2 start = box->GetPosition();
    const Fixed startAngle = box->GetAngle();
    for (int n = 0; n < 10 * kStepsPerMinute; ++n) world.Step(kDt, 8, 3);
    const b2Vec2 end = box->GetPosition();
    const int32 dx = std::abs(end.x.Raw() - start.x.Raw());
    const int32 dy = std::abs(end.y.Raw() - start.y.Raw());
    const int32 da = std::abs(box->GetAngle().Raw() - startAngle.Raw());
    std::printf("creep over 10 min (x0 %.3f): dx %d ULP, dy %d ULP, angle %d ULP\n", x0.ToDouble(), dx, dy, da);
    EXPECT_LT(dx, 10);
    EXPECT_LT(dy, 10);
    EXPECT_LT(da, 10);
    EXPECT_TRUE(box->IsAwake());
}

TEST(Creep, RestingBoxDriftsLessThanOneUlpPerMinute) { RunCreep(0, 0); }

TEST(Creep, OffCentreRestingBoxDriftsLessThanOneUlpPerMinute) { RunCreep(Fixed(3.3), 0); }

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
