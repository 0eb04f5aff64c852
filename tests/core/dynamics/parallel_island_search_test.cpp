// The island search on several workers finds the islands of the one-worker search, in its
// order, each with its bodies, contacts and joints in its order: the same state every step, the
// same PostSolve calls in the same order, the same island counts. The scene has every edge the
// search follows or stops at: a static ground shared by hundreds of islands, stacks that fall
// asleep and are woken by a ball, a rope hung from a static anchor, kinematic platforms joined
// to each other (a joint between bodies without mass, which the search does not follow) with a
// box riding each, a body made inactive on a joint, a sensor over a row of boxes, a contact
// that a listener disables, bodies made at the head of the list while it runs, and a restore
// from a snapshot (which rebuilds the list).
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "DynamicsTestUtil.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;
using lockbox::test::kDt;

// Disables every contact between the ghost and one box, so that the ghost falls through that
// box alone; records the PostSolve calls.
class Listener final : public b2ContactListener {
public:
    void PreSolve(b2Contact* contact, const b2Manifold*) override {
        const int32 a = contact->GetFixtureA()->GetBody()->GetId();
        const int32 b = contact->GetFixtureB()->GetBody()->GetId();
        if ((a == ghost && b == passed) || (a == passed && b == ghost)) {
            contact->SetEnabled(false);
            ++disabled;
        }
    }
    void PostSolve(b2Contact* contact, const b2ContactImpulse* impulse) override {
        log.push_back(contact->GetFixtureA()->GetBody()->GetId());
        log.push_back(contact->GetFixtureB()->GetBody()->GetId());
        log.push_back(static_cast<int32>(impulse->normalImpulses[0].Raw()));
    }
    int32 ghost = -1, passed = -1;
    int disabled = 0;
    std::vector<int32> log;
};

struct SearchRun {
    std::vector<uint64_t> hashes;  // after every step
    std::vector<int32> postSolve;
    std::vector<int32> islands, bodies, contacts, joints, sleepChecks;
    int disabled = 0;
    bool ghostPassed = false;  // the ghost went through its box and lies below it
    bool ridersCarried = false;
};

b2Body* MakeKinematicBox(b2World& world, Fixed x, Fixed y, Fixed hx, Fixed hy) {
    b2BodyDef bd;
    bd.type = b2_kinematicBody;
    bd.position.Set(x, y);
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(hx, hy);
    body->CreateFixture(&box, 0);
    return body;
}

SearchRun Simulate(b2TaskSystem* tasks) {
    auto made = std::make_unique<b2World>(b2Vec2(0, -10));
    b2World& world = *made;
    if (tasks != nullptr) world.SetTaskSystem(tasks);
    Listener listener;
    world.SetContactListener(&listener);

    // One static body, two shelves: a row of boxes on the lower, stacks on the upper.
    b2BodyDef groundDef;
    b2Body* ground = world.CreateBody(&groundDef);
    b2PolygonShape shelf;
    shelf.SetAsBox(60, Fixed(0.5), b2Vec2(0, Fixed(-0.5)), 0);
    ground->CreateFixture(&shelf, 0);
    shelf.SetAsBox(60, Fixed(0.5), b2Vec2(0, Fixed(19.5)), 0);
    ground->CreateFixture(&shelf, 0);

    // The row: 220 one-box islands, some under a static sensor.
    std::vector<b2Body*> row;
    for (int k = 0; k < 220; ++k)
        row.push_back(lockbox::test::MakeDynamicBox(world, Fixed(-55) + Fixed::FromRatio(k, 2), Fixed(0.2), Fixed(0.2),
                                                    Fixed(0.2)));
    lockbox::test::MakeStaticSensorBox(world, -30, 1, 5, 1);
    // The ghost falls onto a box of the row, and through it, since the listener disables their
    // contact; it lands on the shelf beside it.
    b2Body* passed = row[101];
    b2Body* ghost = lockbox::test::MakeDynamicBox(world, passed->GetPosition().x, 3, Fixed(0.1), Fixed(0.1));
    listener.ghost = ghost->GetId();
    listener.passed = passed->GetId();

    // Stacks of four on the upper shelf: islands that fall asleep.
    std::vector<b2Body*> stacks;
    for (int s = 0; s < 10; ++s) {
        for (int k = 0; k < 4; ++k)
            stacks.push_back(lockbox::test::MakeDynamicBox(
                world, Fixed(-45 + 10 * s), Fixed::FromRatio(2051 + 102 * k, 100), Fixed(0.5), Fixed(0.5)));
    }
    // One stack holds a body made inactive on a joint.
    b2Body* inactive = lockbox::test::MakeDynamicCircle(world, Fixed(-43), 22, Fixed(0.25));
    b2RevoluteJointDef pin;
    pin.Initialize(stacks[1], inactive, stacks[1]->GetPosition());
    world.CreateJoint(&pin);
    inactive->SetActive(false);

    // A rope of circles hung from a static anchor.
    b2BodyDef anchorDef;
    anchorDef.position.Set(40, 40);
    b2Body* anchor = world.CreateBody(&anchorDef);
    b2Body* previous = anchor;
    for (int k = 0; k < 10; ++k) {
        b2Body* link = lockbox::test::MakeDynamicCircle(world, Fixed(41 + k), 40, Fixed(0.25));
        b2RevoluteJointDef rj;
        rj.Initialize(previous, link, b2Vec2(Fixed(40 + k), 40));
        world.CreateJoint(&rj);
        previous = link;
    }

    // Two kinematic platforms joined to each other, each carrying a box, and a third alone.
    b2Body* left = MakeKinematicBox(world, -20, 40, 2, Fixed(0.25));
    b2Body* right = MakeKinematicBox(world, -10, 40, 2, Fixed(0.25));
    left->SetLinearVelocity(b2Vec2(Fixed(0.5), 0));
    right->SetLinearVelocity(b2Vec2(Fixed(0.5), 0));
    b2RevoluteJointDef link;
    link.Initialize(left, right, b2Vec2(-15, 40));
    world.CreateJoint(&link);
    b2Body* riderLeft = lockbox::test::MakeDynamicBox(world, -20, Fixed(40.75), Fixed(0.5), Fixed(0.5), 1, Fixed(0.8));
    b2Body* riderRight = lockbox::test::MakeDynamicBox(world, -10, Fixed(40.75), Fixed(0.5), Fixed(0.5), 1, Fixed(0.8));
    MakeKinematicBox(world, 0, 50, 1, 1)->SetAngularVelocity(1);

    SearchRun run;
    std::unique_ptr<b2World> restored;
    b2World* stepped = &world;
    for (int i = 0; i < 240; ++i) {
        if (i == 120) {
            // A ball onto a stack asleep by now, and bodies made at the head of the list.
            lockbox::test::MakeDynamicCircle(*stepped, Fixed(-15), 30, Fixed(0.5), 4);
            for (int k = 0; k < 5; ++k)
                lockbox::test::MakeDynamicBox(*stepped, Fixed(10 + 2 * k), 25, Fixed(0.3), Fixed(0.3));
        }
        if (i == 160) {
            // The run goes on in another world restored from a snapshot, whose body list the
            // restore builds.
            restored = std::make_unique<b2World>(b2Vec2(0, -10));
            EXPECT_TRUE(restored->Restore(world.Save()).ok());
            if (tasks != nullptr) restored->SetTaskSystem(tasks);
            restored->SetContactListener(&listener);
            world.SetContactListener(nullptr);
            stepped = restored.get();
        }
        stepped->Step(kDt, 8, 3);
        run.hashes.push_back(stepped->Hash());
        const b2Profile& p = stepped->GetProfile();
        run.islands.push_back(p.islandsSolved);
        run.bodies.push_back(p.bodiesIntegrated);
        run.contacts.push_back(p.contactConstraints);
        run.joints.push_back(p.jointConstraints);
        run.sleepChecks.push_back(p.sleepChecks);
        if (i == 150) {
            run.ghostPassed = ghost->GetPosition().y < passed->GetPosition().y;
            run.ridersCarried = riderLeft->GetPosition().x > Fixed(-19) && riderRight->GetPosition().x > Fixed(-9);
        }
    }
    run.postSolve = listener.log;
    run.disabled = listener.disabled;
    stepped->SetContactListener(nullptr);
    world.SetContactListener(nullptr);
    return run;
}

void ExpectSame(const SearchRun& one, const SearchRun& many, const char* what) {
    EXPECT_EQ(one.hashes, many.hashes) << what;
    EXPECT_TRUE(one.postSolve == many.postSolve) << what << ": PostSolve calls differ";
    EXPECT_EQ(one.islands, many.islands) << what;
    EXPECT_EQ(one.bodies, many.bodies) << what;
    EXPECT_EQ(one.contacts, many.contacts) << what;
    EXPECT_EQ(one.joints, many.joints) << what;
    EXPECT_EQ(one.sleepChecks, many.sleepChecks) << what;
    EXPECT_EQ(one.disabled, many.disabled) << what;
}

TEST(ParallelIslandSearch, EveryEdgeOfTheSearchMatchesOneWorker) {
    const SearchRun one = Simulate(nullptr);
    // The scene does what the test is for: hundreds of islands, stacks asleep and woken, the
    // listener's disabled contact, the riders carried by their platforms.
    EXPECT_GE(one.islands.front(), 230);
    int fewest = one.islands.front();
    for (const int32 n : one.islands) fewest = n < fewest ? n : fewest;
    EXPECT_LT(fewest, one.islands.front() - 5) << "no stack fell asleep";
    EXPECT_GT(one.disabled, 10);
    EXPECT_TRUE(one.ghostPassed);
    EXPECT_TRUE(one.ridersCarried);
    EXPECT_GT(one.postSolve.size(), 3000u);

    // The world's own pool searches on the stepping thread below 1,024 body slots; a pool
    // handed over as the game's task system, and scrambled blocks, search on the workers.
    b2ThreadPool two(2), three(3);
    ExpectSame(one, Simulate(&two), "a pool of 2 handed over");
    ExpectSame(one, Simulate(&three), "a pool of 3 handed over");
    lockbox::golden::ScrambledTasks scrambled(4, 0x5ea7);
    ExpectSame(one, Simulate(&scrambled), "scrambled blocks");
    EXPECT_GT(scrambled.Blocks(), scrambled.Loops());
}

}  // namespace LOCKBOX_TEST_FILE
