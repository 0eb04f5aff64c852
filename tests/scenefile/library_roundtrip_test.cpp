// Every light scene of the library round-trips through b2dJson: the world built from the saved
// text has the C++-built world's state hash (and keeps it for 20 steps), and saving the loaded
// world gives the same text again. The heavy scenes: heavy/library_heavy_test.cpp.
#include "SceneFileTestUtil.h"

namespace lockbox::scenefile::test {
namespace LOCKBOX_TEST_FILE {

class LibraryRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(LibraryRoundTrip, SameHashAndSameText) { CheckLibraryRoundTrip(GetParam()); }

INSTANTIATE_TEST_SUITE_P(LightScenes, LibraryRoundTrip, ::testing::ValuesIn(LibraryNames(false)),
                         [](const auto& p) { return p.param; });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenefile::test
