// Without a contact listener the workers update every contact in place, and only what reaches
// outside a contact (destroying it, waking its bodies, re-filtering) is done afterwards in list
// order. The delicate part is waking: a body woken by a contact makes its sleeping neighbours'
// contacts active for the rest of the walk, but not for the part the walk had passed. The scene
// below puts a third of the pile to sleep every few steps while the rest moves, so that wakes
// happen in the walk in both directions; sensors, a kinematic paddle, re-filtering and
// separating pairs add the other cases. Every step must hash as with one worker.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "../dynamics/DynamicsTestUtil.h"
#include "lockbox_internal/WorldInternals.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using test::kDt;

struct Outcome {
    std::vector<uint64_t> hashes;
    std::vector<int32> contactsUpdated;
    int64_t joined = 0;  // inactive contacts a wake earlier in the list brought into the walk
    int64_t passed = 0;  // inactive contacts of woken bodies that the walk had already passed
    int32 sleepersPut = 0;
};

void BuildScene(b2World& world, std::vector<b2Body*>& pile) {
    test::MakeStaticBox(world, 0, Fixed(-0.5), 20, Fixed(0.5));
    test::MakeStaticBox(world, -20, 10, Fixed(0.5), 10);
    test::MakeStaticBox(world, 20, 10, Fixed(0.5), 10);

    // A static sensor over the left half of the container: sensor pairs update without a
    // manifold and never wake their bodies.
    test::MakeStaticSensorBox(world, -10, 3, 8, 3);

    for (int row = 0; row < 12; ++row) {
        for (int col = 0; col < 24; ++col) {
            const Fixed x = Fixed(-18) + Fixed::FromRatio(150 * col + 20 * (row % 3), 100);
            const Fixed y = Fixed::FromRatio(45 + 95 * row, 100);
            pile.push_back((row + col) % 4 == 0 ? test::MakeDynamicCircle(world, x, y, Fixed::FromRatio(45, 100))
                                                : test::MakeDynamicBox(world, x, y, Fixed::FromRatio(45, 100),
                                                                       Fixed::FromRatio(45, 100)));
        }
    }

    // A kinematic paddle that sweeps through the pile's top, turning slowly.
    b2BodyDef paddleDef;
    paddleDef.type = b2_kinematicBody;
    paddleDef.position.Set(-17, 9);
    paddleDef.linearVelocity.Set(Fixed::FromRatio(3, 2), Fixed::FromRatio(-1, 10));
    paddleDef.angularVelocity = Fixed::FromRatio(1, 5);
    b2Body* paddle = world.CreateBody(&paddleDef);
    b2PolygonShape paddleBox;
    paddleBox.SetAsBox(3, Fixed::FromRatio(1, 4));
    b2FixtureDef paddleFixture;
    paddleFixture.shape = &paddleBox;
    paddle->CreateFixture(&paddleFixture);
}

Outcome Simulate(b2TaskSystem* tasks) {
    b2World world(b2Vec2(0, -10));
    if (tasks != nullptr) world.SetTaskSystem(tasks);
    std::vector<b2Body*> pile;
    BuildScene(world, pile);

    Outcome run;
    for (int i = 0; i < 360; ++i) {
        if (i % 17 == 5) {
            // A third of the pile asleep, whatever its neighbours do: their touches then wake
            // them during the narrow phase, at every place of the contact list.
            for (size_t k = 0; k < pile.size(); ++k) {
                if ((k * 7 + static_cast<size_t>(i)) % 3 != 0 || !pile[k]->IsAwake()) continue;
                pile[k]->SetAwake(false);
                ++run.sleepersPut;
            }
        }
        if (i % 23 == 11) {
            // Re-filter a fifth of the pile (a group that still collides): their contacts are
            // flagged and go through the walk's own filtering.
            for (size_t k = static_cast<size_t>(i) % 5; k < pile.size(); k += 5) {
                b2Fixture* fixture = pile[k]->GetFixtureList();
                b2Filter filter = fixture->GetFilterData();
                filter.groupIndex = static_cast<int16>(filter.groupIndex == 0 ? 1 : 0);
                fixture->SetFilterData(filter);
            }
        }
        world.Step(kDt, 8, 3);
        run.hashes.push_back(world.Hash());
        run.contactsUpdated.push_back(world.GetProfile().contactsUpdated);
        const auto& woken = test::Internals(world).m_contactManager.m_lastWoken;
        run.joined += woken.joined;
        run.passed += woken.passed;
    }
    return run;
}

void ExpectSame(const Outcome& one, const Outcome& many, const char* what) {
    EXPECT_EQ(one.hashes, many.hashes) << what;
    EXPECT_EQ(one.contactsUpdated, many.contactsUpdated) << what;
    EXPECT_EQ(one.sleepersPut, many.sleepersPut) << what;
    // The list-order pass met wakes on both sides of the contacts they reach.
    EXPECT_GT(many.joined, 0) << what;
    EXPECT_GT(many.passed, 0) << what;
}

TEST(NarrowPhaseOnWorkers, WakesInTheWalkMatchOneWorker) {
    const Outcome one = Simulate(nullptr);
    EXPECT_GT(one.sleepersPut, 500);
    EXPECT_EQ(one.joined, 0);  // one worker walks the list itself
    b2ThreadPool two(2), three(3);
    ExpectSame(one, Simulate(&two), "a pool of 2 handed over");
    ExpectSame(one, Simulate(&three), "a pool of 3 handed over");
    golden::ScrambledTasks scrambled(4, 0x5eed);
    ExpectSame(one, Simulate(&scrambled), "scrambled blocks");
    EXPECT_GT(scrambled.Loops(), 300u);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
