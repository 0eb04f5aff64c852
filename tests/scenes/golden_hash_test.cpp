// Golden world hashes: every light scene of the library, stepped from a fresh world, must give
// the b2WorldHash values recorded in tests/golden/hashes.txt (the four heavy scenes are checked
// by heavy/golden_hash_heavy_test.cpp). LOCKBOX_REGENERATE_GOLDEN=1 rewrites the whole file
// instead (after a deliberate change of results or of the hash definition).
#include <cstdlib>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "../cross/GoldenScenes.h"

namespace lockbox::golden {
namespace LOCKBOX_TEST_FILE {

// Optimised builds check every recorded step; debug and sanitizer builds (about 10x slower)
// check steps 1 and 60 only.
#ifdef NDEBUG
constexpr int kMaxStep = 600;
#else
constexpr int kMaxStep = 60;
#endif

/// tests/golden/hashes.txt, found relative to this source file.
std::string GoldenPath() { return GoldenPathFrom(__FILE__, "/../golden/hashes.txt"); }

// The hand-written scene files of the plan live in the source tree.
const bool kSceneFileDirSet = (SceneFileDir() = GoldenPathFrom(__FILE__, "/../../scenes/files/handmade"), true);

TEST(GoldenHash, EverySceneMatchesTheGoldenFile) {
    const std::vector<ScenePlan> plan = GoldenPlan();
    ASSERT_FALSE(plan.empty());
    if (Regenerating()) {
        std::ofstream out(GoldenPath(), std::ios::trunc);
        ASSERT_TRUE(out.good()) << GoldenPath();
        out << GoldenHeader();
        for (const ScenePlan& p : plan) out << FormatLine(p, RunSceneHashes(p.name, p.steps)) << "\n";
        GTEST_SKIP() << "regenerated " << GoldenPath();
    }
    const auto golden = ReadGolden(GoldenPath());
    ASSERT_FALSE(golden.empty()) << "cannot read " << GoldenPath();
    for (const ScenePlan& p : plan) {
        if (p.heavy) continue;  // heavy/golden_hash_heavy_test.cpp
        const auto it = golden.find(p.name);
        if (it == golden.end()) {
            ADD_FAILURE() << p.name << ": no line in " << GoldenPath();
            continue;
        }
        std::string line;
        EXPECT_TRUE(MatchesGolden(p, kMaxStep, it->second, &line))
            << "computed: " << line << "\ngolden:   " << it->second;
    }
    // Every golden line names a scene that still exists.
    for (const auto& [name, line] : golden) {
        bool known = false;
        for (const ScenePlan& p : plan) known = known || p.name == name;
        EXPECT_TRUE(known) << "golden line for unknown scene: " << line;
    }
}

TEST(GoldenHash, RunIsRepeatable) {
    const std::vector<int> steps{1, 30};
    EXPECT_EQ(RunSceneHashes("pyramid20", steps), RunSceneHashes("pyramid20", steps));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::golden
