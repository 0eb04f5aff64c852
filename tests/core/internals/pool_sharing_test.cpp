// The world's own pool (SetWorkerCount) takes a step's islands only when sharing them can pay:
// enough work in all, and no island holding more than half of it. The choice is made on the
// step before and changes no bit, so each case also checks the one-worker hashes.

#include <cstdint>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/World.h"
#include "lockbox_internal/WorldInternals.h"

namespace lockbox {
namespace {

constexpr Fixed kDt = Fixed::FromRatio(1, 60);

void AddBox(b2World& world, b2BodyType type, Fixed x, Fixed y, Fixed hx, Fixed hy) {
    b2BodyDef bd;
    bd.type = type;
    bd.position.Set(x, y);
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(hx, hy);
    body->CreateFixture(&box, type == b2_dynamicBody ? Fixed(1) : Fixed(0));
}

// Columns of boxes resting on one static ground: one island per column.
void Columns(b2World& world, int columns, int height) {
    AddBox(world, b2_staticBody, 0, Fixed(-0.5), 200, Fixed(0.5));
    for (int c = 0; c < columns; ++c) {
        for (int k = 0; k < height; ++k)
            AddBox(world, b2_dynamicBody, Fixed(-190 + 3 * c), Fixed::FromRatio(50 + 100 * k, 100), Fixed(0.5),
                   Fixed(0.5));
    }
}

// A pyramid of touching boxes (one island holding nearly all the work) and a few lone boxes
// beside it (islands of their own).
void PileAndStrays(b2World& world) {
    AddBox(world, b2_staticBody, 0, Fixed(-0.5), 200, Fixed(0.5));
    constexpr int kRows = 30;
    for (int row = 0; row < kRows; ++row) {
        for (int k = 0; k < kRows - row; ++k)
            AddBox(world, b2_dynamicBody, Fixed(-kRows / 2 + k) + Fixed::FromRatio(row, 2),
                   Fixed::FromRatio(50 + 100 * row, 100), Fixed(0.5), Fixed(0.5));
    }
    for (int s = 0; s < 8; ++s) AddBox(world, b2_dynamicBody, Fixed(40 + 4 * s), Fixed(0.5), Fixed(0.5), Fixed(0.5));
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

TEST(PoolSharing, ManyEqualIslandsGoToThePool) {
    // 64 columns of 10: 640 bodies and 640 contacts in 64 islands.
    const auto build = [](b2World& w) { Columns(w, 64, 10); };
    const Outcome one = Simulate(build, 1);
    const Outcome two = Simulate(build, 2);
    EXPECT_GE(two.work, 1024);
    EXPECT_TRUE(two.shared);
    EXPECT_EQ(one.hashes, two.hashes);
}

TEST(PoolSharing, LittleWorkStaysOnTheSteppingThread) {
    // 10 columns of 3: 60 bodies and contacts.
    const auto build = [](b2World& w) { Columns(w, 10, 3); };
    const Outcome one = Simulate(build, 1);
    const Outcome two = Simulate(build, 2);
    EXPECT_LT(two.work, 1024);
    EXPECT_FALSE(two.shared);
    EXPECT_EQ(one.hashes, two.hashes);
}

TEST(PoolSharing, AnIslandHoldingMostOfTheWorkStaysOnTheSteppingThread) {
    // 465 boxes in one pyramid (over a thousand contacts) against 8 lone boxes.
    const Outcome one = Simulate(PileAndStrays, 1);
    const Outcome two = Simulate(PileAndStrays, 2);
    EXPECT_GE(two.work, 1024) << "the size rule alone would keep it";
    EXPECT_FALSE(two.shared);
    EXPECT_EQ(one.hashes, two.hashes);
}

}  // namespace
}  // namespace lockbox
