// The golden replay corpus (tests/golden/replays): replays committed with the repository must
// verify in every later build and on every architecture. They are re-recorded on purpose,
// with tests/golden/replays/record.sh, only in the commit that bumps b2_determinismVersion.
#include <string>

#include "ReplayTestUtil.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::replay::testing {
namespace LOCKBOX_TEST_FILE {

std::string GoldenDir() {
    std::string here = __FILE__;
    return here.substr(0, here.find_last_of('/')) + "/../golden/replays/";
}

class GoldenReplay : public ::testing::TestWithParam<const char*> {};

TEST_P(GoldenReplay, Verifies) {
    const std::string path = GoldenDir() + GetParam();
    std::vector<uint8> bytes;
    ASSERT_TRUE(ReadFileBytes(path, bytes).ok()) << path;
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok()) << path << ": " << p.error.Describe()
                              << (p.error.code == ErrorCode::e_badEngine
                                      ? " (the determinism version changed: re-record the corpus with "
                                        "tests/golden/replays/record.sh in the same commit)"
                                      : "");
    const VerifyResult r = p.player->Verify();
    EXPECT_TRUE(r.ok) << path << ": " << r.message;
    EXPECT_EQ(r.frames, p.file.frameCount);
}

INSTANTIATE_TEST_SUITE_P(Corpus, GoldenReplay,
                         ::testing::Values("hello.lbr", "car.lbr", "rain.lbr", "bullet_stack_bullet.lbr",
                                           "ragdolls_raw.lbr", "vertical_stack_raw.lbr"));

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::replay::testing
