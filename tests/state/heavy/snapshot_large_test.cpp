// Save and Restore on the large scenes: a fresh world restored from an image has the same
// hash and bytes, and steps to the same bits for 20 frames.

#include <gtest/gtest.h>

#include "../SceneSyncGame.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::SceneRun;

class SnapshotLarge : public ::testing::TestWithParam<std::string_view> {};

TEST_P(SnapshotLarge, FreshWorldMatches) {
    SceneRun original(GetParam());
    ASSERT_TRUE(original.scene);
    original.Advance(30);
    const std::vector<uint8> image = original.world().Save();
    SceneRun joiner(GetParam(), /*build=*/false);
    const b2RestoreResult r = joiner.world().Restore(image);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(joiner.world().Save(), image);
    joiner.step = original.step;
    for (int i = 0; i < 20; ++i) {
        original.Advance();
        joiner.Advance();
        ASSERT_EQ(joiner.world().Hash(), original.world().Hash()) << "frame " << original.step;
    }
}

INSTANTIATE_TEST_SUITE_P(Large, SnapshotLarge, ::testing::ValuesIn(testing_state::SceneNames(/*large=*/true)),
                         [](const ::testing::TestParamInfo<std::string_view>& p) { return std::string(p.param); });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
