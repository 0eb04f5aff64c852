#pragma once
/// The scene interface shared by tests, samples and benchmarks.
///
/// A scene is written once, as a class template over an engine adapter `E`, so that the same
/// definition builds on lockbox (LockboxEngine.h, in this library) and on float Box2D 2.4.1
/// (scenes/float/include/lockbox/scenes/Box2DFloatEngine.h). An adapter provides:
/// - the native types (`E::World`, `E::Body`, `E::BodyDef`, `E::FixtureDef`, `E::PolygonShape`,
///   `E::CircleShape`, `E::EdgeShape`, `E::ChainShape`, `E::Contact`, `E::Fixture`, `E::Vec`,
///   `E::Num`) and, where the engine has them, joint definitions, flagged by `E::kHasRevolute`
///   and friends;
/// - `E::R(num, den)`: the number num/den rounded once (Q16.16 to nearest on lockbox, float
///   on Box2D), so every scene constant comes from an exact decimal or ratio;
/// - `E::D(Num)`: a double for reporting only (metrics, printing; never fed back);
/// - `SetEdge`, `CreateChain`, `SetWheelSpring`, `Deg`: the few API differences;
/// - `world()`, `Step(hz, vel, pos)` (dt = round(65536/hz)/65536 s on both engines), and the
///   contact hooks `onBeginContact` / `onPreSolve` installed by `InstallListener()`.
///
/// Metrics are doubles: they are read from the world after a step, never written back, so they
/// cannot change a simulation.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lockbox::scenes {

/// A scene's defaults, as SCENES.md defines them.
struct SceneInfo {
    std::string_view name;       ///< command-line name, e.g. "pyramid20"
    int steps = 60;              ///< default number of steps
    int velocityIterations = 8;  ///< default velocity iterations
    int positionIterations = 3;  ///< default position iterations
    int hz = 60;                 ///< default step frequency (1/s); dt = round(65536/hz) / 65536 s
    bool allowSleep = true;      ///< world sleep flag
    bool shared = false;         ///< defined in SCENES.md (runs on both engines in comparisons)
    bool heavy = false;          ///< more than ~1 s per run in a debug build
    std::string_view summary;    ///< one line for listings
};

/// One named figure a scene reports (display only).
struct Metric {
    std::string name;  ///< e.g. "max_pen"
    double value = 0;  ///< in the metric's natural unit (m, steps, count)
};

/// Overrides for a run; negative or unset fields keep the scene's default.
struct RunSettings {
    int steps = -1;               ///< number of steps, -1: scene default
    int velocityIterations = -1;  ///< -1: scene default
    int positionIterations = -1;  ///< -1: scene default
    int hz = -1;                  ///< step frequency (1/s), -1: scene default
    bool warmStarting = true;     ///< world warm-starting switch
    bool continuous = true;       ///< world continuous-physics switch
    bool subStepping = false;     ///< world sub-stepping switch
    bool trackMetrics = true;     ///< evaluate per-step metrics after each step
    bool profileTimers = true;    ///< lockbox's stage timers (float Box2D 2.4.1 always times its stages)
};

/// The resolved settings of a run (scene defaults with the overrides applied).
struct Resolved {
    int steps, velocityIterations, positionIterations, hz;
};

/// Applies the overrides in s to the defaults in info.
inline Resolved Resolve(const SceneInfo& info, const RunSettings& s) {
    return Resolved{
        s.steps >= 0 ? s.steps : info.steps, s.velocityIterations >= 0 ? s.velocityIterations : info.velocityIterations,
        s.positionIterations >= 0 ? s.positionIterations : info.positionIterations, s.hz > 0 ? s.hz : info.hz};
}

/// The largest penetration over touching, enabled manifold points of the current contacts, m
/// (SCENES.md max_pen: -min(separation), 0 when nothing penetrates).
template <class E>
double MaxPenetration(E& e) {
    double pen = 0;
    for (auto* c = e.world().GetContactList(); c; c = c->GetNext()) {
        // A contact disabled in PreSolve (one-way platforms) is not solved: not a penetration.
        if (!c->IsTouching() || !c->IsEnabled()) continue;
        typename E::WorldManifold wm;
        c->GetWorldManifold(&wm);
        const int n = c->GetManifold()->pointCount;
        for (int i = 0; i < n; ++i) pen = std::max(pen, -E::D(wm.separations[i]));
    }
    return pen;
}

/// Number of awake dynamic bodies.
template <class E>
int AwakeDynamicCount(E& e) {
    int n = 0;
    for (auto* b = e.world().GetBodyList(); b; b = b->GetNext())
        if (b->GetType() == E::kDynamic && b->IsAwake()) ++n;
    return n;
}

/// Number of dynamic bodies.
template <class E>
int DynamicCount(E& e) {
    int n = 0;
    for (auto* b = e.world().GetBodyList(); b; b = b->GetNext())
        if (b->GetType() == E::kDynamic) ++n;
    return n;
}

/// The largest |anchorA - anchorB| over the world's joints, m (SCENES.md joint_sep). Zero on
/// an engine without joints.
template <class E>
double MaxJointSeparation(E& e) {
    double sep = 0;
    if constexpr (E::kHasRevolute) {
        for (auto* j = e.world().GetJointList(); j; j = j->GetNext()) {
            const auto a = j->GetAnchorA();
            const auto b = j->GetAnchorB();
            const double dx = E::D(a.x) - E::D(b.x);
            const double dy = E::D(a.y) - E::D(b.y);
            sep = std::max(sep, std::sqrt(dx * dx + dy * dy));
        }
    }
    return sep;
}

/// A scene: built once per world, stepped by a driver (RunScene or a benchmark).
template <class E>
class Scene {
public:
    virtual ~Scene() = default;
    /// The scene's defaults.
    virtual const SceneInfo& Info() const = 0;
    /// Creates the scene's bodies, fixtures and joints in the SCENES.md order.
    virtual void Build(E& e) = 0;
    /// Tells the scene the resolved settings of the coming run (call before Build; RunScene
    /// does). Scenes that sample at fixed times read the frequency from here.
    void Prepare(const Resolved& r) noexcept { run_ = r; }
    /// Called before step `step` (0-based); rain spawns bodies here.
    virtual void BeforeStep(E& e, int step) {
        (void)e;
        (void)step;
    }
    /// Called after step `step` when metrics are tracked. The base tracks max_pen and
    /// all_asleep_step; scenes add their own and call the base.
    virtual void AfterStep(E& e, int step) {
        maxPen_ = std::max(maxPen_, MaxPenetration(e));
        if (AwakeDynamicCount(e) == 0) {
            if (allAsleepStep_ < 0) allAsleepStep_ = step + 1;
        } else {
            allAsleepStep_ = -1;  // something woke up (or was spawned): not asleep yet
        }
    }
    /// Appends the scene's metrics; the base gives max_pen and all_asleep_step (-1: never).
    virtual void Report(E& e, std::vector<Metric>& out) {
        (void)e;
        out.push_back({"max_pen", maxPen_});
        out.push_back({"all_asleep_step", static_cast<double>(allAsleepStep_)});
    }

protected:
    /// The step length of the run in seconds: round(65536 / hz) / 65536 (display only).
    double StepSeconds() const noexcept { return static_cast<double>((65536 + run_.hz / 2) / run_.hz) / 65536.0; }
    Resolved run_{60, 8, 3, 60};  ///< settings of the current run
    double maxPen_ = 0;           ///< running max of MaxPenetration, m
    int allAsleepStep_ = -1;      ///< first step count after which all dynamic bodies sleep
};

/// Tracks a body against an ideal rest position: top_dx, top_sag, collapsed (SCENES.md).
struct TopTracker {
    double x0 = 0;        ///< initial x of the tracked body, m
    double restY = 0;     ///< ideal resting height, m
    double maxAbsDx = 0;  ///< largest |dx| seen, m
    double lastDx = 0, lastSag = 0;
    bool collapsed = false;
    /// Records one observation (x, y in m).
    void Observe(double x, double y) {
        lastDx = x - x0;
        lastSag = restY - y;
        maxAbsDx = std::max(maxAbsDx, std::fabs(lastDx));
    }
    /// Appends top_dx, top_sag and collapsed (judged on the final state).
    void Report(std::vector<Metric>& out) {
        collapsed = std::fabs(lastDx) > 0.5 || lastSag > 0.5;
        out.push_back({"top_dx", lastDx});
        out.push_back({"top_sag", lastSag});
        out.push_back({"collapsed", collapsed ? 1.0 : 0.0});
    }
};

/// Applies the world switches of a run (sleep from the scene, the rest from the settings).
template <class E>
void ConfigureWorld(E& e, const SceneInfo& info, const RunSettings& s) {
    e.world().SetAllowSleeping(info.allowSleep);
    e.world().SetWarmStarting(s.warmStarting);
    e.world().SetContinuousPhysics(s.continuous);
    e.world().SetSubStepping(s.subStepping);
    SetProfileTimers(e, s.profileTimers);
}

/// Builds and runs a scene to completion; returns its metrics.
template <class E>
std::vector<Metric> RunScene(E& e, Scene<E>& scene, const RunSettings& s = {}) {
    const Resolved r = Resolve(scene.Info(), s);
    ConfigureWorld(e, scene.Info(), s);
    scene.Prepare(r);
    scene.Build(e);
    for (int i = 0; i < r.steps; ++i) {
        scene.BeforeStep(e, i);
        e.Step(r.hz, r.velocityIterations, r.positionIterations);
        if (s.trackMetrics) scene.AfterStep(e, i);
    }
    std::vector<Metric> out;
    scene.Report(e, out);
    return out;
}

}  // namespace lockbox::scenes
