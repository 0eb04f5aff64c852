// Golden world hashes of the four heavy scenes (large_pyramid, many_pyramids, rain,
// joint_grid at steps 1, 60 and 120): the lines of tests/golden/hashes.txt that the fast
// suite's golden_hash_test.cpp skips. Regenerate the file with the fast suite.
#include <string>

#include <gtest/gtest.h>

#include "../../cross/GoldenScenes.h"

namespace lockbox::golden {
namespace LOCKBOX_TEST_FILE {

TEST(GoldenHashHeavy, HeavyScenesMatchTheGoldenFile) {
    const std::string path = GoldenPathFrom(__FILE__, "/../../golden/hashes.txt");
    const auto golden = ReadGolden(path);
    ASSERT_FALSE(golden.empty()) << "cannot read " << path;
    int checked = 0;
    for (const ScenePlan& p : GoldenPlan()) {
        if (!p.heavy) continue;
        const auto it = golden.find(p.name);
        if (it == golden.end()) {
            ADD_FAILURE() << p.name << ": no line in " << path;
            continue;
        }
        EXPECT_EQ(FormatLine(p, RunSceneHashes(p.name, p.steps)), it->second) << p.name;
        ++checked;
    }
    EXPECT_EQ(checked, 4);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::golden
