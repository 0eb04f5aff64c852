// The end of the discrete step on several workers gives the one-worker results. There, blocks
// of body slots sweep the moved bodies' proxies, flag the fast ones and wrap their angles; the
// bodies whose proxies left their fat boxes, or that left the world bounds, are then taken in
// body-list order for the broad phase's moves and the boundary listener. The scene has all of
// them at once: a rain of boxes (moves), spinning wheels (angles past a half turn), bullets
// fired out of the bounds (fast flags, violations), bodies made and destroyed while it runs
// (the list order of new bodies) and a restore from a snapshot (the list order rebuilt).
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;
using lockbox::test::kDt;

class Violations final : public b2BoundaryListener {
public:
    void Violation(b2Body* body) override { ids.push_back(body->GetId()); }
    std::vector<int32> ids;
};

struct FinishRun {
    std::vector<uint64_t> hashes;  // after every step
    std::vector<int32> violations;
    std::vector<int32> pairs, created;
    Fixed largestAngle;  // of the wheels, over the run
};

FinishRun Simulate(b2TaskSystem* tasks) {
    auto made = std::make_unique<b2World>(b2Vec2(0, -10));
    b2World& world = *made;
    if (tasks != nullptr) world.SetTaskSystem(tasks);
    Violations violations;
    world.SetBoundaryListener(&violations);
    world.SetWorldBounds(b2AABB{b2Vec2(-60, -20), b2Vec2(60, 80)});

    lockbox::test::MakeStaticBox(world, 0, Fixed(-0.5), 50, Fixed(0.5));
    std::vector<b2Body*> wheels;
    for (int k = 0; k < 6; ++k) {
        b2Body* wheel = lockbox::test::MakeDynamicCircle(world, Fixed(-40 + 16 * k), 3, Fixed(0.5));
        wheel->SetAngularVelocity(Fixed(30 + 7 * k));
        wheels.push_back(wheel);
    }
    // A rain of boxes, more than a block of body slots.
    for (int row = 0; row < 12; ++row) {
        for (int k = 0; k < 30; ++k)
            lockbox::test::MakeDynamicBox(world, Fixed(-44 + 3 * k) + Fixed::FromRatio(row % 3, 3), Fixed(6 + 2 * row),
                                          Fixed(0.4), Fixed(0.4));
    }

    FinishRun run;
    std::vector<b2Body*> bullets;
    std::unique_ptr<b2World> restored;
    b2World* stepped = &world;
    for (int i = 0; i < 150; ++i) {
        if (i % 20 == 5) {
            // Fired sideways out of the bounds, above the boxes.
            b2Body* bullet = lockbox::test::MakeDynamicCircle(*stepped, 0, Fixed(50 + i / 10), Fixed(0.2));
            bullet->SetBullet(true);
            bullet->SetLinearVelocity(b2Vec2(Fixed(i % 40 == 5 ? 150 : -150), 5));
            bullets.push_back(bullet);
        }
        if (i == 70) {
            // A body in the middle of the list goes, and its slot is taken by a new one at the head.
            world.DestroyBody(bullets[1]);
            lockbox::test::MakeDynamicBox(world, 3, 40, Fixed(0.4), Fixed(0.4));
        }
        if (i == 90) {
            // The run goes on in another world restored from a snapshot, whose body list the
            // restore builds, as a peer joining a match does.
            restored = std::make_unique<b2World>(b2Vec2(0, -10));
            EXPECT_TRUE(restored->Restore(world.Save()).ok());
            if (tasks != nullptr) restored->SetTaskSystem(tasks);
            restored->SetBoundaryListener(&violations);
            world.SetBoundaryListener(nullptr);
            stepped = restored.get();
        }
        stepped->Step(kDt, 8, 3);
        run.hashes.push_back(stepped->Hash());
        run.pairs.push_back(stepped->GetProfile().pairsFound);
        run.created.push_back(stepped->GetProfile().contactsCreated);
    }
    for (b2Body* b = stepped->GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() == b2_dynamicBody) run.largestAngle = b2Max(run.largestAngle, b2Abs(b->GetAngle()));
    }
    run.violations = violations.ids;
    stepped->SetBoundaryListener(nullptr);
    world.SetBoundaryListener(nullptr);
    return run;
}

void ExpectSame(const FinishRun& one, const FinishRun& many, const char* what) {
    EXPECT_EQ(one.hashes, many.hashes) << what;
    EXPECT_EQ(one.violations, many.violations) << what;
    EXPECT_EQ(one.pairs, many.pairs) << what;
    EXPECT_EQ(one.created, many.created) << what;
}

TEST(ParallelFinish, MovesWrapsAndBoundsMatchOneWorker) {
    const FinishRun one = Simulate(nullptr);
    // The scene does what the test is for.
    EXPECT_GE(one.violations.size(), 4u) << "too few bodies left the bounds";
    int32 pairs = 0;
    for (const int32 p : one.pairs) pairs += p;
    EXPECT_GT(pairs, 1000) << "too few proxies moved";
    EXPECT_LE(one.largestAngle, b2_pi) << "an angle was not wrapped";

    // The world's own pool keeps fewer than 1,024 body slots on the stepping thread; a pool
    // handed over as the game's task system, and scrambled blocks, get the finish.
    b2ThreadPool two(2), three(3);
    ExpectSame(one, Simulate(&two), "a pool of 2 handed over");
    ExpectSame(one, Simulate(&three), "a pool of 3 handed over");
    lockbox::golden::ScrambledTasks scrambled(4, 0xf1a1);
    ExpectSame(one, Simulate(&scrambled), "scrambled blocks");
    EXPECT_GT(scrambled.Blocks(), scrambled.Loops());
}

}  // namespace LOCKBOX_TEST_FILE
