// The island search marks the joints it takes with a number that changes every step instead of
// clearing a flag on every joint. When that number wraps around, the marks left on the joints
// must not be taken for the new step's.

#include <gtest/gtest.h>

#include "../../state/StateTestUtil.h"
#include "lockbox_internal/WorldInternals.h"

namespace lockbox {
namespace {

using testing_state::DescribeDifference;
using testing_state::SceneRun;

TEST(IslandJointMark, WrappingAroundChangesNoStep) {
    for (const char* name : {"ragdolls", "chain60", "joint_grid"}) {
        SceneRun reference(name);
        SceneRun wrapped(name);
        ASSERT_TRUE(reference.scene && wrapped.scene) << name;
        // After one step every joint in an island carries mark 1; the next search's mark wraps
        // around to 0 and starts again at 1, which the joints would already carry.
        reference.Advance();
        wrapped.Advance();
        test::SetIslandJointMark(wrapped.world(), 0xFFFFFFFFu);
        for (int frame = 1; frame < 6; ++frame) {
            reference.Advance();
            wrapped.Advance();
            ASSERT_EQ(DescribeDifference(reference.world(), wrapped.world()), "") << name << ", frame " << frame;
        }
    }
}

}  // namespace
}  // namespace lockbox
