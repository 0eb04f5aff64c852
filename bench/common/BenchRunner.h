#pragma once
/// Runs one scene on one engine and measures it: wall time per world Step (only the Step call
/// is timed; scene hooks and metrics run outside the timed region), world counts, the lockbox
/// state hash, and the per-stage profile averaged per step. Shared by lockbox_bench and
/// lockbox_accuracy. Include after the lockbox headers (Box2DFloatEngine.h takes care of it).

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "lockbox/scenes/Box2DFloatEngine.h"

namespace lockbox::scenes {

/// Figures of one run.
struct RunResult {
    std::string scene;                                    ///< scene name
    std::string engine;                                   ///< "lockbox" or "box2d-float"
    Resolved settings{0, 0, 0, 0};                        ///< steps, iterations, Hz actually used
    double msPerStep = 0;                                 ///< mean wall time of one Step, ms
    double p95Ms = 0;                                     ///< 95th percentile of the Step times, ms
    int bodies = 0, awake = 0, contacts = 0;              ///< world counts after the last step
    uint64_t hash = 0;                                    ///< HashWorld for lockbox, 0 for float
    std::vector<std::pair<std::string, double>> profile;  ///< per-step averages (ms or counts)
    std::vector<Metric> metrics;                          ///< scene metrics (when tracked)
    int workers = 1;                                      ///< lockbox worker threads (float: 1)
};

/// Per-step profile figures: wall-clock stages in ms and work counters, summed over a run in a
/// fixed array (the per-step cost of the harness stays far below a tiny scene's step, so that
/// instruction counts of a whole run measure the engine). ProfileNames<E>::kNames names the slots.
template <class E>
struct ProfileNames;
template <>
struct ProfileNames<LockboxEngine> {
    static constexpr std::array kNames{"step_ms",
                                       "collide_ms",
                                       "solve_ms",
                                       "solveInit_ms",
                                       "solveVelocity_ms",
                                       "solvePosition_ms",
                                       "broadphase_ms",
                                       "solveTOI_ms",
                                       "n_pairsFound",
                                       "n_contactsCreated",
                                       "n_contactsUpdated",
                                       "n_manifolds",
                                       "n_islands",
                                       "n_bodiesIntegrated",
                                       "n_contactConstraints",
                                       "n_jointConstraints",
                                       "n_velocityIterations",
                                       "n_jointVelocityIterations",
                                       "n_positionIterations",
                                       "n_toiCandidates",
                                       "n_toiCalls",
                                       "n_toiSubSteps",
                                       "n_listenerCallbacks"};
};
template <>
struct ProfileNames<Box2DFloatEngine> {
    static constexpr std::array kNames{"step_ms",          "collide_ms",       "solve_ms",      "solveInit_ms",
                                       "solveVelocity_ms", "solvePosition_ms", "broadphase_ms", "solveTOI_ms"};
};

/// Adds lockbox's profile of the last step to acc (slots of ProfileNames<LockboxEngine>::kNames).
inline void AddProfile(LockboxEngine& e, double* acc) {
    const b2Profile& p = e.world().GetProfile();
    auto ms = [](int64_t ns) { return static_cast<double>(ns) * 1e-6; };
    const double values[] = {ms(p.stepNs),
                             ms(p.collideNs),
                             ms(p.solveNs),
                             ms(p.solveInitNs),
                             ms(p.solveVelocityNs),
                             ms(p.solvePositionNs),
                             ms(p.broadphaseNs),
                             ms(p.solveTOINs),
                             static_cast<double>(p.pairsFound),
                             static_cast<double>(p.contactsCreated),
                             static_cast<double>(p.contactsUpdated),
                             static_cast<double>(p.manifoldsEvaluated),
                             static_cast<double>(p.islandsSolved),
                             static_cast<double>(p.bodiesIntegrated),
                             static_cast<double>(p.contactConstraints),
                             static_cast<double>(p.jointConstraints),
                             static_cast<double>(p.velocityIterations),
                             static_cast<double>(p.jointVelocityIterations),
                             static_cast<double>(p.positionIterations),
                             static_cast<double>(p.toiCandidates),
                             static_cast<double>(p.toiCalls),
                             static_cast<double>(p.toiSubSteps),
                             static_cast<double>(p.listenerCallbacks)};
    static_assert(std::size(values) == ProfileNames<LockboxEngine>::kNames.size());
    for (size_t i = 0; i < std::size(values); ++i) acc[i] += values[i];
}

/// Adds float Box2D 2.4.1's profile of the last step (its b2Profile is in ms).
inline void AddProfile(Box2DFloatEngine& e, double* acc) {
    const ::b2Profile& p = e.world().GetProfile();
    const double values[] = {p.step,          p.collide,       p.solve,      p.solveInit,
                             p.solveVelocity, p.solvePosition, p.broadphase, p.solveTOI};
    static_assert(std::size(values) == ProfileNames<Box2DFloatEngine>::kNames.size());
    for (size_t i = 0; i < std::size(values); ++i) acc[i] += static_cast<double>(values[i]);
}

/// Worker threads for a run: the lockbox world's pool; float Box2D 2.4.1 has none.
inline void SetWorkers(LockboxEngine& e, int workers) { e.world().SetWorkerCount(workers); }
inline void SetWorkers(Box2DFloatEngine&, int) {}

/// The lockbox state hash (0 for float).
inline uint64_t EngineHash(LockboxEngine& e) { return HashWorld(e.world()); }
inline uint64_t EngineHash(Box2DFloatEngine&) { return 0; }

/// Runs a scene once on engine E (`name` is what the result reports), lockbox on `workers`
/// threads; false for no scene.
template <class E>
bool RunSceneOnce(std::unique_ptr<Scene<E>> scene, std::string_view name, const RunSettings& s, RunResult& out,
                  int workers = 1) {
    if (!scene) return false;
    E e;
    SetWorkers(e, workers);
    const Resolved r = Resolve(scene->Info(), s);
    ConfigureWorld(e, scene->Info(), s);
    scene->Prepare(r);
    scene->Build(e);
    std::vector<double> times;
    times.reserve(static_cast<size_t>(r.steps));
    std::array<double, ProfileNames<E>::kNames.size()> acc{};
    for (int i = 0; i < r.steps; ++i) {
        scene->BeforeStep(e, i);
        const auto t0 = std::chrono::steady_clock::now();
        e.Step(r.hz, r.velocityIterations, r.positionIterations);
        const auto t1 = std::chrono::steady_clock::now();
        times.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        AddProfile(e, acc.data());
        if (s.trackMetrics) scene->AfterStep(e, i);
    }
    out = RunResult{};
    out.scene = std::string(name);
    out.engine = E::kName;
    out.settings = r;
    out.workers = std::is_same_v<E, LockboxEngine> ? workers : 1;
    double total = 0;
    for (double t : times) total += t;
    out.msPerStep = r.steps > 0 ? total / r.steps : 0;
    if (!times.empty()) {
        std::vector<double> sorted = times;
        std::sort(sorted.begin(), sorted.end());
        out.p95Ms = sorted[std::min(sorted.size() - 1, (sorted.size() * 95) / 100)];
    }
    out.bodies = e.world().GetBodyCount();
    for (auto* b = e.world().GetBodyList(); b; b = b->GetNext())
        if (b->IsAwake() && b->GetType() != E::kStatic) ++out.awake;
    out.contacts = e.world().GetContactCount();
    out.hash = EngineHash(e);
    // By name, as before (reports and the compare table list the figures alphabetically).
    std::map<std::string, double> byName;
    for (size_t i = 0; i < acc.size(); ++i) byName[ProfileNames<E>::kNames[i]] = acc[i];
    for (const auto& [k, v] : byName) out.profile.emplace_back(k, r.steps > 0 ? v / r.steps : 0);
    scene->Report(e, out.metrics);
    return true;
}

/// Runs the named scene once on engine E (lockbox on `workers` threads); false when the scene
/// is unknown or unavailable.
template <class E>
bool RunOnce(std::string_view name, const RunSettings& s, RunResult& out, int workers = 1) {
    return RunSceneOnce<E>(MakeScene<E>(name), name, s, out, workers);
}

/// Median of a list (0 when empty).
inline double Median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// The median over repeats of every timing and profile figure; counts and hash from the
/// first run (they are identical across repeats for lockbox by construction).
inline RunResult MedianOf(const std::vector<RunResult>& runs) {
    RunResult m = runs.front();
    std::vector<double> v;
    for (const auto& r : runs) v.push_back(r.msPerStep);
    m.msPerStep = Median(v);
    v.clear();
    for (const auto& r : runs) v.push_back(r.p95Ms);
    m.p95Ms = Median(v);
    for (size_t k = 0; k < m.profile.size(); ++k) {
        v.clear();
        for (const auto& r : runs)
            if (k < r.profile.size()) v.push_back(r.profile[k].second);
        m.profile[k].second = Median(v);
    }
    return m;
}

}  // namespace lockbox::scenes
