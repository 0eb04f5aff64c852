// The scene library exported as b2dJson files (scenes/files/<scene>.json, written by
// the saver): each loads to the C++-built scene's state hash, and is exactly what the saver
// writes for that scene today. LOCKBOX_REGENERATE_SCENE_FILES=1 rewrites them instead (after a
// deliberate change of a scene or of the saver's output; run the heavy suite too, which holds
// the heavy scenes' files).
#include "SceneFileTestUtil.h"

namespace lockbox::scenefile::test {
namespace LOCKBOX_TEST_FILE {

class CommittedSceneFiles : public ::testing::TestWithParam<std::string> {};

TEST_P(CommittedSceneFiles, LoadToTheBuiltHashAndMatchTheSaver) { CheckCommittedFile(GetParam()); }

INSTANTIATE_TEST_SUITE_P(LightScenes, CommittedSceneFiles, ::testing::ValuesIn(LibraryNames(false)),
                         [](const auto& p) { return p.param; });

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenefile::test
