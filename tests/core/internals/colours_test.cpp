// A large island's contacts (and, apart, its joints) are solved in colour order: each colour's
// constraints share no dynamic body (so workers may solve them at the same time), each has the
// lowest colour its bodies left free (the greedy rule, which makes the order a function of the
// island alone), and one that found every colour taken, or a joint that touches a body without
// mass, goes to the overflow, solved last. Within each run of a colour, contacts of one point
// come before those of two (for the contact lanes), each kind in island order. Then the order's promise: the same bits
// with one worker, with several, and with a task system that runs its items one after the other.

#include <algorithm>
#include <cstdint>
#include <set>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "../dynamics/DynamicsTestUtil.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox_internal/WorldInternals.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

// A pyramid of boxes on a static ground: one island of well over b2_minColouredConstraints
// contacts.
void Pyramid(b2World& world) { test::MakeBoxPyramid(world, 40, 50, 100); }

// A net of small discs hung from a static bar: each disc is jointed to its right and lower
// neighbours, the top row to the bar; one island of well over b2_minColouredConstraints joints.
void Net(b2World& world) {
    b2Body* bar = test::MakeStaticBox(world, 0, 30, 40, Fixed(0.25));
    constexpr int kColumns = 40, kRows = 20;
    std::vector<b2Body*> discs;
    for (int r = 0; r < kRows; ++r) {
        for (int c = 0; c < kColumns; ++c)
            discs.push_back(test::MakeDynamicCircle(world, Fixed(-20 + c), Fixed(29 - r), Fixed(0.25)));
    }
    auto at = [&](int r, int c) { return discs[static_cast<size_t>(r * kColumns + c)]; };
    for (int r = 0; r < kRows; ++r) {
        for (int c = 0; c < kColumns; ++c) {
            b2RevoluteJointDef jd;
            if (c + 1 < kColumns) {
                jd.Initialize(at(r, c), at(r, c + 1), at(r, c)->GetPosition());
                world.CreateJoint(&jd);
            }
            b2Body* above = r == 0 ? bar : at(r - 1, c);
            jd.Initialize(above, at(r, c), at(r, c)->GetPosition());
            world.CreateJoint(&jd);
        }
    }
}

// The dynamic bodies a contact or a joint may write.
std::vector<const b2Body*> Written(const b2Body* a, const b2Body* b) {
    std::vector<const b2Body*> bodies;
    for (const b2Body* x : {a, b})
        if (x->GetType() == b2_dynamicBody) bodies.push_back(x);
    return bodies;
}
std::vector<const b2Body*> Written(const b2Contact* c) {
    return Written(c->GetFixtureA()->GetBody(), c->GetFixtureB()->GetBody());
}
std::vector<const b2Body*> Written(const b2Joint* j) { return Written(j->GetBodyA(), j->GetBodyB()); }

template <class Item>
bool ShareABody(const Item* a, const Item* b) {
    for (const b2Body* x : Written(a))
        for (const b2Body* y : Written(b))
            if (x == y) return true;
    return false;
}

// Checks the colour order of items[0, count); returns the number of colours used.
template <class Item>
int32 ExpectColourOrder(const b2Colours<Item>& colours, Item* const* items, int32 count) {
    EXPECT_EQ(colours.Start(0), 0);
    EXPECT_EQ(colours.Start(b2_colourCount + 1), count);
    // The island's items, each once.
    std::set<const Item*> distinct(items, items + count);
    EXPECT_EQ(static_cast<int32>(distinct.size()), count);

    int32 used = 0;
    for (int32 c = 0; c <= b2_colourCount; ++c) {
        const int32 begin = colours.Start(c), end = colours.Start(c + 1);
        EXPECT_LE(begin, end);
        if (end > begin && c < b2_colourCount) ++used;
        for (int32 i = begin; i < end; ++i) {
            // No other item of its colour touches its dynamic bodies (the overflow may).
            if (c < b2_colourCount) {
                for (int32 j = begin; j < end; ++j) {
                    if (j != i) {
                        EXPECT_FALSE(ShareABody(items[i], items[j]));
                    }
                }
            }
            // Every lower colour was taken by one of its bodies, unless it may not be coloured
            // (a joint with a static end).
            if (c == b2_colourCount && Written(items[i]).size() < 2 && std::is_same_v<Item, b2Joint>) continue;
            for (int32 lower = 0; lower < c; ++lower) {
                bool taken = false;
                for (int32 j = colours.Start(lower); j < colours.Start(lower + 1) && !taken; ++j)
                    taken = ShareABody(items[i], items[j]);
                EXPECT_TRUE(taken) << "item " << i << " of colour " << c << " could have had colour " << lower;
            }
        }
    }
    return used;
}

// Builds a scene in world, steps it three times and returns its last solved island. The
// time-of-impact stage reuses the island buffers, so continuous physics is off: they keep the
// scene's island.
const auto& SteppedIsland(b2World& world, void (*build)(b2World&)) {
    world.SetContinuousPhysics(false);
    build(world);
    for (int i = 0; i < 3; ++i) world.Step(test::kDt, 8, 3);
    return test::Internals(world).LastIsland();
}

TEST(Colours, ContactsShareNoDynamicBodyWithinAColourAndEachIsTheLowestFree) {
    b2World world(b2Vec2(0, -10));
    const auto& island = SteppedIsland(world, Pyramid);
    ASSERT_GE(island.m_contactCount, b2_minColouredConstraints);
    const int32 used = ExpectColourOrder(island.m_contactColours, island.m_contacts.data(), island.m_contactCount);
    // A pyramid needs a handful of colours: a box touches at most six others and the ground.
    EXPECT_GE(used, 2);
    EXPECT_LE(used, 12);
}

TEST(Colours, JointsShareNoDynamicBodyWithinAColourAndThoseOnTheBarComeLast) {
    b2World world(b2Vec2(0, -10));
    const auto& island = SteppedIsland(world, Net);
    ASSERT_GE(island.m_jointCount, b2_minColouredConstraints);
    const int32 used = ExpectColourOrder(island.m_jointColours, island.m_joints.data(), island.m_jointCount);
    // A disc has at most four joints: four colours, and a few more for the greedy order.
    EXPECT_GE(used, 4);
    EXPECT_LE(used, 8);
    // The 40 joints to the static bar are the overflow.
    EXPECT_EQ(island.m_jointColours.Start(b2_colourCount + 1) - island.m_jointColours.Start(b2_colourCount), 40);
}

// Items of the greedy order alone: what each writes, of which kind, and its island position.
struct Item {
    int32 id = 0;
    int32 a = -1, b = -1;
    bool colourable = true, secondKind = false;
};

TEST(Colours, EachRunOfAColourPutsTheFirstKindFirstAndKeepsIslandOrderWithinAKind) {
    // A chain of 3,000 items over 600 slots, item i writing slots i and i + 1 (mod 600), of
    // pseudo-random kinds, and every 97th item bound to the overflow.
    constexpr int32 kCount = 3000, kSlots = 600;
    std::vector<Item> storage(kCount);
    std::vector<Item*> items;
    uint32 seed = 12345;
    for (int32 i = 0; i < kCount; ++i) {
        seed = seed * 1664525u + 1013904223u;
        storage[static_cast<size_t>(i)] = {i, i % kSlots, (i + 1) % kSlots, i % 97 != 0, (seed >> 16) % 3 == 0};
        items.push_back(&storage[static_cast<size_t>(i)]);
    }
    b2Colours<Item> colours;
    colours.Order(items.data(), kCount, kSlots, [&](size_t i) {
        const Item& item = storage[i];
        return b2Colours<Item>::Written{item.a, item.b, item.colourable, item.secondKind};
    });

    int32 runs = 0, mixedRuns = 0;
    for (int32 c = 0; c < b2_colourCount; ++c) {
        for (int32 run = colours.Start(c); run < colours.Start(c + 1); run += b2Colours<Item>::kRun) {
            const int32 end = std::min(run + b2Colours<Item>::kRun, colours.Start(c + 1));
            ++runs;
            bool seenSecond = false, seenFirst = false;
            int32 lastId[2] = {-1, -1};
            for (int32 k = run; k < end; ++k) {
                const Item& item = *items[static_cast<size_t>(k)];
                EXPECT_FALSE(seenSecond && !item.secondKind) << "colour " << c << ", position " << k;
                seenSecond = seenSecond || item.secondKind;
                seenFirst = seenFirst || !item.secondKind;
                int32& last = lastId[item.secondKind ? 1 : 0];
                EXPECT_GT(item.id, last) << "colour " << c << ", position " << k;
                last = item.id;
            }
            if (seenFirst && seenSecond) ++mixedRuns;
        }
    }
    EXPECT_GE(runs, 24);
    EXPECT_GE(mixedRuns, 12);  // the rule was exercised
    // Runs follow one another in island order: every item of a run comes after every item of
    // the run before it in the same colour.
    for (int32 c = 0; c < b2_colourCount; ++c) {
        int32 previousMax = -1;
        for (int32 run = colours.Start(c); run < colours.Start(c + 1); run += b2Colours<Item>::kRun) {
            const int32 end = std::min(run + b2Colours<Item>::kRun, colours.Start(c + 1));
            int32 runMin = kCount, runMax = -1;
            for (int32 k = run; k < end; ++k) {
                runMin = std::min(runMin, items[static_cast<size_t>(k)]->id);
                runMax = std::max(runMax, items[static_cast<size_t>(k)]->id);
            }
            EXPECT_GT(runMin, previousMax) << "colour " << c;
            previousMax = runMax;
        }
    }
    // The overflow keeps island order, whatever the kinds.
    const int32 overflow = colours.Start(b2_colourCount);
    EXPECT_EQ(colours.Start(b2_colourCount + 1) - overflow, (kCount + 96) / 97);
    for (int32 k = overflow + 1; k < kCount; ++k)
        EXPECT_LT(items[static_cast<size_t>(k) - 1]->id, items[static_cast<size_t>(k)]->id);
}

std::vector<uint64_t> Hashes(void (*build)(b2World&), b2TaskSystem* tasks, int workers) {
    b2World world(b2Vec2(0, -10));
    if (tasks != nullptr) {
        world.SetTaskSystem(tasks);
    } else {
        world.SetWorkerCount(workers);
    }
    build(world);
    return test::StepHashes(world, 20);
}

TEST(Colours, SameBitsWithAnyWorkers) {
    for (auto* build : {&Pyramid, &Net}) {
        const std::vector<uint64_t> one = Hashes(build, nullptr, 1);
        for (const int workers : {2, 3, 8}) {
            EXPECT_EQ(Hashes(build, nullptr, workers), one) << workers << " workers, the world's own pool";
            b2ThreadPool pool(workers);
            EXPECT_EQ(Hashes(build, &pool, workers), one) << workers << " workers, a pool handed over";
        }
        golden::ScrambledTasks serial(4, 11);
        EXPECT_EQ(Hashes(build, &serial, 4), one) << "items run one after the other";
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
