// A large island's contacts are solved in colour order: each colour's contacts share no dynamic
// body (so workers may solve them at the same time), each contact has the lowest colour its
// bodies left free (the greedy rule, which makes the order a function of the island alone), and
// a contact that found every colour taken goes to the overflow, solved last. Then the order's
// promise: the same bits with one worker, with several, and with a task system that runs its
// items one after the other.

#include <cstdint>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "../dynamics/DynamicsTestUtil.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox_internal/WorldInternals.h"

namespace lockbox {
namespace {

using Colours = core_detail::Engine::ContactColours;

// A pyramid of boxes on a static ground: one island of well over Colours::kMinContacts contacts.
void Pyramid(b2World& world) {
    test::MakeStaticBox(world, 0, Fixed(-0.5), 100, Fixed(0.5));
    constexpr int kRows = 40;
    for (int row = 0; row < kRows; ++row) {
        for (int k = 0; k < kRows - row; ++k)
            test::MakeDynamicBox(world, Fixed(-kRows / 2 + k) + Fixed::FromRatio(row, 2),
                                 Fixed::FromRatio(50 + 100 * row, 100), Fixed(0.5), Fixed(0.5));
    }
}

// The dynamic bodies of a contact (the solver writes only these).
std::vector<const b2Body*> Written(const b2Contact* c) {
    std::vector<const b2Body*> bodies;
    for (const b2Body* b : {c->GetFixtureA()->GetBody(), c->GetFixtureB()->GetBody()})
        if (b->GetType() == b2_dynamicBody) bodies.push_back(b);
    return bodies;
}

bool ShareABody(const b2Contact* a, const b2Contact* b) {
    for (const b2Body* x : Written(a))
        for (const b2Body* y : Written(b))
            if (x == y) return true;
    return false;
}

TEST(ContactColours, ColoursShareNoDynamicBodyAndEachIsTheLowestFree) {
    b2World world(b2Vec2(0, -10));
    // The time-of-impact stage reuses the island buffers: without it they keep the pyramid's.
    world.SetContinuousPhysics(false);
    Pyramid(world);
    for (int i = 0; i < 3; ++i) world.Step(test::kDt, 8, 3);

    const auto& island = test::Internals(world).LastIsland();
    const int32 count = island.m_contactCount;
    ASSERT_GE(count, Colours::kMinContacts);
    const Colours& colours = island.m_colours;
    ASSERT_EQ(colours.Start(0), 0);
    ASSERT_EQ(colours.Start(Colours::kColourCount + 1), count);

    // The island's contacts, each once.
    std::set<const b2Contact*> distinct(island.m_contacts.begin(), island.m_contacts.begin() + count);
    EXPECT_EQ(static_cast<int32>(distinct.size()), count);

    int32 used = 0;
    for (int32 c = 0; c <= Colours::kColourCount; ++c) {
        const int32 begin = colours.Start(c), end = colours.Start(c + 1);
        ASSERT_LE(begin, end);
        if (end > begin && c < Colours::kColourCount) ++used;
        for (int32 i = begin; i < end; ++i) {
            const b2Contact* contact = island.m_contacts[static_cast<size_t>(i)];
            // No other contact of its colour touches its dynamic bodies (the overflow may).
            if (c < Colours::kColourCount) {
                for (int32 j = begin; j < end; ++j)
                    if (j != i) EXPECT_FALSE(ShareABody(contact, island.m_contacts[static_cast<size_t>(j)]));
            }
            // Every lower colour was taken by one of its bodies.
            for (int32 lower = 0; lower < c; ++lower) {
                bool taken = false;
                for (int32 j = colours.Start(lower); j < colours.Start(lower + 1) && !taken; ++j)
                    taken = ShareABody(contact, island.m_contacts[static_cast<size_t>(j)]);
                EXPECT_TRUE(taken) << "contact " << i << " of colour " << c << " could have had colour " << lower;
            }
        }
    }
    // A pyramid needs a handful of colours: a box touches at most six others and the ground.
    EXPECT_GE(used, 2);
    EXPECT_LE(used, 12);
}

std::vector<uint64_t> Hashes(b2TaskSystem* tasks, int workers) {
    b2World world(b2Vec2(0, -10));
    if (tasks != nullptr) {
        world.SetTaskSystem(tasks);
    } else {
        world.SetWorkerCount(workers);
    }
    Pyramid(world);
    std::vector<uint64_t> hashes;
    for (int i = 0; i < 20; ++i) {
        world.Step(test::kDt, 8, 3);
        hashes.push_back(world.Hash());
    }
    return hashes;
}

TEST(ContactColours, SameBitsWithAnyWorkers) {
    const std::vector<uint64_t> one = Hashes(nullptr, 1);
    for (const int workers : {2, 3, 8}) {
        EXPECT_EQ(Hashes(nullptr, workers), one) << workers << " workers, the world's own pool";
        b2ThreadPool pool(workers);
        EXPECT_EQ(Hashes(&pool, workers), one) << workers << " workers, a pool handed over";
    }
    golden::ScrambledTasks serial(4, 11);
    EXPECT_EQ(Hashes(&serial, 4), one) << "items run one after the other";
}

}  // namespace
}  // namespace lockbox
