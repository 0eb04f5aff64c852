// Contacts evaluated ahead on several workers give the one-worker narrow phase, also when the
// listener acts during the list walk that uses the evaluations: it re-filters fixtures (the
// walk then decides those contacts itself), disables contacts in PreSolve, and wakes sleeping
// bodies, so that contacts the workers skipped as inactive must be updated by the walk itself
// (the sleepers were turned while asleep, so an evaluation kept from before would be wrong). The state after every step
// and the sequence of listener calls must be those of one worker.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;
using lockbox::test::kDt;

struct Call {
    char kind = 0;  // 'b'egin, 'e'nd, 'p're-solve
    int32 bodyA = 0, bodyB = 0;
    bool operator==(const Call&) const = default;
};

class Meddler final : public b2ContactListener {
public:
    std::vector<b2Body*> sleepers;  // woken one at a time by BeginContact, once `waking`
    bool waking = false;
    std::vector<Call> calls;
    int32 step = 0;

    void BeginContact(b2Contact* contact) override {
        Record('b', contact);
        b2Fixture* a = contact->GetFixtureA();
        // Every third new touch between two dynamic bodies re-filters fixture A (a group that
        // still collides): the flagged contacts of its body go through the walk's own filtering.
        const bool bothDynamic =
            a->GetBody()->GetType() == b2_dynamicBody && contact->GetFixtureB()->GetBody()->GetType() == b2_dynamicBody;
        if (bothDynamic && calls.size() % 3 == 0) {
            b2Filter filter = a->GetFilterData();
            filter.groupIndex = static_cast<int16>(filter.groupIndex == 0 ? 1 : 0);
            a->SetFilterData(filter);
        }
        if (waking && !sleepers.empty()) {
            sleepers.back()->SetAwake(true);
            sleepers.pop_back();
        }
    }
    void EndContact(b2Contact* contact) override { Record('e', contact); }
    void PreSolve(b2Contact* contact, const b2Manifold*) override {
        Record('p', contact);
        const int32 a = contact->GetFixtureA()->GetBody()->GetId();
        const int32 b = contact->GetFixtureB()->GetBody()->GetId();
        const bool bothDynamic = contact->GetFixtureA()->GetBody()->GetType() == b2_dynamicBody &&
                                 contact->GetFixtureB()->GetBody()->GetType() == b2_dynamicBody;
        if (bothDynamic && (a * 7 + b * 3 + step) % 11 == 0) contact->SetEnabled(false);
    }

private:
    void Record(char kind, b2Contact* contact) {
        calls.push_back({kind, contact->GetFixtureA()->GetBody()->GetId(), contact->GetFixtureB()->GetBody()->GetId()});
    }
};

struct Outcome {
    std::vector<uint64_t> hashes;
    std::vector<Call> calls;
    int32 contactsUpdated = 0;
    int32 sleepersMovedAsleep = 0;
};

Outcome Simulate(int workers, b2TaskSystem* tasks) {
    b2World world(b2Vec2(0, -10));
    if (tasks != nullptr)
        world.SetTaskSystem(tasks);
    else
        world.SetWorkerCount(workers);
    Meddler meddler;
    world.SetContactListener(&meddler);

    lockbox::test::MakeStaticBox(world, 0, Fixed(-0.5), 60, Fixed(0.5));
    // Ten columns of six boxes (well over the contacts the parallel path needs), a box on the
    // ground between each two (it falls asleep), and a box dropped from high above each column,
    // whose landing starts new touches late in the run.
    std::vector<b2Body*> sleepers;
    for (int s = 0; s < 10; ++s) {
        for (int k = 0; k < 6; ++k)
            lockbox::test::MakeDynamicBox(world, Fixed(-27 + 6 * s) + Fixed::FromRatio(k % 2, 10),
                                          Fixed::FromRatio(51 + 102 * k, 100), Fixed(0.5), Fixed(0.5));
        sleepers.push_back(
            lockbox::test::MakeDynamicBox(world, Fixed(-24 + 6 * s), Fixed(0.5), Fixed(0.5), Fixed(0.5)));
        lockbox::test::MakeDynamicBox(world, Fixed(-27 + 6 * s), Fixed(40 + s), Fixed(0.5), Fixed(0.5));
    }

    Outcome run;
    for (int i = 0; i < 240; ++i) {
        meddler.step = i;
        if (i == 120) {
            // Tilt the sleepers without waking them (their manifolds, kept in body frames, change
            // only with a turn: one corner lifts off); from now on the landings' new touches wake
            // them during the walk.
            for (b2Body* b : sleepers) {
                if (b->IsAwake()) continue;
                b->SetTransform(b->GetPosition(), b->GetAngle() + Fixed(0.3));
                run.sleepersMovedAsleep += b->IsAwake() ? 0 : 1;
                meddler.sleepers.push_back(b);
            }
            meddler.waking = true;
        }
        world.Step(kDt, 8, 3);
        run.hashes.push_back(world.Hash());
        run.contactsUpdated += world.GetProfile().contactsUpdated;
    }
    run.calls = meddler.calls;
    world.SetContactListener(nullptr);
    return run;
}

void ExpectSame(const Outcome& one, const Outcome& many, const char* what) {
    EXPECT_EQ(one.hashes, many.hashes) << what;
    EXPECT_TRUE(one.calls == many.calls) << what << ": listener calls differ";
    EXPECT_EQ(one.contactsUpdated, many.contactsUpdated) << what;
}

TEST(ParallelNarrowPhase, ListenerThatRefiltersWakesAndDisablesMatchesOneWorker) {
    const Outcome one = Simulate(1, nullptr);
    // The listener did act: calls of every kind, and far more than the walk needs to go parallel.
    int begins = 0, presolves = 0;
    for (const Call& c : one.calls) {
        begins += c.kind == 'b' ? 1 : 0;
        presolves += c.kind == 'p' ? 1 : 0;
    }
    EXPECT_GT(begins, 60);
    EXPECT_GT(presolves, 1000);
    EXPECT_GT(one.contactsUpdated, 64 * 100);
    EXPECT_GE(one.sleepersMovedAsleep, 5);
    // The world's own pool keeps work this small on the stepping thread; a pool handed over
    // as the game's task system gets every loop, on real threads.
    ExpectSame(one, Simulate(2, nullptr), "2 workers of the world's own pool");
    b2ThreadPool two(2), three(3);
    ExpectSame(one, Simulate(0, &two), "a pool of 2 handed over");
    ExpectSame(one, Simulate(0, &three), "a pool of 3 handed over");
    lockbox::golden::ScrambledTasks scrambled(4, 0x5eed);
    ExpectSame(one, Simulate(0, &scrambled), "scrambled blocks");
    EXPECT_GT(scrambled.Loops(), 100u);
}

}  // namespace LOCKBOX_TEST_FILE
