// diff narrows an injected divergence to frame, category, body and field; bisect finds the
// frame in O(log n) keyframe restores and the stage inside the step.
#include <cmath>

#include "ReplayTestUtil.h"
#include "lockbox/replay/Bisect.h"
#include "lockbox/replay/Diff.h"

namespace lockbox::replay::testing {
namespace LOCKBOX_TEST_FILE {

TEST(ReplayDiff, IdenticalRunsAreSame) {
    RecordOptions o;
    o.frames = 40;
    const std::vector<uint8> bytes = RecordScene("hello", o);
    Playback a(bytes), b(bytes);
    const DiffResult d = DiffReplays(*a.player, *b.player, a.file, b.file);
    EXPECT_TRUE(d.same) << d.Describe();
    EXPECT_EQ(d.firstInputFrame, -1);
}

TEST(ReplayDiff, InjectedFaultNamesFrameBodyAndField) {
    RecordOptions o;
    o.frames = 60;
    const std::vector<uint8> bytes = RecordScene("vertical_stack", o);
    Playback a(bytes), b(bytes);
    // Run B gets one raw unit of x velocity on body 7 at the end of the step of frame 23
    // (after the TOI phase), so no solver spreads it to the neighbours before the compare.
    NudgeHook nudge(23, 4, 7);
    b.player->SetStageHook(&nudge);
    const DiffResult d = DiffReplays(*a.player, *b.player, a.file, b.file);
    ASSERT_FALSE(d.same);
    EXPECT_EQ(d.frame, 23);
    EXPECT_EQ(d.where.category, b2HashCategory::e_bodies);
    EXPECT_EQ(d.where.bodyId, 7);
    ASSERT_EQ(d.fields.size(), 1u) << d.Describe();
    EXPECT_EQ(d.fields[0].field, "linearVelocity.x");
    EXPECT_NE(d.fields[0].a, d.fields[0].b);
    EXPECT_NE(d.Describe().find("DIFFER after frame 23"), std::string::npos) << d.Describe();
}

TEST(ReplayDiff, FaultBeforeTheStepSpreadsThroughContacts) {
    RecordOptions o;
    o.frames = 60;
    const std::vector<uint8> bytes = RecordScene("vertical_stack", o);
    Playback a(bytes), b(bytes);
    // Before the step the solver spreads the fault over the touching boxes: diff names the
    // first differing body in body-list order (newest first), with position and velocity.
    NudgeHook nudge(23, 0, 7);
    b.player->SetStageHook(&nudge);
    const DiffResult d = DiffReplays(*a.player, *b.player, a.file, b.file);
    ASSERT_FALSE(d.same);
    EXPECT_EQ(d.frame, 23);
    EXPECT_EQ(d.where.category, b2HashCategory::e_bodies);
    EXPECT_GE(d.where.bodyId, 0);
    EXPECT_FALSE(d.fields.empty());
}

TEST(ReplayDiff, DifferentInputsAreReported) {
    RecordOptions o;
    o.frames = 60;
    const std::vector<uint8> bytes = RecordScene("hello", o);
    Playback a(bytes), b(bytes);
    SceneInput spawn;
    spawn.action = e_actSpawnBox;
    spawn.a = 64;
    spawn.b = 1280;
    spawn.Encode(b.file.inputs.data() + 12 * b.file.FrameInputBytes());
    b.Rebind();
    const DiffResult d = DiffReplays(*a.player, *b.player, a.file, b.file);
    ASSERT_FALSE(d.same);
    EXPECT_EQ(d.firstInputFrame, 12);
    EXPECT_EQ(d.frame, 12);
}

TEST(ReplayDiff, FormatsValuesExactly) {
    EXPECT_EQ(FormatFixed(Fixed::FromRaw(0x18000)), "1.500000 (raw 0x00018000)");
    EXPECT_EQ(FormatFixed(Fixed::FromRaw(-1)), "-0.000015 (raw 0xffffffff)");
    EXPECT_EQ(FormatWide(Wide::FromRaw(int64_t{-3} << 31)), "-1.500000 (raw 0xfffffffe80000000)");
}

class BisectStage : public ::testing::TestWithParam<uint32> {};

TEST_P(BisectStage, FindsFrameAndStage) {
    const uint32 stage = GetParam();
    RecordOptions o;
    o.frames = 240;
    o.keyframeInterval = 15;  // 16 keyframes
    o.stageHashes = true;
    const std::vector<uint8> bytes = RecordScene("bullet_stack_bullet", o);
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok());
    NudgeHook nudge(157, stage);
    p.player->SetStageHook(&nudge);
    const BisectResult r = Bisect(*p.player);
    ASSERT_TRUE(r.error.ok()) << r.error.Describe();
    ASSERT_TRUE(r.diverged) << r.Describe();
    EXPECT_EQ(r.frame, 157) << r.Describe();
    EXPECT_EQ(r.stage, static_cast<int32>(stage)) << r.Describe();
    EXPECT_EQ(r.lowKeyframe, 150);
    EXPECT_EQ(r.highKeyframe, 165);
    // 17 stored states: ceil(log2(16)) = 4 probes, at most one restore each plus the scan's.
    EXPECT_LE(r.probes, 5);
    EXPECT_LE(r.restores, r.probes + 1);
    EXPECT_LT(r.framesPlayed, 2 * o.frames);
}

// Stage 4 (toi) needs a fast body at frame 157; the nudge after the TOI phase then shows up as
// kStageAfterToi or toi. The other stages are exact.
INSTANTIATE_TEST_SUITE_P(Stages, BisectStage, ::testing::Values(0u, 1u, 2u, 3u));

// Nudges the solver buffer of the first island of more than two bodies (the stack, not a
// spawned body an input may destroy later) at one phase of one frame, every time that frame is
// played: a velocity after the velocity iterations, or a position after the position
// iterations. 1/64 m/s or 1/64 m: a one-raw nudge can be rounded away by the resting stack's
// solver before the next keyframe, and bisect then rightly reports no divergence.
class IslandNudge : public StageHook {
public:
    IslandNudge(int32 frame, b2IslandPhase phase) : m_frame(frame), m_phase(phase) {}
    void OnStage(int32, uint32 stage, b2World&) override {
        if (stage == 0) m_done = false;  // a new pass over a frame
    }
    void OnIsland(int32 frame, b2IslandPhase phase, std::span<b2Body* const> bodies, std::span<b2Position> positions,
                  std::span<b2Velocity> velocities) override {
        if (frame != m_frame || phase != m_phase || m_done || bodies.size() <= 2) return;
        if (phase == b2IslandPhase::e_velocity) {
            velocities[0].v.x = Wide::FromRaw(velocities[0].v.x.Raw() + (int64_t{1024} << 16));
        } else {
            positions[0].c.x = Fixed::FromRaw(positions[0].c.x.Raw() + 1024);
        }
        m_done = true;
    }

private:
    int32 m_frame;
    b2IslandPhase m_phase;
    bool m_done = false;
};

class BisectSolvePhase : public ::testing::TestWithParam<b2IslandPhase> {};

TEST_P(BisectSolvePhase, SplitsTheSolveIntoVelocityAndPosition) {
    RecordOptions o;
    o.frames = 120;
    o.keyframeInterval = 20;
    o.stageHashes = true;
    Playback p(RecordScene("vertical_stack", o));
    ASSERT_TRUE(p.error.ok());
    ASSERT_FALSE(p.file.solveHashes.empty());
    IslandNudge nudge(71, GetParam());
    p.player->SetStageHook(&nudge);
    const BisectResult r = Bisect(*p.player);
    ASSERT_TRUE(r.diverged) << r.Describe();
    EXPECT_EQ(r.frame, 71) << r.Describe();
    EXPECT_EQ(r.stage, 2) << r.Describe();
    EXPECT_EQ(r.solvePhase, static_cast<int32>(GetParam())) << r.Describe();
    EXPECT_NE(r.Describe().find(SolvePhaseName(static_cast<uint32>(GetParam()))), std::string::npos) << r.Describe();
}

INSTANTIATE_TEST_SUITE_P(Phases, BisectSolvePhase,
                         ::testing::Values(b2IslandPhase::e_velocity, b2IslandPhase::e_position));

TEST(ReplayBisect, NoDivergenceWithoutFault) {
    RecordOptions o;
    o.frames = 60;
    o.keyframeInterval = 10;
    Playback p(RecordScene("hello", o));
    const BisectResult r = Bisect(*p.player);
    EXPECT_FALSE(r.diverged) << r.Describe();
}

TEST(ReplayBisect, WithoutStageHashesFindsTheFrame) {
    RecordOptions o;
    o.frames = 120;
    o.keyframeInterval = 20;
    Playback p(RecordScene("rain", o));
    NudgeHook nudge(66, 2);
    p.player->SetStageHook(&nudge);
    const BisectResult r = Bisect(*p.player);
    ASSERT_TRUE(r.diverged);
    EXPECT_EQ(r.frame, 66);
    EXPECT_EQ(r.stage, -1);
    EXPECT_NE(r.Describe().find("stage unknown"), std::string::npos);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::replay::testing
