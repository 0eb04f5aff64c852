// Record then verify every scene of the scene library, with two players'
// scripted inputs, keyframes and fencepost hashes; seek to the middle equals straight play.
#include "../ReplayTestUtil.h"
#include "lockbox/replay/Bisect.h"
#include "lockbox/scenes/Registry.h"

namespace lockbox::replay::testing {
namespace LOCKBOX_TEST_FILE {

class EveryScene : public ::testing::TestWithParam<std::string_view> {};

TEST_P(EveryScene, RecordVerifySeek) {
    // The four big scenes (thousands of bodies) get fewer frames and no fencepost hashes, so
    // the suite stays within about a minute.
    const std::string_view name = GetParam();
    const bool big = name == "large_pyramid" || name == "many_pyramids" || name == "joint_grid" || name == "tumbler";
    RecordOptions o;
    o.frames = big ? 24 : 120;
    o.keyframeInterval = big ? 8 : 40;
    o.stageHashes = !big;
    std::vector<uint64> hashes;
    const std::vector<uint8> bytes = RecordScene(name, o, &hashes);
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok()) << p.error.Describe();
    const VerifyResult r = p.player->Verify();
    EXPECT_TRUE(r.ok) << r.message;
    const int32 middle = o.frames / 2 + 1;
    ASSERT_TRUE(p.player->Seek(middle).ok());
    EXPECT_EQ(p.game->world().Hash(), hashes[static_cast<size_t>(middle - 1)]);
    if (!big) {
        EXPECT_FALSE(Bisect(*p.player).diverged);
    }
}

INSTANTIATE_TEST_SUITE_P(Library, EveryScene, ::testing::ValuesIn(scenes::AllSceneNames()),
                         [](const ::testing::TestParamInfo<std::string_view>& p) { return std::string(p.param); });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::replay::testing
