// The world's own pool (SetWorkerCount) takes a step's islands only when sharing them can pay:
// enough work in all, and no island holding more than half of it. The choice is made on the
// step before and changes no bit, so each case also checks the one-worker hashes.

#include <cstdint>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "../dynamics/DynamicsTestUtil.h"
#include "lockbox_internal/WorldInternals.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using test::kDt;
using test::MakeDynamicBox;
using test::MakeStaticBox;

// Columns of boxes resting on one static ground: one island per column.
void Columns(b2World& world, int columns, int height) {
    MakeStaticBox(world, 0, Fixed(-0.5), 200, Fixed(0.5));
    for (int c = 0; c < columns; ++c) {
        for (int k = 0; k < height; ++k)
            MakeDynamicBox(world, Fixed(-190 + 3 * c), Fixed::FromRatio(50 + 100 * k, 100), Fixed(0.5), Fixed(0.5));
    }
}

// A pyramid of touching boxes (one island holding nearly all the work) and a few lone boxes
// beside it (islands of their own).
void PileAndStrays(b2World& world) {
    MakeStaticBox(world, 0, Fixed(-0.5), 200, Fixed(0.5));
    constexpr int kRows = 30;
    for (int row = 0; row < kRows; ++row) {
        for (int k = 0; k < kRows - row; ++k)
            MakeDynamicBox(world, Fixed(-kRows / 2 + k) + Fixed::FromRatio(row, 2),
                           Fixed::FromRatio(50 + 100 * row, 100), Fixed(0.5), Fixed(0.5));
    }
    for (int s = 0; s < 8; ++s) MakeDynamicBox(world, Fixed(40 + 4 * s), Fixed(0.5), Fixed(0.5), Fixed(0.5));
}

struct Outcome {
    std::vector<uint64_t> hashes;
    bool shared = false;  // the pool's choice after the last step
    int64_t work = 0;     // bodies, contacts and joints in the last step's islands
};

Outcome Simulate(const std::function<void(b2World&)>& build, int workers) {
    b2World world(b2Vec2(0, -10));
    world.SetWorkerCount(workers);
    build(world);
    Outcome run;
    for (int i = 0; i < 4; ++i) {
        world.Step(kDt, 8, 3);
        run.hashes.push_back(world.Hash());
    }
    run.shared = test::Internals(world).m_shareIslands;
    const b2Profile& p = world.GetProfile();
    run.work = int64_t{p.bodiesIntegrated} + p.contactConstraints + p.jointConstraints;
    return run;
}

// Steps a scene on one worker and on the world's own pool of two, which must give the same
// hashes; returns the pool's run.
Outcome OnPoolOfTwo(const std::function<void(b2World&)>& build) {
    const Outcome one = Simulate(build, 1);
    Outcome two = Simulate(build, 2);
    EXPECT_EQ(one.hashes, two.hashes);
    return two;
}

TEST(PoolSharing, ManyEqualIslandsGoToThePool) {
    // 64 columns of 10: 640 bodies and 640 contacts in 64 islands.
    const Outcome two = OnPoolOfTwo([](b2World& w) { Columns(w, 64, 10); });
    EXPECT_GE(two.work, 1024);
    EXPECT_TRUE(two.shared);
}

TEST(PoolSharing, LittleWorkStaysOnTheSteppingThread) {
    // 10 columns of 3: 30 bodies and 30 contacts.
    const Outcome two = OnPoolOfTwo([](b2World& w) { Columns(w, 10, 3); });
    EXPECT_LT(two.work, 1024);
    EXPECT_FALSE(two.shared);
}

TEST(PoolSharing, AnIslandHoldingMostOfTheWorkStaysOnTheSteppingThread) {
    // 465 boxes in one pyramid (over a thousand contacts) against 8 lone boxes.
    const Outcome two = OnPoolOfTwo(PileAndStrays);
    EXPECT_GE(two.work, 1024) << "the size rule alone would keep it";
    EXPECT_FALSE(two.shared);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
