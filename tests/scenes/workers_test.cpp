// Worker counts never change the bits. Every light scene of the golden plan (library scenes and
// scene files), stepped to step 60 with the built-in pool at 2, 3 and 8 workers (the world's
// own, and handed over as a task system) and with a task system that runs blocks in a
// scrambled order, gives the hashes of tests/golden/
// hashes.txt. The heavy suite (heavy/workers_heavy_test.cpp) does the same for the four heavy
// scenes.
#include <string>

#include <gtest/gtest.h>

#include "../cross/GoldenScenes.h"
#include "../cross/ScrambledTasks.h"
#include "lockbox/dynamics/Tasks.h"

namespace lockbox::golden {
namespace LOCKBOX_TEST_FILE {

const std::string& GoldenFile() {
    static const std::string path = GoldenPathFrom(__FILE__, "/../golden/hashes.txt");
    return path;
}
const bool kSceneFileDirSet = (SceneFileDir() = GoldenPathFrom(__FILE__, "/../../scenes/files/handmade"), true);

// Checks every light scene to step 60 with the given world setup.
void ExpectGoldenLightScenes(const WorldSetup& setup) {
    ASSERT_TRUE(kSceneFileDirSet);
    const auto golden = ReadGolden(GoldenFile());
    ASSERT_FALSE(golden.empty()) << "cannot read " << GoldenFile();
    for (const ScenePlan& p : GoldenPlan()) {
        if (p.heavy) continue;
        const auto it = golden.find(p.name);
        ASSERT_NE(it, golden.end()) << p.name;
        std::string line;
        EXPECT_TRUE(MatchesGolden(p, 60, it->second, &line, setup))
            << "computed: " << line << "\ngolden:   " << it->second;
    }
}

class BuiltInPool : public ::testing::TestWithParam<int> {};

TEST_P(BuiltInPool, LightScenesMatchTheGoldenFile) {
    const int workers = GetParam();
    ExpectGoldenLightScenes([workers](b2World& world) {
        world.SetWorkerCount(workers);
        ASSERT_EQ(world.GetWorkerCount(), workers);
    });
}

#ifdef NDEBUG
INSTANTIATE_TEST_SUITE_P(Workers, BuiltInPool, ::testing::Values(2, 3, 8));
#else
// Sanitizer and debug builds (about 10x slower) check the pool at one count, and skip the
// scrambled order (single-threaded: the optimised builds' check suffices).
INSTANTIATE_TEST_SUITE_P(Workers, BuiltInPool, ::testing::Values(3));
#endif

// The world's own pool keeps most light scenes on the stepping thread (too little work to pay
// for waking threads); the same pool handed over as a game's task system gets every loop.
class PoolHandedOver : public ::testing::TestWithParam<int> {};

TEST_P(PoolHandedOver, LightScenesMatchTheGoldenFile) {
    b2ThreadPool pool(GetParam());
    ExpectGoldenLightScenes([&pool](b2World& world) { world.SetTaskSystem(&pool); });
}

#ifdef NDEBUG
INSTANTIATE_TEST_SUITE_P(Workers, PoolHandedOver, ::testing::Values(2, 8));
#else
INSTANTIATE_TEST_SUITE_P(Workers, PoolHandedOver, ::testing::Values(2));
#endif

#ifdef NDEBUG
TEST(ScrambledTaskSystem, LightScenesMatchTheGoldenFile) {
    ScrambledTasks tasks(4, 0x5eed);
    ExpectGoldenLightScenes([&tasks](b2World& world) { world.SetTaskSystem(&tasks); });
    // The parallel path ran, in many blocks.
    EXPECT_GT(tasks.Loops(), 100u);
    EXPECT_GT(tasks.Blocks(), 2 * tasks.Loops());
}
#endif

TEST(Workers, OneWorkerCreatesNoPoolAndGoingBackToOneDropsIt) {
    b2World world(b2Vec2(0, -10));
    EXPECT_EQ(world.GetWorkerCount(), 1);
    world.SetWorkerCount(3);
    EXPECT_EQ(world.GetWorkerCount(), 3);
    world.SetWorkerCount(100);
    EXPECT_EQ(world.GetWorkerCount(), 64);
    world.SetWorkerCount(1);
    EXPECT_EQ(world.GetWorkerCount(), 1);
    ScrambledTasks tasks(5, 1);
    world.SetTaskSystem(&tasks);
    EXPECT_EQ(world.GetWorkerCount(), 5);
    EXPECT_EQ(world.GetTaskSystem(), &tasks);
    world.SetTaskSystem(nullptr);
    EXPECT_EQ(world.GetWorkerCount(), 1);
}

TEST(Workers, PoolRunsEveryItemOnce) {
    for (const int workers : {1, 2, 3, 8}) {
        b2ThreadPool pool(workers);
        for (const int count : {1, 5, 64, 1000}) {
            std::vector<int> hits(static_cast<size_t>(count), 0);
            for (int repeat = 0; repeat < 20; ++repeat) {
                pool.ParallelFor(
                    count, 7,
                    [](int32 begin, int32 end, void* context) {
                        auto& h = *static_cast<std::vector<int>*>(context);
                        for (int32 i = begin; i < end; ++i) ++h[static_cast<size_t>(i)];
                    },
                    &hits);
            }
            for (const int h : hits) ASSERT_EQ(h, 20) << workers << " workers, " << count << " items";
        }
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::golden
