// New broad-phase pairs screened on several workers give the one-worker contacts: the same
// contacts in the same order, the same calls of a user's contact filter, the same counts. The
// scene has what each rule of the screening rejects: jointed neighbours, a negative group (the
// default filter) or a filter that turns pairs away, and pairs that already have a contact.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;
using lockbox::test::kDt;

struct FilterCall {
    int32 bodyA = 0, bodyB = 0;
    bool operator==(const FilterCall&) const = default;
};

// Turns away a fixed share of the pairs it is asked about, and remembers every question.
class Picky final : public b2ContactFilter {
public:
    std::vector<FilterCall> calls;
    bool ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB) override {
        const int32 a = fixtureA->GetBody()->GetId();
        const int32 b = fixtureB->GetBody()->GetId();
        calls.push_back({a, b});
        if ((a * 3 + b * 5) % 7 == 0) return false;
        return b2ContactFilter::ShouldCollide(fixtureA, fixtureB);
    }
};

struct Outcome {
    std::vector<uint64_t> hashes;
    std::vector<int32> pairsFound;
    std::vector<int32> contactsCreated;
    std::vector<FilterCall> filterCalls;
    int32 busySteps = 0;  // steps with more pairs than one block of the screening
};

Outcome Simulate(b2TaskSystem* tasks, bool userFilter) {
    b2World world(b2Vec2(0, -10));
    if (tasks != nullptr) world.SetTaskSystem(tasks);
    Picky picky;
    if (userFilter) world.SetContactFilter(&picky);

    // A box 16 m wide; 480 small boxes rain into it in rows, every fourth one with a negative
    // group shared with its neighbour, and every fifth jointed to the one before it.
    lockbox::test::MakeStaticBox(world, 0, Fixed(-0.5), 9, Fixed(0.5));
    lockbox::test::MakeStaticBox(world, -8, 20, Fixed(0.5), 20);
    lockbox::test::MakeStaticBox(world, 8, 20, Fixed(0.5), 20);
    // A paddle turning through the pile keeps its boxes moving after they land.
    b2BodyDef paddleDef;
    paddleDef.type = b2_kinematicBody;
    paddleDef.position.Set(0, 3);
    paddleDef.angularVelocity = 2;
    b2Body* paddle = world.CreateBody(&paddleDef);
    b2PolygonShape blade;
    blade.SetAsBox(Fixed(5.5), Fixed(0.2));
    paddle->CreateFixture(&blade, 0);
    b2Body* previous = nullptr;
    for (int i = 0; i < 480; ++i) {
        const Fixed x = Fixed(-7) + Fixed::FromRatio((i % 24) * 58, 100);
        const Fixed y = Fixed(2) + Fixed::FromRatio((i / 24) * 70 + (i % 3) * 10, 100);
        b2Body* body = lockbox::test::MakeDynamicBox(world, x, y, Fixed(0.26), Fixed(0.26));
        if (i % 4 < 2) {
            b2Filter filter;
            filter.groupIndex = static_cast<int16>(-(1 + i / 4));
            body->GetFixtureList()->SetFilterData(filter);
        }
        if (previous != nullptr && i % 5 == 0) {
            b2RevoluteJointDef jd;
            jd.Initialize(previous, body, body->GetPosition());
            world.CreateJoint(&jd);
        }
        previous = body;
    }

    Outcome run;
    for (int i = 0; i < 180; ++i) {
        world.Step(kDt, 8, 3);
        run.hashes.push_back(world.Hash());
        run.pairsFound.push_back(world.GetProfile().pairsFound);
        run.contactsCreated.push_back(world.GetProfile().contactsCreated);
        run.busySteps += world.GetProfile().pairsFound > 128 ? 1 : 0;
    }
    run.filterCalls = picky.calls;
    return run;
}

void ExpectSame(const Outcome& one, const Outcome& many, const char* what) {
    EXPECT_EQ(one.hashes, many.hashes) << what;
    EXPECT_EQ(one.pairsFound, many.pairsFound) << what;
    EXPECT_EQ(one.contactsCreated, many.contactsCreated) << what;
    EXPECT_TRUE(one.filterCalls == many.filterCalls) << what << ": filter calls differ";
}

void CheckWorkerCounts(bool userFilter) {
    const Outcome one = Simulate(nullptr, userFilter);
    // Enough pairs for the workers in nearly every step, and contacts made throughout.
    EXPECT_GT(one.busySteps, 150);
    int32 created = 0;
    for (const int32 c : one.contactsCreated) created += c;
    EXPECT_GT(created, 400);
    if (userFilter) {
        EXPECT_GT(one.filterCalls.size(), 400u);
    }
    b2ThreadPool two(2), three(3);
    ExpectSame(one, Simulate(&two, userFilter), "a pool of 2");
    ExpectSame(one, Simulate(&three, userFilter), "a pool of 3");
    lockbox::golden::ScrambledTasks scrambled(4, 0xbead);
    ExpectSame(one, Simulate(&scrambled, userFilter), "scrambled blocks");
}

TEST(ParallelNewPairs, DefaultFilterMatchesOneWorker) { CheckWorkerCounts(false); }

TEST(ParallelNewPairs, UserFilterSeesTheOneWorkerQuestions) { CheckWorkerCounts(true); }

}  // namespace LOCKBOX_TEST_FILE
