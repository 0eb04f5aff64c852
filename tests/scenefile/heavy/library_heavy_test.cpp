// The heavy scenes of the library (thousands of bodies) through b2dJson: the round trip of
// library_roundtrip_test.cpp and the committed-file check of committed_files_test.cpp.
#include "../SceneFileTestUtil.h"

namespace lockbox::scenefile::test {
namespace LOCKBOX_TEST_FILE {

class HeavyScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(HeavyScenes, SameHashAndSameText) { CheckLibraryRoundTrip(GetParam()); }

TEST_P(HeavyScenes, CommittedFileLoadsToTheBuiltHashAndMatchesTheSaver) { CheckCommittedFile(GetParam()); }

INSTANTIATE_TEST_SUITE_P(Library, HeavyScenes, ::testing::ValuesIn(LibraryNames(true)),
                         [](const auto& p) { return p.param; });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenefile::test
