// Worker counts never change the bits, for the four heavy scenes (large_pyramid, many_pyramids,
// rain, joint_grid) that the fast suite's workers_test.cpp leaves out: to step 60 at 2, 3 and 8
// workers of the built-in pool and with a task system that runs blocks in a scrambled order,
// each gives the hashes of tests/golden/hashes.txt. And every scene, light and heavy, at 2
// workers to its last recorded step (600, or 120 for the heavy ones): long enough for stacks to
// settle and sleep, islands to merge and split, while the islands are solved in parallel.
#include <climits>
#include <string>

#include <gtest/gtest.h>

#include "../../cross/GoldenScenes.h"
#include "../../cross/ScrambledTasks.h"

namespace lockbox::golden {
namespace LOCKBOX_TEST_FILE {

void ExpectGoldenHeavyScenes(const WorldSetup& setup) {
    const std::string path = GoldenPathFrom(__FILE__, "/../../golden/hashes.txt");
    const auto golden = ReadGolden(path);
    ASSERT_FALSE(golden.empty()) << "cannot read " << path;
    int checked = 0;
    for (const ScenePlan& p : GoldenPlan()) {
        if (!p.heavy) continue;
        const auto it = golden.find(p.name);
        ASSERT_NE(it, golden.end()) << p.name;
        std::string line;
        EXPECT_TRUE(MatchesGolden(p, 60, it->second, &line, setup))
            << "computed: " << line << "\ngolden:   " << it->second;
        ++checked;
    }
    EXPECT_EQ(checked, 4);
}

class BuiltInPoolHeavy : public ::testing::TestWithParam<int> {};

TEST_P(BuiltInPoolHeavy, HeavyScenesMatchTheGoldenFile) {
    const int workers = GetParam();
    ExpectGoldenHeavyScenes([workers](b2World& world) { world.SetWorkerCount(workers); });
}

INSTANTIATE_TEST_SUITE_P(Workers, BuiltInPoolHeavy, ::testing::Values(2, 3, 8));

TEST(ScrambledTaskSystemHeavy, HeavyScenesMatchTheGoldenFile) {
    ScrambledTasks tasks(3, 0xb10c);
    ExpectGoldenHeavyScenes([&tasks](b2World& world) { world.SetTaskSystem(&tasks); });
    EXPECT_GT(tasks.Loops(), 100u);
}

TEST(WorkersFullLength, EverySceneMatchesTheGoldenFileToItsLastStep) {
    SceneFileDir() = GoldenPathFrom(__FILE__, "/../../../scenes/files/handmade");
    const std::string path = GoldenPathFrom(__FILE__, "/../../golden/hashes.txt");
    const auto golden = ReadGolden(path);
    ASSERT_FALSE(golden.empty()) << "cannot read " << path;
    for (const ScenePlan& p : GoldenPlan()) {
        const auto it = golden.find(p.name);
        ASSERT_NE(it, golden.end()) << p.name;
        std::string line;
        EXPECT_TRUE(MatchesGolden(p, INT_MAX, it->second, &line, [](b2World& world) { world.SetWorkerCount(2); }))
            << "computed: " << line << "\ngolden:   " << it->second;
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::golden
