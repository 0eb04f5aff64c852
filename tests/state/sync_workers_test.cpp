// The sync test with several workers: rollbacks (portable images and rollback frames, with
// mispredicted branches) reproduce every frame, and the world ends in the same state as the
// same sync test run on one worker. The worker count is not state, so restoring never has to
// know it.

#include <gtest/gtest.h>

#include "SceneSyncGame.h"
#include "lockbox/dynamics/Tasks.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::SceneRun;
using testing_state::SceneSyncGame;

#ifdef NDEBUG
constexpr int32 kFrames = 40;
#else
constexpr int32 kFrames = 16;  // sanitizer and debug builds are ~10x slower
#endif

// Runs the mispredicting sync test on `name` with `workers` threads; returns the final hash.
// The world's own pool keeps small scenes on the stepping thread, so a pool handed over as the
// game's task system (every loop on real threads) is the default here.
uint64 SyncTestOn(std::string_view name, int32 workers, bool useFrames, bool ownPool = false) {
    b2ThreadPool pool(ownPool ? 1 : workers);  // a pool of one creates no thread
    SceneRun run(name);
    EXPECT_TRUE(run.scene) << name;
    if (!run.scene) return 0;
    if (ownPool)
        run.world().SetWorkerCount(workers);
    else
        run.world().SetTaskSystem(&pool);
    SceneSyncGame game(run);
    SyncTestConfig config;
    config.mispredict = true;
    config.frames = useFrames;
    config.step = game.Step();
    SyncTest test(run.world(), game, {}, config);
    const SyncTestResult r = test.Run(kFrames);
    EXPECT_TRUE(r.ok) << name << " at " << workers << " workers: " << r.message;
    EXPECT_EQ(r.rollbacks, kFrames - 7);
    return b2WorldHash(run.world());
}

class SyncWorkers : public ::testing::TestWithParam<std::string_view> {};

TEST_P(SyncWorkers, MispredictingRollbacksMatchOneWorker) {
    const uint64 one = SyncTestOn(GetParam(), 1, /*useFrames=*/false);
    EXPECT_EQ(SyncTestOn(GetParam(), 3, /*useFrames=*/false), one);
    EXPECT_EQ(SyncTestOn(GetParam(), 2, /*useFrames=*/true), one);
    EXPECT_EQ(SyncTestOn(GetParam(), 2, /*useFrames=*/true, /*ownPool=*/true), one);
}

// Scenes with enough contacts for the parallel narrow phase, a sensor-free stack and a
// jointed scene.
INSTANTIATE_TEST_SUITE_P(Scenes, SyncWorkers, ::testing::Values("pyramid20", "ragdolls", "bullet_wall_bullet"),
                         [](const ::testing::TestParamInfo<std::string_view>& param) {
                             return std::string(param.param);
                         });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
