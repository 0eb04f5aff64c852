// Islands solved on several workers give the one-worker results: the same state every step,
// the same PostSolve calls in the same order with the same impulses, the same work counters.
// The scene makes the workers' hard cases happen together: one static ground shared by many
// islands (it is never written by an island solve, and sleeps with its islands in island
// order), stacks that fall asleep while a jointed pendulum on the same ground keeps swinging,
// and a contact listener. A second scene adds a pyramid large enough to be solved in colour
// order, shared colour by colour between the workers, beside the islands solved in blocks.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;
using lockbox::test::kDt;

struct PostSolveRecord {
    int32 bodyA = 0, bodyB = 0;
    int64_t normal0 = 0, normal1 = 0, tangent0 = 0, tangent1 = 0;
    bool operator==(const PostSolveRecord&) const = default;
};

class Recorder final : public b2ContactListener {
public:
    void PostSolve(b2Contact* contact, const b2ContactImpulse* impulse) override {
        log.push_back({contact->GetFixtureA()->GetBody()->GetId(), contact->GetFixtureB()->GetBody()->GetId(),
                       impulse->normalImpulses[0].Raw(), impulse->normalImpulses[1].Raw(),
                       impulse->tangentImpulses[0].Raw(), impulse->tangentImpulses[1].Raw()});
    }
    std::vector<PostSolveRecord> log;
};

struct SceneRun {
    std::vector<uint64_t> hashes;  // after every step
    std::vector<PostSolveRecord> postSolve;
    std::vector<int32> islands, bodies, contacts, joints, velocity, position, sleepChecks, callbacks;
    int asleepSteps = 0;  // steps at whose end the ground was asleep
};

// Rows of the pyramid of the second scene: 528 boxes, over 1,024 contacts once they touch.
constexpr int kPileRows = 32;

SceneRun Simulate(int workers, b2TaskSystem* tasks, bool withPile = false) {
    b2World world(b2Vec2(0, -10));
    if (tasks != nullptr)
        world.SetTaskSystem(tasks);
    else
        world.SetWorkerCount(workers);
    Recorder recorder;
    world.SetContactListener(&recorder);

    b2Body* ground = lockbox::test::MakeStaticBox(world, 0, Fixed(-0.5), 60, Fixed(0.5));
    // A pendulum hinged on the ground: an island with a joint to the shared static body that
    // never sleeps. Made first, it is the last island of every step (bodies are listed newest
    // first): the ground, put to sleep with the stacks before it, must wake with it.
    b2Body* bob = lockbox::test::MakeDynamicCircle(world, 30, 5, Fixed(0.25));
    b2RevoluteJointDef rj;
    rj.Initialize(ground, bob, b2Vec2(27, 5));
    world.CreateJoint(&rj);
    // Eight separate stacks of three boxes: eight islands that settle and sleep.
    for (int s = 0; s < 8; ++s) {
        for (int k = 0; k < 3; ++k)
            lockbox::test::MakeDynamicBox(world, Fixed(-28 + 7 * s), Fixed::FromRatio(51 + 102 * k, 100), Fixed(0.5),
                                          Fixed(0.5));
    }
    if (withPile) {
        for (int row = 0; row < kPileRows; ++row) {
            for (int k = 0; k < kPileRows - row; ++k)
                lockbox::test::MakeDynamicBox(world, Fixed(-kPileRows / 2 + k) + Fixed::FromRatio(row, 2) + 100,
                                              Fixed::FromRatio(50 + 100 * row, 100), Fixed(0.5), Fixed(0.5));
        }
        lockbox::test::MakeStaticBox(world, 100, Fixed(-0.5), 30, Fixed(0.5));
    }

    SceneRun run;
    const int steps = withPile ? 40 : 240;
    for (int i = 0; i < steps; ++i) {
        world.Step(kDt, 8, 3);
        run.hashes.push_back(world.Hash());
        const b2Profile& p = world.GetProfile();
        run.islands.push_back(p.islandsSolved);
        run.bodies.push_back(p.bodiesIntegrated);
        run.contacts.push_back(p.contactConstraints);
        run.joints.push_back(p.jointConstraints);
        run.velocity.push_back(p.velocityIterations);
        run.position.push_back(p.positionIterations);
        run.sleepChecks.push_back(p.sleepChecks);
        run.callbacks.push_back(p.listenerCallbacks);
        if (!ground->IsAwake()) ++run.asleepSteps;
    }
    run.postSolve = recorder.log;
    world.SetContactListener(nullptr);
    return run;
}

void ExpectSame(const SceneRun& one, const SceneRun& many, const char* what) {
    EXPECT_EQ(one.hashes, many.hashes) << what;
    EXPECT_TRUE(one.postSolve == many.postSolve) << what << ": PostSolve calls differ";
    EXPECT_EQ(one.islands, many.islands) << what;
    EXPECT_EQ(one.bodies, many.bodies) << what;
    EXPECT_EQ(one.contacts, many.contacts) << what;
    EXPECT_EQ(one.joints, many.joints) << what;
    EXPECT_EQ(one.velocity, many.velocity) << what;
    EXPECT_EQ(one.position, many.position) << what;
    EXPECT_EQ(one.sleepChecks, many.sleepChecks) << what;
    EXPECT_EQ(one.callbacks, many.callbacks) << what;
    EXPECT_EQ(one.asleepSteps, many.asleepSteps) << what;
}

TEST(ParallelIslands, SharedGroundSleepingStacksAndListenerMatchOneWorker) {
    const SceneRun one = Simulate(1, nullptr);
    // The scene does what the test is for: many islands, PostSolve calls, stacks that sleep.
    EXPECT_GE(one.islands.front(), 9);
    EXPECT_LT(one.islands.back(), one.islands.front()) << "no stack fell asleep";
    EXPECT_GT(one.postSolve.size(), 500u);
    // The world's own pool keeps work this small on the stepping thread; a pool handed over
    // as the game's task system gets every loop, on real threads.
    ExpectSame(one, Simulate(2, nullptr), "2 workers of the world's own pool");
    b2ThreadPool two(2), three(3);
    ExpectSame(one, Simulate(0, &two), "a pool of 2 handed over");
    ExpectSame(one, Simulate(0, &three), "a pool of 3 handed over");
    lockbox::golden::ScrambledTasks scrambled(4, 0x15ad);
    ExpectSame(one, Simulate(0, &scrambled), "scrambled blocks");
    EXPECT_GT(scrambled.Blocks(), scrambled.Loops());
}

// The pyramid's island is solved in colour order, shared by the workers, while the other
// islands are solved in blocks: its PostSolve calls keep the one-worker order and impulses.
TEST(ParallelIslands, ColouredPileBesideSmallIslandsMatchesOneWorker) {
    const SceneRun one = Simulate(1, nullptr, true);
    EXPECT_GE(one.contacts.back(), 1024);
    ExpectSame(one, Simulate(2, nullptr, true), "2 workers of the world's own pool");
    b2ThreadPool two(2), three(3);
    ExpectSame(one, Simulate(0, &two, true), "a pool of 2 handed over");
    ExpectSame(one, Simulate(0, &three, true), "a pool of 3 handed over");
    lockbox::golden::ScrambledTasks scrambled(4, 0x9ad);
    ExpectSame(one, Simulate(0, &scrambled, true), "scrambled blocks");
}

}  // namespace LOCKBOX_TEST_FILE
