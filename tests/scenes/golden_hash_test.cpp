// Golden world hashes: every scene of the library, stepped from a fresh world, must give the
// b2WorldHash values recorded in tests/golden/hashes.txt. LOCKBOX_REGENERATE_GOLDEN=1
// rewrites the file instead (after a deliberate change of results or of the hash definition).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "../cross/GoldenScenes.h"

namespace lockbox::golden {
namespace {

/// tests/golden/hashes.txt, found next to this source file.
std::string GoldenPath() {
    std::string here = __FILE__;
    const size_t slash = here.find_last_of("/\\");
    const std::string dir = slash == std::string::npos ? std::string(".") : here.substr(0, slash);
    return dir + "/../golden/hashes.txt";
}

bool Regenerating() {
    const char* v = std::getenv("LOCKBOX_REGENERATE_GOLDEN");
    return v != nullptr && std::string(v) == "1";
}

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
        const auto it = golden.find(p.name);
        if (it == golden.end()) {
            ADD_FAILURE() << p.name << ": no line in " << GoldenPath();
            continue;
        }
        EXPECT_EQ(FormatLine(p, RunSceneHashes(p.name, p.steps)), it->second) << p.name;
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

}  // namespace
}  // namespace lockbox::golden
