#pragma once
/// `lockbox_bench --all --compare`: every SCENES.md scene on both engines, alternating engine
/// order between repeats (so drift in machine speed hits both), with the same iterations and
/// time step. Writes bench/results/<machine>/compare.csv and the table in docs/benchmarks.md.
///
/// The geometric mean counts each SCENES.md scene once: bullet's six 60-step variants enter as
/// one scene whose ratio is their summed lockbox time over their summed float time.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "BenchReport.h"
#include "BenchRunner.h"

namespace lockbox::scenes {

/// The two largest lockbox stage costs of a run, as "stage 41%, stage 22%".
inline std::string TopCosts(const RunResult& r) {
    double step = 0;
    std::vector<std::pair<double, std::string>> stages;
    for (const auto& [k, v] : r.profile) {
        if (k == "step_ms") step = v;
        // The leaf stages (solve_ms contains the three solve stages).
        if (k == "collide_ms" || k == "solveInit_ms" || k == "solveVelocity_ms" || k == "solvePosition_ms" ||
            k == "broadphase_ms" || k == "solveTOI_ms")
            stages.emplace_back(v, k.substr(0, k.size() - 3));
    }
    std::sort(stages.rbegin(), stages.rend());
    std::ostringstream os;
    for (size_t i = 0; i < 2 && i < stages.size() && step > 0; ++i) {
        if (i) os << ", ";
        os << stages[i].second << " " << static_cast<int>(std::lround(100 * stages[i].first / step)) << "%";
    }
    return os.str();
}

/// Runs the comparison; returns false when nothing could be compared.
inline bool RunCompare(int repeat) {
    RunSettings s;
    s.trackMetrics = false;
    struct Row {
        std::string name;
        bool lockboxOk = false;
        RunResult lb, fl;
    };
    std::vector<Row> rows;
    for (auto name : SharedSceneNames()) {
        Row row;
        row.name = std::string(name);
        std::vector<RunResult> lbRuns, flRuns;
        for (int i = 0; i < repeat; ++i) {
            RunResult a, b;
            bool okA = true;
            if (i % 2 == 0) {
                okA = RunOnce<LockboxEngine>(name, s, a);
                RunOnce<Box2DFloatEngine>(name, s, b);
            } else {
                RunOnce<Box2DFloatEngine>(name, s, b);
                okA = RunOnce<LockboxEngine>(name, s, a);
            }
            if (okA) lbRuns.push_back(a);
            flRuns.push_back(b);
        }
        row.fl = MedianOf(flRuns);
        PrintLine(row.fl);
        if (!lbRuns.empty()) {
            row.lockboxOk = true;
            row.lb = MedianOf(lbRuns);
            PrintLine(row.lb);
            PrintProfile(row.lb);
        } else {
            std::printf("scene=%s engine=lockbox unavailable (needs joints)\n", row.name.c_str());
        }
        std::fflush(stdout);
        rows.push_back(std::move(row));
    }

    // Ratios per SCENES.md scene (bullet variants summed) and their geometric mean.
    std::map<std::string, std::pair<double, double>> perScene;  // name -> (lockbox, float) ms
    std::vector<std::string> order;
    for (const Row& r : rows) {
        if (!r.lockboxOk) continue;
        const std::string key = r.name.rfind("bullet_", 0) == 0 ? "bullet" : r.name;
        if (!perScene.count(key)) order.push_back(key);
        perScene[key].first += r.lb.msPerStep;
        perScene[key].second += r.fl.msPerStep;
    }
    double logSum = 0;
    int n = 0;
    for (const auto& key : order) {
        const auto& [lb, fl] = perScene[key];
        if (lb > 0 && fl > 0) {
            logSum += std::log(lb / fl);
            ++n;
        }
    }
    const double geomean = n ? std::exp(logSum / n) : 0;

    const std::string machine = MachineName();
    const std::filesystem::path dir = std::filesystem::path(LOCKBOX_BENCH_RESULTS_DIR) / machine;
    std::filesystem::create_directories(dir);
    {
        std::ofstream csv(dir / "compare.csv");
        csv << "scene,steps,vel_iters,pos_iters,hz,lockbox_ms_per_step,lockbox_p95_ms,float_ms_per_step,"
               "float_p95_ms,ratio,bodies,lockbox_awake,float_awake,lockbox_contacts,float_contacts,"
               "lockbox_hash,top_costs\n";
        for (const Row& r : rows) {
            csv << r.name << "," << r.fl.settings.steps << "," << r.fl.settings.velocityIterations << ","
                << r.fl.settings.positionIterations << "," << r.fl.settings.hz << ",";
            if (r.lockboxOk) {
                char hash[32];
                std::snprintf(hash, sizeof hash, "0x%016" PRIx64, r.lb.hash);
                csv << r.lb.msPerStep << "," << r.lb.p95Ms << "," << r.fl.msPerStep << "," << r.fl.p95Ms << ","
                    << r.lb.msPerStep / r.fl.msPerStep << "," << r.lb.bodies << "," << r.lb.awake << ","
                    << r.fl.awake << "," << r.lb.contacts << "," << r.fl.contacts << "," << hash << ",\""
                    << TopCosts(r.lb) << "\"\n";
            } else {
                csv << ",," << r.fl.msPerStep << "," << r.fl.p95Ms << ",," << r.fl.bodies << ",,"
                    << r.fl.awake << ",," << r.fl.contacts << ",,unavailable\n";
            }
        }
    }

    std::ostringstream md;
    md << "Machine `" << machine << "`, " << repeat << " repeat(s) per engine, engines alternating; "
       << "release build; only `b2World::Step` is timed. Same scene definitions, iterations and time step "
          "(1092/65536 s) on both engines.\n\n";
    md << "| scene | steps | vel/pos | lockbox ms/step | float ms/step | ratio | lockbox p95 | float p95 | "
          "bodies | contacts lockbox/float | lockbox top costs |\n";
    md << "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |\n";
    char buf[512];
    for (const Row& r : rows) {
        if (r.lockboxOk) {
            std::snprintf(buf, sizeof buf, "| %s | %d | %d/%d | %.4f | %.4f | %.2f | %.4f | %.4f | %d | %d/%d | %s |\n",
                          r.name.c_str(), r.fl.settings.steps, r.fl.settings.velocityIterations,
                          r.fl.settings.positionIterations, r.lb.msPerStep, r.fl.msPerStep,
                          r.lb.msPerStep / r.fl.msPerStep, r.lb.p95Ms, r.fl.p95Ms, r.lb.bodies, r.lb.contacts,
                          r.fl.contacts, TopCosts(r.lb).c_str());
        } else {
            std::snprintf(buf, sizeof buf, "| %s | %d | %d/%d | n/a | %.4f | n/a | n/a | %.4f | %d | -/%d | "
                          "needs joints |\n",
                          r.name.c_str(), r.fl.settings.steps, r.fl.settings.velocityIterations,
                          r.fl.settings.positionIterations, r.fl.msPerStep, r.fl.p95Ms, r.fl.bodies, r.fl.contacts);
        }
        md << buf;
    }
    md << "\n";
    for (const auto& key : order) {
        const auto& [lb, fl] = perScene[key];
        if (key == "bullet") {
            std::snprintf(buf, sizeof buf, "bullet (six variants summed): %.4f / %.4f ms = ratio %.2f.\n\n", lb, fl,
                          lb / fl);
            md << buf;
        }
    }
    std::snprintf(buf, sizeof buf,
                  "**Geometric mean of the ratios (lockbox / float), %d scenes: %.2f** (goal: <= 1.0).\n", n, geomean);
    md << buf;
    std::printf("geomean_ratio=%.3f scenes=%d machine=%s\n", geomean, n, machine.c_str());
    const std::string doc = std::string(LOCKBOX_BENCH_RESULTS_DIR) + "/../../docs/benchmarks.md";
    SpliceMarkdown(doc, "compare", md.str(), "Benchmarks");
    return n > 0;
}

}  // namespace lockbox::scenes
