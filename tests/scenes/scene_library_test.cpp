// Scene library: every scene builds and runs 60 steps on lockbox without an assert, builds the
// same bits twice, and the SCENES.md scenes also build and run through the float adapter.
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "lockbox/scenes/LockboxScenes.h"
// After the lockbox headers: float Box2D's macros would break them (see the adapter).
#include "lockbox/scenes/Box2DFloatEngine.h"

namespace lockbox::scenes {
namespace LOCKBOX_TEST_FILE {

int g_asserts = 0;

void CountingHandler(const char* expr, const char* msg, const char* file, int line) {
    ++g_asserts;
    ADD_FAILURE() << "lockbox assert: " << expr << " (" << msg << ") at " << file << ":" << line;
}

/// Installs the counting assert handler for one test.
class SceneTest : public ::testing::TestWithParam<std::string_view> {
protected:
    void SetUp() override {
        g_asserts = 0;
        previous_ = b2SetAssertHandler(&CountingHandler);
    }
    void TearDown() override { b2SetAssertHandler(previous_); }

private:
    b2AssertHandler previous_ = nullptr;
};

/// A lockbox scene sized for the fast suite: the three heavy SCENES.md scenes shrink (their
/// full sizes run in heavy/); everything else is built as defined.
std::unique_ptr<LockboxScene> MakeSmall(std::string_view name) {
    if (name == "large_pyramid") return std::make_unique<LargePyramidScene<LockboxEngine>>(8);
    if (name == "many_pyramids") return std::make_unique<ManyPyramidsScene<LockboxEngine>>(1, 2);
    if (name == "joint_grid") {
        if constexpr (JointGridScene<LockboxEngine>::kAvailable)
            return std::make_unique<JointGridScene<LockboxEngine>>(8);
        return nullptr;
    }
    return MakeLockboxScene(name);
}

/// Runs `steps` steps of a scene on a fresh world; returns the world hash.
uint64_t RunHash(std::string_view name, int steps, std::vector<Metric>* metrics = nullptr) {
    LockboxEngine e;
    auto scene = MakeSmall(name);
    RunSettings s;
    s.steps = steps;
    auto m = RunScene(e, *scene, s);
    if (metrics) *metrics = m;
    return HashWorld(e.world());
}

TEST_P(SceneTest, Runs60StepsWithoutAssert) {
    const std::string_view name = GetParam();
    auto scene = MakeSmall(name);
    if (!scene) GTEST_SKIP() << name << ": needs joints the lockbox world does not offer yet";
    EXPECT_EQ(scene->Info().name.substr(0, 6), name.substr(0, 6));
    LockboxEngine e;
    RunSettings s;
    s.steps = 60;
    const auto metrics = RunScene(e, *scene, s);
    EXPECT_EQ(g_asserts, 0);
    EXPECT_GT(e.world().GetBodyCount(), 0);
    for (const Metric& m : metrics) EXPECT_TRUE(std::isfinite(m.value)) << name << " " << m.name;
}

TEST_P(SceneTest, SameSceneTwiceGivesIdenticalBits) {
    const std::string_view name = GetParam();
    if (!MakeSmall(name)) GTEST_SKIP() << name << ": needs joints the lockbox world does not offer yet";
    const uint64_t a = RunHash(name, 60);
    const uint64_t b = RunHash(name, 60);
    EXPECT_EQ(a, b) << name;
    EXPECT_NE(a, 0u);
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SceneTest, ::testing::ValuesIn(AllSceneNames()),
                         [](const auto& p) { return std::string(p.param); });

TEST(SceneLibrary, RegistryKnowsEverySharedScene) {
    EXPECT_EQ(SharedSceneNames().size(), 15u);  // nine scenes plus bullet's six variants
    EXPECT_GE(OwnSceneNames().size(), 4u);
    EXPECT_EQ(MakeLockboxScene("no_such_scene"), nullptr);
    for (auto name : {"hello", "vertical_stack", "pyramid20", "large_pyramid", "many_pyramids", "rain"})
        EXPECT_NE(MakeLockboxScene(name), nullptr) << name;
}

TEST(SceneLibrary, InfoMatchesScenesMd) {
    const SceneInfo& h = HelloScene<LockboxEngine>::kInfo;
    EXPECT_EQ(h.steps, 60);
    EXPECT_EQ(h.velocityIterations, 6);
    EXPECT_EQ(h.positionIterations, 2);
    EXPECT_FALSE(LargePyramidScene<LockboxEngine>::kInfo.allowSleep);
    EXPECT_FALSE(ManyPyramidsScene<LockboxEngine>::kInfo.allowSleep);
    EXPECT_FALSE(JointGridScene<LockboxEngine>::kInfo.allowSleep);
    EXPECT_EQ(RainScene<LockboxEngine>::kInfo.steps, 1000);
    EXPECT_EQ(TumblerScene<LockboxEngine>::kInfo.steps, 750);
    EXPECT_EQ(LockboxEngine::TimeStep(60).Raw(), 1092);
    EXPECT_EQ(Box2DFloatEngine::TimeStep(60), 1092.0f / 65536.0f);
    EXPECT_EQ(Box2DFloatEngine::TimeStep(240), 273.0f / 65536.0f);
    for (int hz : {30, 60, 120, 240})
        EXPECT_EQ(static_cast<double>(LockboxEngine::TimeStep(hz).Raw()) / 65536.0, Box2DFloatEngine::TimeStep(hz));
}

TEST(SceneLibrary, BodyCountsMatchScenesMd) {
    struct Case {
        const char* name;
        int dynamicBodies;
    };
    for (const Case& c :
         {Case{"hello", 1}, Case{"vertical_stack", 20}, Case{"pyramid20", 210}, Case{"bullet_stack_bullet", 11}}) {
        LockboxEngine e;
        auto scene = MakeLockboxScene(c.name);
        scene->Build(e);
        EXPECT_EQ(DynamicCount(e), c.dynamicBodies) << c.name;
    }
    LockboxEngine e;
    ManyPyramidsScene<LockboxEngine> many(2, 3);
    many.Build(e);
    EXPECT_EQ(DynamicCount(e), 6 * 55);
}

TEST(SceneLibrary, RainSpawns2000BodiesBy632) {
    LockboxEngine e;
    RainScene<LockboxEngine> rain;
    for (int s = 0; s < 640; ++s) rain.BeforeStep(e, s);
    EXPECT_EQ(DynamicCount(e), 2000);
    rain.BeforeStep(e, 640);
    EXPECT_EQ(DynamicCount(e), 2000);
}

TEST(SceneLibrary, HelloBoxComesToRestOnTheGround) {
    LockboxEngine e;
    HelloScene<LockboxEngine> hello;
    RunSettings s;
    s.steps = 120;
    RunScene(e, hello, s);
    // The box rests with its centre 1 m above the ground's top face (plus two 0.01 m skins).
    EXPECT_NEAR(hello.Box()->GetPosition().y.ToDouble(), 1.0, 0.03);
    EXPECT_NEAR(hello.Box()->GetPosition().x.ToDouble(), 0.0, 1e-3);
}

/// The shared scenes also run through the float adapter (same definitions, 60 steps).
TEST(FloatAdapter, SharedScenesBuildAndRun) {
    for (auto name : SharedSceneNames()) {
        Box2DFloatEngine e;
        std::unique_ptr<Scene<Box2DFloatEngine>> scene;
        if (name == "large_pyramid")
            scene = std::make_unique<LargePyramidScene<Box2DFloatEngine>>(20);
        else if (name == "many_pyramids")
            scene = std::make_unique<ManyPyramidsScene<Box2DFloatEngine>>(2, 3);
        else if (name == "joint_grid")
            scene = std::make_unique<JointGridScene<Box2DFloatEngine>>(12);
        else
            scene = MakeScene<Box2DFloatEngine>(name);
        ASSERT_NE(scene, nullptr) << name;
        RunSettings s;
        s.steps = 60;
        const auto metrics = RunScene(e, *scene, s);
        EXPECT_GT(e.world().GetBodyCount(), 0) << name;
        for (const Metric& m : metrics) EXPECT_TRUE(std::isfinite(m.value)) << name << " " << m.name;
    }
}

TEST(FloatAdapter, OwnScenesBuildAndRun) {
    for (auto name : OwnSceneNames()) {
        Box2DFloatEngine e;
        auto scene = MakeScene<Box2DFloatEngine>(name);
        ASSERT_NE(scene, nullptr) << name;
        RunSettings s;
        s.steps = 60;
        RunScene(e, *scene, s);
        EXPECT_GT(e.world().GetBodyCount(), 0) << name;
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenes

namespace lockbox::scenes {
namespace LOCKBOX_TEST_FILE {

double MetricOf(const std::vector<Metric>& m, const char* name) {
    for (const Metric& x : m)
        if (x.name == name) return x.value;
    ADD_FAILURE() << "no metric " << name;
    return 0;
}

/// The analytic scenes agree with their truth and with float Box2D on the same definition.
TEST(AnalyticScenes, SlopeAccelerationMatchesTheory) {
    LockboxEngine e;
    SlopeScene<LockboxEngine> slope;
    const auto m = RunScene(e, slope);
    // 4.4 m/s^2; Q16.16 velocity rounding biases it by about 5e-5 relative.
    EXPECT_LT(MetricOf(m, "slide_accel_err"), 1e-3);
}

TEST(AnalyticScenes, PendulumPeriodMatchesFloatAndTheory) {
    if constexpr (PendulumScene<LockboxEngine>::kAvailable) {
        LockboxEngine e;
        PendulumScene<LockboxEngine> lb;
        const auto m = RunScene(e, lb);
        Box2DFloatEngine f;
        PendulumScene<Box2DFloatEngine> fl;
        const auto mf = RunScene(f, fl);
        // Semi-implicit Euler at 60 Hz lengthens the period by about 0.1 %.
        EXPECT_LT(MetricOf(m, "period_err"), 3e-3);
        EXPECT_NEAR(MetricOf(m, "period"), MetricOf(mf, "period"), 1e-3);
        EXPECT_LT(MetricOf(m, "joint_sep"), 1e-3);
    } else {
        GTEST_SKIP() << "needs revolute joints";
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenes

namespace lockbox::scenes {
namespace LOCKBOX_TEST_FILE {

TEST(Adapters, DegreesConvertOnceToRadians) {
    // 25 deg = 0.436332 rad = raw 28595.5 -> 28596 (ties away from zero is not reached here).
    EXPECT_NEAR(LockboxEngine::Deg(25).ToDouble(), 25 * 3.14159265358979323846 / 180, 1.0 / 65536);
    EXPECT_EQ(LockboxEngine::Deg(180).Raw(), 205887);  // b2_pi
    EXPECT_EQ(LockboxEngine::Deg(-90).Raw(), -102944);
    EXPECT_NEAR(Box2DFloatEngine::Deg(25), LockboxEngine::Deg(25).ToDouble(), 1e-5);
    EXPECT_EQ(LockboxEngine::R(752 + 1540 * 3, 1000).Raw(), Fixed::FromRatio(5372, 1000).Raw());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenes
