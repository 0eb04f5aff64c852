// Determinism: identical runs give identical bits; a scene moved by whole metres gives the same
// relative motion (ARCHITECTURE §5), as long as no coordinate changes sign.
#include <vector>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"
#include "FixedPrint.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

struct State {
    std::vector<int32> raws;
};

// A small mixed scene (boxes, circles, a slope) offset by (ox, oy) metres; returns every
// dynamic body's raw position relative to the offset, angle and velocities after 300 steps.
State RunScene(int ox, int oy) {
    b2World world(b2Vec2(0, -10));
    const Fixed fx = ox, fy = oy;
    MakeStaticBox(world, fx, fy - 1, 20, 1);
    MakeStaticBox(world, fx + 6, fy + 2, 3, Fixed(0.2), Fixed(-0.4));
    std::vector<b2Body*> bodies;
    for (int i = 0; i < 6; ++i) {
        bodies.push_back(MakeDynamicBox(world, fx + Fixed::FromRatio(3 * i, 10), fy + Fixed(1) + Fixed(1.1) * Fixed(i),
                                        Fixed(0.4), Fixed(0.3), 1, Fixed(0.5), 0, Fixed::FromRatio(i, 7)));
        bodies.push_back(
            MakeDynamicCircle(world, fx + 6 + Fixed::FromRatio(i, 5), fy + Fixed(4) + Fixed(i), Fixed(0.25)));
    }
    for (int n = 0; n < 300; ++n) world.Step(kDt, 8, 3);
    State s;
    for (b2Body* b : bodies) {
        s.raws.push_back((b->GetPosition().x - fx).Raw());
        s.raws.push_back((b->GetPosition().y - fy).Raw());
        s.raws.push_back(b->GetAngle().Raw());
        s.raws.push_back(b->GetLinearVelocity().x.Raw());
        s.raws.push_back(b->GetLinearVelocity().y.Raw());
        s.raws.push_back(b->GetAngularVelocity().Raw());
    }
    return s;
}

TEST(Determinism, RepeatedRunsAreBitIdentical) { EXPECT_EQ(RunScene(0, 0).raws, RunScene(0, 0).raws); }

TEST(Determinism, WholeMetreTranslationKeepsRelativeMotion) {
    // All coordinates stay positive in both runs, so round-to-nearest (ties away from zero)
    // sees the same fractional parts.
    EXPECT_EQ(RunScene(100, 50).raws, RunScene(1000, 3000).raws);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
