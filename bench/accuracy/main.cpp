// lockbox_accuracy: what accuracy costs in time. For pyramid20, vertical_stack, chain60, the
// pendulum, the slope and large_pyramid (over its first 300 steps) it sweeps, one knob at a time
// from the scene's defaults (60 Hz, 8/3):
//   time step 1/30, 1/60, 1/120, 1/240 (steps scaled to cover the same simulated time);
//   velocity iterations 1, 2, 4, 8, 16, 32; position iterations 1, 2, 3, 8;
//   effect switches: warm starting off, continuous collision off, sub-stepping on;
// on lockbox and on float Box2D 2.4.1 with the same settings, and writes
// bench/results/<machine>/accuracy.csv (one row per run) and effects.csv (stage shares and
// work counters per configuration), which plot_accuracy.py turns into plots and tables.
//
//   lockbox_accuracy [--scene NAME] [--repeat R] [--quick] [--out DIR]
// --quick runs only the default and one knob per family (a smoke run). A partial run writes
// files of its own (accuracy_quick.csv, accuracy_<scene>.csv, ...) so that it never replaces
// the full sweep's; --out DIR writes into DIR instead of bench/results/<machine>/.
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "BenchReport.h"
#include "BenchRunner.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox::scenes;

namespace {

/// One configuration of the sweep.
struct Config {
    std::string family;  ///< "base", "hz", "vel", "pos", "effect"
    std::string label;   ///< e.g. "hz=120", "warm=off"
    RunSettings settings;
};

std::vector<Config> Configs(bool quick) {
    std::vector<Config> out;
    out.push_back({"base", "base", RunSettings{}});
    for (int hz : {30, 60, 120, 240}) {
        if (quick && hz != 120) continue;
        Config c{"hz", "hz=" + std::to_string(hz), RunSettings{}};
        c.settings.hz = hz;
        out.push_back(c);
    }
    for (int v : {1, 2, 4, 8, 16, 32}) {
        if (quick && v != 2) continue;
        Config c{"vel", "vel=" + std::to_string(v), RunSettings{}};
        c.settings.velocityIterations = v;
        out.push_back(c);
    }
    for (int p : {1, 2, 3, 8}) {
        if (quick && p != 1) continue;
        Config c{"pos", "pos=" + std::to_string(p), RunSettings{}};
        c.settings.positionIterations = p;
        out.push_back(c);
    }
    Config warm{"effect", "warm=off", RunSettings{}};
    warm.settings.warmStarting = false;
    out.push_back(warm);
    Config cont{"effect", "continuous=off", RunSettings{}};
    cont.settings.continuous = false;
    out.push_back(cont);
    Config sub{"effect", "substep=on", RunSettings{}};
    sub.settings.subStepping = true;
    out.push_back(sub);
    return out;
}

/// The primary error of each scene (what the plots put on the y axis).
const char* PrimaryMetric(std::string_view scene) {
    if (scene == "pendulum") return "period_err";
    if (scene == "slope") return "slide_accel_err";
    if (scene == "chain60") return "joint_sep";
    if (scene == "vertical_stack" || scene == "large_pyramid") return "stack_drift";
    return "max_pen";
}

/// Steps at the scene's own rate. large_pyramid runs 300 of its benchmark's 500 (5 simulated
/// seconds, by which float Box2D's has fallen at the defaults) so that its settings on both
/// engines take minutes, not half an hour; the others run their benchmark's steps.
int SweepSteps(std::string_view scene, int benchmarkSteps) { return scene == "large_pyramid" ? 300 : benchmarkSteps; }

/// Settings a scene leaves out of its sweep. Without warm starting large_pyramid falls apart, and
/// float Box2D 2.4.1's time-of-impact stage, which scans every contact for each event, then takes
/// over a quarter of an hour for the run.
bool Skipped(std::string_view scene, const Config& c) { return scene == "large_pyramid" && c.label == "warm=off"; }

/// Scene metrics plus derived ones (stack drift = |top_dx| + |top_sag - sag at the finest
/// settings| is not known here, so drift is |top_dx| + max(0, top_sag)).
std::vector<Metric> WithDerived(std::vector<Metric> m) {
    double dx = 0, sag = 0;
    bool has = false;
    for (const Metric& x : m) {
        if (x.name == "top_dx") dx = x.value, has = true;
        if (x.name == "top_sag") sag = x.value;
    }
    if (has) m.push_back({"stack_drift", std::fabs(dx) + std::max(0.0, sag)});
    return m;
}

double Find(const std::vector<Metric>& m, const std::string& name, double fallback = NAN) {
    for (const Metric& x : m)
        if (x.name == name) return x.value;
    return fallback;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> scenes = {"pyramid20", "vertical_stack", "chain60", "pendulum", "slope", "large_pyramid"};
    int repeat = 1;
    bool quick = false;
    std::string only, out;
    lockbox::cli::OptionReader args("lockbox_accuracy", argc, argv);
    while (args.Next()) {
        if (args.Is("--scene")) {
            if (args.Text(only)) scenes = {only};
        } else if (args.Is("--repeat")) {
            args.Int(1, 100000, repeat);
        } else if (args.Is("--quick")) {
            quick = true;
        } else if (args.Is("--out")) {
            args.Text(out);
        } else {
            args.Unknown();
        }
    }
    if (args.Failed()) return args.Fail("usage: lockbox_accuracy [--scene NAME] [--repeat R] [--quick] [--out DIR]\n");
    // Every scene is known before any file is opened, so a misspelt name replaces nothing.
    for (const std::string& scene : scenes) {
        if (!MakeScene<Box2DFloatEngine>(scene)) {
            std::fprintf(stderr, "lockbox_accuracy: unknown scene %s\n", scene.c_str());
            return 2;
        }
    }
    const std::filesystem::path dir =
        out.empty() ? std::filesystem::path(LOCKBOX_BENCH_RESULTS_DIR) / MachineName() : std::filesystem::path(out);
    const std::string suffix = std::string(quick ? "_quick" : "") + (only.empty() ? "" : "_" + only) + ".csv";
    const std::filesystem::path csvPath = dir / ("accuracy" + suffix), effPath = dir / ("effects" + suffix);
    std::error_code ignored;  // a directory that cannot be made shows as files that do not open
    std::filesystem::create_directories(dir, ignored);
    std::ofstream csv(csvPath);
    std::ofstream eff(effPath);
    if (!csv || !eff) {
        std::fprintf(stderr, "lockbox_accuracy: cannot write %s\n", (csv ? effPath : csvPath).c_str());
        return 1;
    }
    csv << "scene,engine,family,config,hz,steps,vel_iters,pos_iters,warm,continuous,substep,ms_per_step,"
           "primary_metric,primary,primary_vs_float,max_pen,top_dx,top_sag,collapsed,joint_sep,"
           "all_asleep_step,energy_drift,period_err,slide_accel_err,stack_drift\n";
    eff << "scene,engine,config,stage,value\n";

    for (const std::string& scene : scenes) {
        for (const Config& c : Configs(quick)) {
            if (Skipped(scene, c)) {
                std::printf("%-15s %-12s %-15s left out (float Box2D's time of impact takes too long)\n", scene.c_str(),
                            "both", c.label.c_str());
                continue;
            }
            RunSettings s = c.settings;
            s.trackMetrics = true;
            auto proto = MakeScene<Box2DFloatEngine>(scene);
            // Cover the same simulated time at every frequency.
            const int hz = s.hz > 0 ? s.hz : proto->Info().hz;
            s.steps = SweepSteps(scene, proto->Info().steps) * hz / proto->Info().hz;

            RunResult fl, lb;
            bool flOk = false, lbOk = false;
            std::vector<RunResult> flRuns, lbRuns;
            for (int r = 0; r < repeat; ++r) {
                RunResult a, b;
                if (RunOnce<Box2DFloatEngine>(scene, s, a)) flRuns.push_back(a);
                if (RunOnce<LockboxEngine>(scene, s, b)) lbRuns.push_back(b);
            }
            if (!flRuns.empty()) fl = MedianOf(flRuns), flOk = true;
            if (!lbRuns.empty()) lb = MedianOf(lbRuns), lbOk = true;
            const char* primary = PrimaryMetric(scene);
            const double flPrimary = flOk ? Find(WithDerived(fl.metrics), primary) : NAN;
            for (int k = 0; k < 2; ++k) {
                const bool ok = k == 0 ? lbOk : flOk;
                if (!ok) continue;
                const RunResult& r = k == 0 ? lb : fl;
                const auto m = WithDerived(r.metrics);
                const double p = Find(m, primary);
                char line[1024];
                std::snprintf(
                    line, sizeof line,
                    "%s,%s,%s,%s,%d,%d,%d,%d,%d,%d,%d,%.6f,%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,"
                    "%.9g,%.9g\n",
                    scene.c_str(), r.engine.c_str(), c.family.c_str(), c.label.c_str(), r.settings.hz, r.settings.steps,
                    r.settings.velocityIterations, r.settings.positionIterations, s.warmStarting, s.continuous,
                    s.subStepping, r.msPerStep, primary, p, k == 0 ? std::fabs(p - flPrimary) : 0.0, Find(m, "max_pen"),
                    Find(m, "top_dx"), Find(m, "top_sag"), Find(m, "collapsed"), Find(m, "joint_sep"),
                    Find(m, "all_asleep_step"), Find(m, "energy_drift"), Find(m, "period_err"),
                    Find(m, "slide_accel_err"), Find(m, "stack_drift"));
                csv << line;
                for (const auto& [stage, v] : r.profile)
                    eff << scene << "," << r.engine << "," << c.label << "," << stage << "," << v << "\n";
                std::printf("%-15s %-12s %-15s ms/step=%.4f %s=%.6g\n", scene.c_str(), r.engine.c_str(),
                            c.label.c_str(), r.msPerStep, primary, p);
            }
            if (!lbOk)
                std::printf("%-15s lockbox      %-15s unavailable (needs joints)\n", scene.c_str(), c.label.c_str());
            std::fflush(stdout);
            csv.flush();
            eff.flush();
        }
    }
    std::printf("wrote %s and %s\n", csvPath.c_str(), effPath.c_str());
    return 0;
}
