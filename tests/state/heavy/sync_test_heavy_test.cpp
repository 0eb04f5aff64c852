// SyncTest over every scene of the library at full length: 600 frames for the light
// scenes and 120 for the heavy ones (many_pyramids: 64 unless LOCKBOX_TEST_FULL=1), with and
// without mispredicted branches.

#include <cstdlib>
#include <string_view>

#include <gtest/gtest.h>

#include "../SceneSyncGame.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::RunSceneSyncTest;

class SceneSyncFull : public ::testing::TestWithParam<std::string_view> {};

// Light scenes: 600 frames, a rollback after every frame. Large scenes: 120 frames, rollback
// windows of 8 tiling the run (every frame re-simulated and checked once; a rollback after
// every frame would take many_pyramids ~30 minutes). many_pyramids (22,000 bodies) runs 64 of
// its 120 frames unless LOCKBOX_TEST_FULL=1: its four full runs took 155 s of CPU, a sixth of
// CI's release tests, and its pyramids start touching, so 64 frames already hold every contact's
// creation and the stacks settling under load.
struct Plan {
    int32 frames;
    int32 stride;
};
bool FullLength() {
    const char* v = std::getenv("LOCKBOX_TEST_FULL");
    return v != nullptr && std::string_view(v) == "1";
}
Plan PlanFor(std::string_view name) {
    auto scene = scenes::MakeLockboxScene(name);
    if (scene && testing_state::IsLargeScene(*scene)) return {name == "many_pyramids" && !FullLength() ? 64 : 120, 8};
    return {600, 1};
}

TEST_P(SceneSyncFull, Rollback) {
    const Plan p = PlanFor(GetParam());
    const SyncTestResult r = RunSceneSyncTest(GetParam(), p.frames, false, p.stride);
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.framesResimulated, p.stride == 1 ? (p.frames - 7) * 8 : (p.frames / 8) * 8);
}

TEST_P(SceneSyncFull, Mispredict) {
    const Plan p = PlanFor(GetParam());
    const SyncTestResult r = RunSceneSyncTest(GetParam(), p.frames, true, p.stride);
    EXPECT_TRUE(r.ok) << r.message;
}

// The same through rollback frames (SaveFrame/RestoreFrame): their fast path between
// structural changes, their undo of spawn-only branches, and their structure image when a
// branch changed anything else.
TEST_P(SceneSyncFull, RollbackThroughFrames) {
    const Plan p = PlanFor(GetParam());
    const SyncTestResult r = RunSceneSyncTest(GetParam(), p.frames, false, p.stride, /*useFrames=*/true);
    EXPECT_TRUE(r.ok) << r.message;
}

TEST_P(SceneSyncFull, MispredictThroughFrames) {
    const Plan p = PlanFor(GetParam());
    const SyncTestResult r = RunSceneSyncTest(GetParam(), p.frames, true, p.stride, /*useFrames=*/true);
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_GT(r.frameRestores.undoneCreations, 0u);
    EXPECT_GT(r.frameRestores.restoredStructure, 0u);
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SceneSyncFull, ::testing::ValuesIn(scenes::AllSceneNames()),
                         [](const ::testing::TestParamInfo<std::string_view>& p) { return std::string(p.param); });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
