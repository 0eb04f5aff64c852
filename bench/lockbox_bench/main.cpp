// lockbox_bench: runs scenes on lockbox and on float Box2D 2.4.1 side by side.
//
//   lockbox_bench --scene NAME [--steps N] [--velocity-iterations V] [--position-iterations P]
//                 [--hz H] [--engine lockbox|box2d-float] [--repeat R] [--metrics]
//   lockbox_bench ... --workers N   (lockbox steps on N threads, b2World::SetWorkerCount; with
//                 --compare, lockbox runs at 1 and at N workers and the table gains a column)
//   lockbox_bench --all --compare [--repeat R]   (every SCENES.md scene, both engines,
//                 alternating, at least R runs each and more for scenes of short runs; writes
//                 bench/results/<machine>/compare.csv and the table in docs/benchmarks.md)
//   lockbox_bench --all --compare --scenes a,b [--repeat R]   (re-measure some scenes, keep
//                 the other rows of compare.csv; the table names the re-measured ones; a name
//                 that is not a shared scene is refused before anything runs)
//   lockbox_bench --all --compare ... --out DIR   (compare.csv and the tables, as compare.md,
//                 into DIR; bench/results and docs/benchmarks.md are left alone)
//   lockbox_bench --scene-file FILE [--steps N] [--repeat R] [--metrics]   (a b2dJson scene
//                 file on lockbox at the file's own rate and iterations unless given; also
//                 prints how long the file takes to load, median over the repeats)
//   lockbox_bench --list
//   lockbox_bench --scene NAME --headroom   (after the timed runs, one untimed lockbox run with
//                 headroom telemetry on: per quantity class, the largest magnitude as a
//                 fraction of its format's limit, and the saturation count; docs/stability.md)
//
// One line per run (the median over repeats):
//   scene=NAME engine=E steps=N ms_per_step=M p95_ms=Q bodies=B awake=A contacts=C hash=0x...
// followed by the per-stage profile (per-step averages, medians over repeats). Only the world's
// Step is timed. Scene "bullet" expands to its six variants.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "BenchReport.h"
#include "BenchRunner.h"
#include "Compare.h"
#include "lockbox/scenes/SceneFileScene.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox::scenes;

namespace {

constexpr const char* kUsage =
    "usage: lockbox_bench --scene NAME [--steps N] [--velocity-iterations V]\n"
    "         [--position-iterations P] [--hz H] [--engine lockbox|box2d-float]\n"
    "         [--repeat R] [--metrics] [--no-profile] [--no-timers] [--headroom] [--workers N]\n"
    "       lockbox_bench --all --compare [--scenes a,b,...] [--repeat R] [--workers N]\n"
    "         [--out DIR]\n"
    "       lockbox_bench --scene-file FILE.json [--steps N] [--repeat R] [--metrics]\n"
    "       lockbox_bench --list\n";

/// Runs one scene `repeat` times on engine E and prints the median line and profile.
template <class E>
bool RunAndPrint(std::string_view name, const RunSettings& s, int repeat, bool profile, int workers = 1) {
    std::vector<RunResult> runs;
    for (int i = 0; i < repeat; ++i) {
        RunResult r;
        if (!RunOnce<E>(name, s, r, workers)) {
            std::fprintf(stderr, "scene %.*s is unknown or not available on %s\n", static_cast<int>(name.size()),
                         name.data(), E::kName);
            return false;
        }
        runs.push_back(std::move(r));
    }
    const RunResult m = MedianOf(runs);
    PrintLine(m);
    if (profile) PrintProfile(m);
    if (!m.metrics.empty()) {
        std::printf("  metrics:");
        for (const Metric& x : m.metrics) std::printf(" %s=%.6g", x.name.c_str(), x.value);
        std::printf("\n");
    }
    return true;
}

/// One untimed lockbox run of the scene with headroom telemetry on (b2World::
/// SetHeadroomTelemetry); prints the running maximum of b2Profile::headroom per class.
void PrintHeadroom(std::string_view name, const RunSettings& s) {
    auto sc = MakeLockboxScene(name);
    if (!sc) return;
    LockboxEngine e;
    e.world().SetHeadroomTelemetry(true);
    const Resolved r = Resolve(sc->Info(), s);
    ConfigureWorld(e, sc->Info(), s);
    sc->Prepare(r);
    sc->Build(e);
    lockbox::b2Headroom h;
    for (int i = 0; i < r.steps; ++i) {
        sc->BeforeStep(e, i);
        e.Step(r.hz, r.velocityIterations, r.positionIterations);
        h.Merge(e.world().GetProfile().headroom);
    }
    std::printf("  headroom (fraction of format limit):");
    for (int c = 0; c < static_cast<int>(lockbox::b2HeadroomClass::e_count); ++c) {
        const auto cls = static_cast<lockbox::b2HeadroomClass>(c);
        std::printf(" %s=%.3g", lockbox::b2HeadroomClassName(cls), h[cls].Fraction());
    }
    std::printf(" saturations=%lld tightest=%s\n", static_cast<long long>(h.saturations),
                lockbox::b2HeadroomClassName(h.Tightest()));
}

/// Runs a scene file `repeat` times (each run loads it into a new world); prints the median
/// line and profile, and the median time of the load (parse, validation and build).
bool RunSceneFile(const std::string& path, const RunSettings& s, int repeat, bool profile) {
    std::string bytes;
    if (lockbox::scenefile::SceneResult r = lockbox::scenefile::ReadSceneFileBytes(path, bytes); !r) {
        std::fprintf(stderr, "%s: %s\n", path.c_str(), r.Describe().c_str());
        return false;
    }
    const std::string name = SceneFileScene::StemOf(path);
    std::vector<RunResult> runs;
    std::vector<double> loads;
    for (int i = 0; i < repeat; ++i) {
        lockbox::scenefile::SceneResult error;
        const auto t0 = std::chrono::steady_clock::now();
        auto scene = SceneFileScene::FromText(name, bytes, &error);
        loads.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        if (!scene) {
            std::fprintf(stderr, "%s: %s\n", path.c_str(), error.Describe().c_str());
            return false;
        }
        RunResult r;
        RunSceneOnce<LockboxEngine>(std::move(scene), name, s, r);
        runs.push_back(std::move(r));
    }
    const RunResult m = MedianOf(runs);
    PrintLine(m);
    if (profile) PrintProfile(m);
    // FromText reads, checks and builds the file once on a scratch world: a load's full cost.
    std::printf("  load: median %.3f ms over %d runs (%zu bytes)\n", Median(loads), repeat, bytes.size());
    if (!m.metrics.empty()) {
        std::printf("  metrics:");
        for (const Metric& x : m.metrics) std::printf(" %s=%.6g", x.name.c_str(), x.value);
        std::printf("\n");
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene, engine = "lockbox", sceneFile, outDir;
    RunSettings s;
    s.trackMetrics = false;
    int repeat = 1, workers = 1;
    bool all = false, compare = false, list = false, profile = true, headroom = false;
    std::vector<std::string> only;
    lockbox::cli::OptionReader args("lockbox_bench", argc, argv);
    while (args.Next()) {
        if (args.Is("--scene")) {
            args.Text(scene);
        } else if (args.Is("--scene-file")) {
            args.Text(sceneFile);
        } else if (args.Is("--engine")) {
            args.Choice({"lockbox", "box2d-float"}, engine);
        } else if (args.Is("--steps")) {
            args.Int(-1, 100000000, s.steps);
        } else if (args.Is("--velocity-iterations")) {
            args.Int(-1, 1000, s.velocityIterations);
        } else if (args.Is("--position-iterations")) {
            args.Int(-1, 1000, s.positionIterations);
        } else if (args.Is("--hz")) {
            args.Int(1, 10000, s.hz);
        } else if (args.Is("--repeat")) {
            args.Int(1, 100000, repeat);
        } else if (args.Is("--workers")) {
            args.Int(1, 64, workers);
        } else if (args.Is("--metrics")) {
            s.trackMetrics = true;
        } else if (args.Is("--no-profile")) {
            profile = false;
        } else if (args.Is("--no-timers")) {
            // lockbox's world reads no clock for its profile (b2World::SetProfileTimers).
            s.profileTimers = false;
        } else if (args.Is("--headroom")) {
            headroom = true;
        } else if (args.Is("--all")) {
            all = true;
        } else if (args.Is("--compare")) {
            compare = true;
        } else if (args.Is("--out")) {
            args.Text(outDir);
        } else if (args.Is("--list")) {
            list = true;
        } else if (args.Is("--scenes")) {
            // Comma-separated subset for --all --compare; the other rows are kept.
            std::string names;
            if (!args.Text(names)) continue;
            size_t p = 0;
            while (p <= names.size()) {
                const size_t q = std::min(names.find(',', p), names.size());
                if (q > p) only.push_back(names.substr(p, q - p));
                p = q + 1;
            }
        } else {
            args.Unknown();
        }
    }
    if (args.Failed()) return args.Fail(kUsage);
    if ((!only.empty() || !outDir.empty()) && !(all && compare)) {
        // They shape the comparison's files only; elsewhere they would be ignored in silence.
        args.Refuse("--scenes and --out go with --all --compare");
        return args.Fail(kUsage);
    }
    if (repeat < 1) repeat = 1;
    if (list) {
        for (auto n : AllSceneNames()) {
            auto sc = MakeLockboxScene(n);
            std::printf("%-26.*s %s\n", static_cast<int>(n.size()), n.data(),
                        sc ? std::string(sc->Info().summary).c_str() : "(needs joints not yet in lockbox)");
        }
        return 0;
    }
    if (all && compare) {
        if (const std::string bad = UnknownCompareScene(only); !bad.empty()) {
            std::string known;
            for (const std::string& key : CompareKeys()) known += (known.empty() ? "" : ", ") + key;
            std::fprintf(stderr, "lockbox_bench: unknown scene %s in --scenes (shared scenes: %s)\n", bad.c_str(),
                         known.c_str());
            return 2;
        }
        return RunCompare(repeat, only, workers, outDir) ? 0 : 1;
    }
    if (!sceneFile.empty()) return RunSceneFile(sceneFile, s, repeat, profile) ? 0 : 1;
    if (scene.empty()) {
        args.Refuse("give --scene NAME, --scene-file FILE, --all --compare or --list");
        return args.Fail(kUsage);
    }
    std::vector<std::string_view> names;
    if (scene == "bullet") {
        for (auto n : SharedSceneNames())
            if (n.substr(0, 7) == "bullet_") names.push_back(n);
    } else {
        names.push_back(scene);
    }
    bool ok = true;
    for (auto n : names) {
        if (engine == "lockbox") {
            ok = RunAndPrint<LockboxEngine>(n, s, repeat, profile, workers) && ok;
            if (headroom) PrintHeadroom(n, s);
        } else if (engine == "box2d-float")
            ok = RunAndPrint<Box2DFloatEngine>(n, s, repeat, profile) && ok;
        else
            return 2;  // unreachable: --engine is checked against its choices above
    }
    return ok ? 0 : 1;
}
