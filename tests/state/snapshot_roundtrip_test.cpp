// Save and Restore on every library scene: a restored world (in place or fresh) has the same
// hash and the same bytes, and steps to the same bits as the world that was saved.

#include <gtest/gtest.h>

#include "SceneSyncGame.h"
#include "StateTestUtil.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::DescribeDifference;
using testing_state::SceneRun;

class SnapshotRoundTrip : public ::testing::TestWithParam<std::string_view> {};

constexpr int kFrames = 90;
int FramesFor(const scenes::SceneInfo&) { return kFrames; }

TEST_P(SnapshotRoundTrip, FreshWorldMatchesBitsAndBytes) {
    SceneRun original(GetParam());
    ASSERT_TRUE(original.scene) << GetParam();
    const int frames = FramesFor(original.scene->Info());
    original.Advance(frames / 2);
    const std::vector<uint8> image = original.world().Save();

    // Late join: a fresh, empty world; the scene object only supplies pre-step actions.
    SceneRun joiner(GetParam(), /*build=*/false);
    const b2RestoreResult result = joiner.world().Restore(image);
    ASSERT_TRUE(result.ok()) << b2SnapshotErrorName(result.error) << ": " << result.message;
    EXPECT_EQ(joiner.world().Hash(), original.world().Hash()) << DescribeDifference(joiner.world(), original.world());
    EXPECT_EQ(joiner.world().Save(), image);

    // Step both with the scene's frames: bit-identical throughout.
    joiner.step = original.step;
    for (int i = 0; i < frames - frames / 2; ++i) {
        original.Advance();
        joiner.Advance();
        ASSERT_EQ(joiner.world().Hash(), original.world().Hash())
            << "frame " << original.step << ": " << DescribeDifference(joiner.world(), original.world());
    }
}

TEST_P(SnapshotRoundTrip, InPlaceRollbackKeepsAddressesAndBits) {
    SceneRun run(GetParam());
    ASSERT_TRUE(run.scene) << GetParam();
    const int frames = FramesFor(run.scene->Info());
    run.Advance(frames / 3);
    const int savedStep = run.step;
    const std::vector<uint8> image = run.world().Save();
    const uint64 savedHash = run.world().Hash();
    std::vector<const b2Body*> bodies;
    for (const b2Body* b = run.world().GetBodyList(); b; b = b->GetNext()) bodies.push_back(b);

    // The reference continuation.
    run.Advance(frames - savedStep);
    const uint64 endHash = run.world().Hash();

    // Roll back and replay the same frames.
    const b2RestoreResult result = run.world().Restore(image);
    ASSERT_TRUE(result.ok()) << b2SnapshotErrorName(result.error) << ": " << result.message;
    EXPECT_EQ(run.world().Hash(), savedHash);
    size_t i = 0;
    for (const b2Body* b = run.world().GetBodyList(); b; b = b->GetNext(), ++i) {
        ASSERT_LT(i, bodies.size());
        EXPECT_EQ(b, bodies[i]) << "body " << b->GetId() << " moved in memory";
    }
    EXPECT_EQ(i, bodies.size());
    run.step = savedStep;
    run.Advance(frames - savedStep);
    EXPECT_EQ(run.world().Hash(), endHash);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SnapshotRoundTrip, ::testing::ValuesIn(testing_state::SceneNames(/*large=*/false)),
                         [](const ::testing::TestParamInfo<std::string_view>& p) { return std::string(p.param); });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
