// Test 5: stages with nothing to do cost nothing. The profile's work counters are
// deterministic, so they are checked exactly.
#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"
#include "FixedPrint.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

// A resting stack of three boxes on the ground.
void BuildStack(b2World& world) {
    MakeStaticBox(world, 0, -1, 10, 1);
    for (int i = 0; i < 3; ++i) MakeDynamicBox(world, 0, Fixed(0.52) + Fixed(1.02) * Fixed(i), Fixed(0.5), Fixed(0.5));
}

TEST(Profile, SleepingWorldDoesNoSolverWork) {
    b2World world(b2Vec2(0, -10));
    BuildStack(world);
    int n = 0;
    for (; n < 600; ++n) {
        world.Step(kDt, 8, 3);
        bool awake = false;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) awake = awake || b->IsAwake();
        if (!awake) break;
    }
    ASSERT_LT(n, 600);
    world.Step(kDt, 8, 3);
    const b2Profile& p = world.GetProfile();
    EXPECT_EQ(p.islandsSolved, 0);
    EXPECT_EQ(p.bodiesIntegrated, 0);
    EXPECT_EQ(p.contactConstraints, 0);
    EXPECT_EQ(p.velocityIterations, 0);
    EXPECT_EQ(p.positionIterations, 0);
    EXPECT_EQ(p.contactsUpdated, 0);
    EXPECT_EQ(p.manifoldsEvaluated, 0);
    EXPECT_EQ(p.pairsFound, 0);
    EXPECT_EQ(p.sleepChecks, 0);
    EXPECT_EQ(p.toiCandidates, 0);
    EXPECT_EQ(p.toiCalls, 0);
    EXPECT_EQ(p.listenerCallbacks, 0);
}

TEST(Profile, AwakeWorldCountsItsWork) {
    b2World world(b2Vec2(0, -10));
    BuildStack(world);
    for (int n = 0; n < 10; ++n) world.Step(kDt, 8, 3);
    const b2Profile& p = world.GetProfile();
    EXPECT_EQ(p.islandsSolved, 1);
    EXPECT_EQ(p.bodiesIntegrated, 4);  // three boxes and the ground in one island
    EXPECT_EQ(p.contactConstraints, 3);
    EXPECT_EQ(p.velocityIterations, 8 * 3);
    EXPECT_GE(p.positionIterations, 1);
    EXPECT_LE(p.positionIterations, 3);
    EXPECT_EQ(p.manifoldsEvaluated, 3);
    EXPECT_EQ(p.sleepChecks, 3);
    EXPECT_GT(p.stepNs, 0);
}

TEST(Profile, JointFreeWorldNeverEntersJointLoops) {
    b2World world(b2Vec2(0, -10));
    BuildStack(world);
    for (int n = 0; n < 10; ++n) {
        world.Step(kDt, 8, 3);
        EXPECT_EQ(world.GetProfile().jointConstraints, 0);
        EXPECT_EQ(world.GetProfile().jointVelocityIterations, 0);
    }
}

TEST(Profile, NoFastBodiesMeansNoTOIWork) {
    b2World world(b2Vec2(0, -10));
    BuildStack(world);
    // Let it settle: resting bodies move far less than linearSlop per step.
    for (int n = 0; n < 30; ++n) world.Step(kDt, 8, 3);
    for (int n = 0; n < 10; ++n) {
        world.Step(kDt, 8, 3);
        const b2Profile& p = world.GetProfile();
        EXPECT_EQ(p.toiCandidates, 0);
        EXPECT_EQ(p.toiCalls, 0);
        EXPECT_EQ(p.toiEvents, 0);
        EXPECT_EQ(p.toiSubSteps, 0);
    }
    // A fast body near the ground does get TOI work.
    b2Body* fast = MakeDynamicCircle(world, 5, Fixed(1.5), Fixed(0.25));
    fast->SetLinearVelocity(b2Vec2(0, -100));
    int calls = 0, events = 0;
    for (int n = 0; n < 3; ++n) {
        world.Step(kDt, 8, 3);
        calls += world.GetProfile().toiCalls;
        events += world.GetProfile().toiEvents;
    }
    EXPECT_GT(calls, 0);
    EXPECT_GT(events, 0);
}

TEST(Profile, NoListenerMeansNoCallbacks) {
    b2World world(b2Vec2(0, -10));
    BuildStack(world);
    for (int n = 0; n < 10; ++n) {
        world.Step(kDt, 8, 3);
        EXPECT_EQ(world.GetProfile().listenerCallbacks, 0);
    }
    RecordingListener listener;
    world.SetContactListener(&listener);
    world.Step(kDt, 8, 3);
    // Three touching contacts: one PreSolve and one PostSolve each.
    EXPECT_EQ(world.GetProfile().listenerCallbacks, 6);
    EXPECT_EQ(listener.preSolves + listener.postSolves, 6);
}

// The stage times of a world whose timers are off: all of them zero.
int64_t TimeSum(const b2Profile& p) {
    return p.stepNs + p.collideNs + p.solveNs + p.solveInitNs + p.solveVelocityNs + p.solvePositionNs + p.broadphaseNs +
           p.solveTOINs;
}

// A world with its stage timers off reads no clock: every stage time is zero, and the work and the
// state are those of the same world timed, with one worker and with two (the islands' shared
// solve times its phases in its own place).
TEST(Profile, TimersOffLeaveTimesZeroAndChangeNothing) {
    for (int workers : {1, 2}) {
        b2World timed(b2Vec2(0, -10)), untimed(b2Vec2(0, -10));
        untimed.SetProfileTimers(false);
        EXPECT_TRUE(timed.GetProfileTimers());
        EXPECT_FALSE(untimed.GetProfileTimers());
        int64_t timedNs = 0;
        for (b2World* world : {&timed, &untimed}) {
            world->SetWorkerCount(workers);
            BuildStack(*world);
            // A fast circle, so that the time of impact has work too.
            MakeDynamicCircle(*world, 5, Fixed(1.5), Fixed(0.25))->SetLinearVelocity(b2Vec2(0, -100));
        }
        for (int n = 0; n < 60; ++n) {
            timed.Step(kDt, 8, 3);
            untimed.Step(kDt, 8, 3);
            const b2Profile& a = timed.GetProfile();
            const b2Profile& b = untimed.GetProfile();
            ASSERT_EQ(TimeSum(b), 0) << "step " << n;
            EXPECT_EQ(b.bodiesIntegrated, a.bodiesIntegrated);
            EXPECT_EQ(b.velocityIterations, a.velocityIterations);
            EXPECT_EQ(b.positionIterations, a.positionIterations);
            EXPECT_EQ(b.toiCalls, a.toiCalls);
            ASSERT_EQ(b2WorldHash(timed), b2WorldHash(untimed)) << "step " << n << ", " << workers << " workers";
            timedNs += a.stepNs;
        }
        EXPECT_GT(timedNs, 0);
        // Switched back on, the next step is timed again.
        untimed.SetProfileTimers(true);
        untimed.Step(kDt, 8, 3);
        EXPECT_GT(untimed.GetProfile().stepNs, 0);
    }
}

TEST(Profile, EmptyStepIsFree) {
    b2World world(b2Vec2(0, -10));
    world.Step(kDt, 8, 3);
    const b2Profile& p = world.GetProfile();
    EXPECT_EQ(p.islandsSolved + p.bodiesIntegrated + p.contactsUpdated + p.toiCalls + p.pairsFound, 0);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
