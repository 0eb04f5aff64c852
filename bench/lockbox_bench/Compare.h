#pragma once
/// `lockbox_bench --all --compare`: every SCENES.md scene on both engines, alternating engine
/// order between repeats (so drift in machine speed hits both), with the same iterations and
/// time step. Writes bench/results/<machine>/compare.csv and the table in docs/benchmarks.md
/// (or both into the directory --out names).
/// With --workers N (N > 1) lockbox also runs on N threads in the same alternation, and the
/// table gains a column: its time per step and the speed-up over one worker. A second table
/// splits both engines' one-worker steps by stage (broad phase, collide, set-up, velocity,
/// position, time of impact), so that the ratio shows where exact arithmetic costs time.
///
/// The geometric mean counts each SCENES.md scene once: bullet's six 60-step variants enter as
/// one scene whose ratio is their summed lockbox time over their summed float time.

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "BenchReport.h"
#include "BenchRunner.h"

namespace lockbox::scenes {

/// The leaf stages of a step, in the order of the stage table (solve_ms contains the three
/// solve stages), with the table's headings.
inline constexpr std::pair<const char*, const char*> kStages[] = {
    {"broadphase_ms", "broad phase"}, {"collide_ms", "collide"},        {"solveInit_ms", "set-up"},
    {"solveVelocity_ms", "velocity"}, {"solvePosition_ms", "position"}, {"solveTOI_ms", "TOI"}};
inline constexpr size_t kStageCount = std::size(kStages);

/// A run's per-step time of each stage of kStages (0 where the profile lacks it).
inline std::vector<double> StageTimes(const RunResult& r) {
    std::vector<double> out(kStageCount, 0.0);
    for (const auto& [k, v] : r.profile)
        for (size_t i = 0; i < kStageCount; ++i)
            if (k == kStages[i].first) out[i] = v;
    return out;
}

/// The two largest lockbox stage costs of a run, as "stage 41%, stage 22%".
inline std::string TopCosts(const RunResult& r) {
    double step = 0;
    for (const auto& [k, v] : r.profile)
        if (k == "step_ms") step = v;
    const std::vector<double> times = StageTimes(r);
    std::vector<std::pair<double, std::string>> stages;
    for (size_t i = 0; i < kStageCount; ++i) {
        const std::string key = kStages[i].first;
        stages.emplace_back(times[i], key.substr(0, key.size() - 3));
    }
    std::sort(stages.rbegin(), stages.rend());
    std::ostringstream os;
    for (size_t i = 0; i < 2 && i < stages.size() && step > 0; ++i) {
        if (i) os << ", ";
        os << stages[i].second << " " << static_cast<int>(std::lround(100 * stages[i].first / step)) << "%";
    }
    return os.str();
}

/// One row of the comparison (what compare.csv stores).
struct CompareRow {
    std::string name;
    int steps = 0, vel = 0, pos = 0, hz = 0;
    bool lockboxOk = false;
    double lbMs = 0, lbP95 = 0, flMs = 0, flP95 = 0;
    int bodies = 0, lbAwake = 0, flAwake = 0, lbContacts = 0, flContacts = 0;
    std::string hash, topCosts;
    int workers = 1;                         ///< worker count of the extra lockbox run (1: none)
    double lbWorkersMs = 0;                  ///< lockbox ms/step on `workers` threads
    int rounds = 0;                          ///< runs per engine the medians are taken over (0: not recorded)
    std::vector<double> lbStages, flStages;  ///< ms/step of each stage of kStages (empty: not measured)
};

/// Splits one CSV line (quoted fields may hold commas).
inline std::vector<std::string> SplitCsv(const std::string& line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (char c : line) {
        if (c == '"')
            quoted = !quoted;
        else if (c == ',' && !quoted)
            out.emplace_back();
        else
            out.back() += c;
    }
    return out;
}

/// Reads the rows of an existing compare.csv (empty when absent).
inline std::vector<CompareRow> ReadCompareCsv(const std::filesystem::path& path) {
    std::vector<CompareRow> rows;
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
        const auto f = SplitCsv(line);
        if (f.size() < 17) continue;
        CompareRow r;
        auto num = [](const std::string& t) { return t.empty() ? 0.0 : std::stod(t); };
        r.name = f[0];
        r.steps = static_cast<int>(num(f[1])), r.vel = static_cast<int>(num(f[2]));
        r.pos = static_cast<int>(num(f[3])), r.hz = static_cast<int>(num(f[4]));
        r.lockboxOk = !f[5].empty();
        r.lbMs = num(f[5]), r.lbP95 = num(f[6]), r.flMs = num(f[7]), r.flP95 = num(f[8]);
        r.bodies = static_cast<int>(num(f[10]));
        r.lbAwake = static_cast<int>(num(f[11])), r.flAwake = static_cast<int>(num(f[12]));
        r.lbContacts = static_cast<int>(num(f[13])), r.flContacts = static_cast<int>(num(f[14]));
        r.hash = f[15];
        r.topCosts = f[16];
        if (f.size() >= 19) {
            r.workers = std::max(1, static_cast<int>(num(f[17])));
            r.lbWorkersMs = num(f[18]);
        }
        if (f.size() >= 19 + 2 * kStageCount && r.lockboxOk) {
            for (size_t i = 0; i < kStageCount; ++i) {
                r.lbStages.push_back(num(f[19 + i]));
                r.flStages.push_back(num(f[19 + kStageCount + i]));
            }
        }
        if (f.size() >= 20 + 2 * kStageCount) r.rounds = static_cast<int>(num(f[19 + 2 * kStageCount]));
        rows.push_back(r);
    }
    return rows;
}

/// A row's run count for the table ("-" for a row kept from a table that did not record it).
inline std::string RunsText(const CompareRow& r) { return r.rounds > 0 ? std::to_string(r.rounds) : "-"; }

/// ms as microseconds with about three significant digits, never in exponent form.
inline std::string Micros(double ms) {
    const double us = 1000 * ms;
    char buf[32];
    std::snprintf(buf, sizeof buf, us >= 100 ? "%.0f" : us >= 10 ? "%.1f" : "%.2f", us);
    return buf;
}

/// The SCENES.md scene a shared scene's row counts for: "bullet" for each of bullet's six
/// variants, else the scene itself.
inline std::string CompareKey(std::string_view name) {
    return name.rfind("bullet_", 0) == 0 ? std::string("bullet") : std::string(name);
}

/// The SCENES.md scenes of the comparison, each once, in the shared scenes' order (what
/// --scenes accepts).
inline std::vector<std::string> CompareKeys() {
    std::vector<std::string> keys;
    for (auto name : SharedSceneNames()) {
        const std::string key = CompareKey(name);
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
    return keys;
}

/// The stage table: each stage's time per step on both engines and their ratio, per SCENES.md
/// scene (bullet's variants summed), and each stage's geometric mean ratio over the scenes where
/// both engines spend time in it. Scenes measured before the stage columns existed are left out.
inline std::string StageTable(const std::vector<CompareRow>& rows, const std::vector<std::string>& order,
                              const std::string& machine) {
    std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> perScene;
    for (const CompareRow& r : rows) {
        if (!r.lockboxOk || r.lbStages.size() != kStageCount || r.flStages.size() != kStageCount) continue;
        auto& [lb, fl] = perScene[CompareKey(r.name)];
        lb.resize(kStageCount, 0.0);
        fl.resize(kStageCount, 0.0);
        for (size_t i = 0; i < kStageCount; ++i) {
            lb[i] += r.lbStages[i];
            fl[i] += r.flStages[i];
        }
    }
    std::ostringstream md;
    md << "Machine `" << machine << "`, the one-worker runs of the table above (medians of each stage over "
       << "the repeats). Each cell is lockbox µs / float µs per step (ratio); the stages are Box2D's "
          "`b2Profile` fields, timed the same way in both engines. bullet sums its six variants.\n\n";
    md << "| scene |";
    for (const auto& stage : kStages) md << " " << stage.second << " |";
    md << "\n| --- |";
    for (size_t i = 0; i < kStageCount; ++i) md << " ---: |";
    md << "\n";
    std::vector<double> logSum(kStageCount, 0.0);
    std::vector<int> counted(kStageCount, 0);
    char buf[96];
    for (const std::string& key : order) {
        const auto it = perScene.find(key);
        if (it == perScene.end()) continue;
        const auto& [lb, fl] = it->second;
        md << "| " << key << " |";
        for (size_t i = 0; i < kStageCount; ++i) {
            if (lb[i] > 0 && fl[i] > 0) {
                std::snprintf(buf, sizeof buf, " %s / %s (%.2f) |", Micros(lb[i]).c_str(), Micros(fl[i]).c_str(),
                              lb[i] / fl[i]);
                logSum[i] += std::log(lb[i] / fl[i]);
                ++counted[i];
            } else {
                std::snprintf(buf, sizeof buf, " %s / %s |", Micros(lb[i]).c_str(), Micros(fl[i]).c_str());
            }
            md << buf;
        }
        md << "\n";
    }
    md << "| **geometric mean** |";
    for (size_t i = 0; i < kStageCount; ++i) {
        if (counted[i] > 0) {
            std::snprintf(buf, sizeof buf, " **%.2f** |", std::exp(logSum[i] / counted[i]));
        } else {
            std::snprintf(buf, sizeof buf, " n/a |");
        }
        md << buf;
    }
    md << "\n";
    return md.str();
}

/// The name in `only` that is neither a shared scene nor one of CompareKeys() ("bullet" for all
/// six variants), or empty when every name is one.
inline std::string UnknownCompareScene(const std::vector<std::string>& only) {
    const std::vector<std::string> keys = CompareKeys();
    const auto shared = SharedSceneNames();
    for (const std::string& name : only) {
        if (std::find(keys.begin(), keys.end(), name) == keys.end() &&
            std::find(shared.begin(), shared.end(), name) == shared.end())
            return name;
    }
    return {};
}

/// How many runs per engine a scene gets: at least `repeat`, and for a scene whose run lasts
/// only microseconds to a few milliseconds, enough runs for each engine to step for about
/// kMeasuredMs in all, so that one descheduled moment cannot move the median. A raised count is
/// odd, so the median is one run's figure. `lockbox` and `float` are the first round's runs.
inline int RoundsFor(int repeat, const RunResult& lockbox, const RunResult& flt) {
    constexpr double kMeasuredMs = 200;
    constexpr int kMaxRounds = 301;
    const auto runMs = [](const RunResult& r) { return r.msPerStep * r.settings.steps; };
    const double shortest = std::min(runMs(lockbox), runMs(flt));
    if (repeat >= kMaxRounds || !(shortest > 0)) return repeat;
    const int wanted = static_cast<int>(std::ceil(kMeasuredMs / shortest)) | 1;
    return std::max(repeat, std::min(kMaxRounds, wanted));
}

/// Runs the comparison for `only` (every SCENES.md scene when empty; other rows are kept from
/// the existing compare.csv) and rewrites compare.csv and the tables; false when nothing could
/// be compared. With `outDir` set, compare.csv and the tables (compare.md) go there, and
/// neither bench/results nor docs/benchmarks.md is touched.
inline bool RunCompare(int repeat, const std::vector<std::string>& only = {}, int workers = 1,
                       const std::string& outDir = {}) {
    RunSettings s;
    s.trackMetrics = false;
    const std::string machine = MachineName();
    const std::filesystem::path dir =
        outDir.empty() ? std::filesystem::path(LOCKBOX_BENCH_RESULTS_DIR) / machine : std::filesystem::path(outDir);
    // A folder that cannot be made is reported before the minutes of measuring, not after.
    std::error_code made;
    std::filesystem::create_directories(dir, made);
    if (made || !std::filesystem::is_directory(dir)) {
        std::fprintf(stderr, "lockbox_bench: cannot write into %s\n", dir.string().c_str());
        return false;
    }
    const std::vector<CompareRow> previous =
        only.empty() ? std::vector<CompareRow>{} : ReadCompareCsv(dir / "compare.csv");
    std::vector<CompareRow> rows;
    size_t keptRows = 0;
    for (auto name : SharedSceneNames()) {
        const std::string key(name);
        const auto named = [&](const std::string& n) { return std::find(only.begin(), only.end(), n) != only.end(); };
        const bool selected = only.empty() || named(key) || named(CompareKey(key));
        if (!selected) {
            for (const CompareRow& p : previous) {
                if (p.name != key) continue;
                rows.push_back(p);
                ++keptRows;
            }
            continue;
        }
        std::vector<RunResult> lbRuns, flRuns, wkRuns;
        int rounds = repeat;
        for (int i = 0; i < rounds; ++i) {
            RunResult a, b, w;
            bool okA = true;
            if (i % 2 == 0) {
                okA = RunOnce<LockboxEngine>(name, s, a);
                RunOnce<Box2DFloatEngine>(name, s, b);
                if (okA && workers > 1 && RunOnce<LockboxEngine>(name, s, w, workers)) wkRuns.push_back(w);
            } else {
                if (workers > 1 && RunOnce<LockboxEngine>(name, s, w, workers)) wkRuns.push_back(w);
                RunOnce<Box2DFloatEngine>(name, s, b);
                okA = RunOnce<LockboxEngine>(name, s, a);
            }
            if (okA) lbRuns.push_back(a);
            flRuns.push_back(b);
            if (i == 0) rounds = RoundsFor(repeat, okA ? a : b, b);
        }
        const RunResult fl = MedianOf(flRuns);
        PrintLine(fl);
        CompareRow row;
        row.name = key;
        row.steps = fl.settings.steps, row.vel = fl.settings.velocityIterations;
        row.pos = fl.settings.positionIterations, row.hz = fl.settings.hz;
        row.flMs = fl.msPerStep, row.flP95 = fl.p95Ms, row.bodies = fl.bodies;
        row.rounds = rounds;
        std::printf("scene=%s runs=%d\n", key.c_str(), rounds);
        row.flAwake = fl.awake, row.flContacts = fl.contacts;
        if (!lbRuns.empty()) {
            const RunResult lb = MedianOf(lbRuns);
            row.lbStages = StageTimes(lb);
            row.flStages = StageTimes(fl);
            PrintLine(lb);
            PrintProfile(lb);
            row.lockboxOk = true;
            row.lbMs = lb.msPerStep, row.lbP95 = lb.p95Ms, row.lbAwake = lb.awake, row.lbContacts = lb.contacts;
            char hash[32];
            std::snprintf(hash, sizeof hash, "0x%016" PRIx64, lb.hash);
            row.hash = hash;
            row.topCosts = TopCosts(lb);
            if (!wkRuns.empty()) {
                const RunResult wk = MedianOf(wkRuns);
                PrintLine(wk);
                // The bits do not depend on the workers.
                if (wk.hash != lb.hash) std::printf("scene=%s WORKERS CHANGED THE HASH\n", key.c_str());
                row.workers = workers;
                row.lbWorkersMs = wk.msPerStep;
            }
        } else {
            std::printf("scene=%s engine=lockbox unavailable (needs joints)\n", key.c_str());
        }
        std::fflush(stdout);
        rows.push_back(row);
    }

    // Ratios per SCENES.md scene (bullet variants summed) and their geometric mean.
    std::map<std::string, std::pair<double, double>> perScene;  // name -> (lockbox, float) ms
    std::vector<std::string> order;
    for (const CompareRow& r : rows) {
        if (!r.lockboxOk) continue;
        const std::string key = CompareKey(r.name);
        if (!perScene.count(key)) order.push_back(key);
        perScene[key].first += r.lbMs;
        perScene[key].second += r.flMs;
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

    {
        std::ofstream csv(dir / "compare.csv");
        if (!csv) {
            std::fprintf(stderr, "lockbox_bench: cannot write %s\n", (dir / "compare.csv").string().c_str());
            return false;
        }
        csv << "scene,steps,vel_iters,pos_iters,hz,lockbox_ms_per_step,lockbox_p95_ms,float_ms_per_step,"
               "float_p95_ms,ratio,bodies,lockbox_awake,float_awake,lockbox_contacts,float_contacts,"
               "lockbox_hash,top_costs,workers,lockbox_workers_ms_per_step";
        for (const char* engine : {"lockbox", "float"})
            for (const auto& stage : kStages) csv << "," << engine << "_" << stage.first;
        csv << ",runs\n";
        for (const CompareRow& r : rows) {
            csv << r.name << "," << r.steps << "," << r.vel << "," << r.pos << "," << r.hz << ",";
            if (r.lockboxOk) {
                csv << r.lbMs << "," << r.lbP95 << "," << r.flMs << "," << r.flP95 << "," << r.lbMs / r.flMs << ","
                    << r.bodies << "," << r.lbAwake << "," << r.flAwake << "," << r.lbContacts << "," << r.flContacts
                    << "," << r.hash << ",\"" << r.topCosts << "\"," << r.workers << ",";
                if (r.workers > 1) csv << r.lbWorkersMs;
                for (const auto* stages : {&r.lbStages, &r.flStages})
                    for (size_t i = 0; i < kStageCount; ++i) {
                        csv << ",";
                        if (i < stages->size()) csv << (*stages)[i];
                    }
            } else {
                csv << ",," << r.flMs << "," << r.flP95 << ",," << r.bodies << ",," << r.flAwake << ",," << r.flContacts
                    << ",,unavailable,1,";
                for (size_t i = 0; i < 2 * kStageCount; ++i) csv << ",";
            }
            csv << ",";
            if (r.rounds > 0) csv << r.rounds;
            csv << "\n";
        }
    }

    std::ostringstream md;
    md << "Machine `" << machine << "`, at least " << repeat
       << " run(s) per engine, engines alternating (a scene whose run lasts under 200 ms runs until each engine "
          "has stepped for about 200 ms, at most 301 times; `runs` gives the count); "
       << "release build; only `b2World::Step` is timed. Same scene definitions, iterations and time step "
          "(1092/65536 s) on both engines.";
    if (keptRows > 0) {
        // Rows from different runs met different machine speeds; say which ones are new.
        md << " Re-measured in the last run:";
        for (size_t i = 0; i < only.size(); ++i) md << (i ? ", " : " ") << only[i];
        md << "; the other rows are kept from an earlier run.";
    }
    md << "\n\n";
    // The workers column appears when every measured row has a run on more than one worker.
    int tableWorkers = 0;
    for (const CompareRow& r : rows) {
        if (!r.lockboxOk) continue;
        if (tableWorkers == 0) tableWorkers = r.workers;
        if (r.workers != tableWorkers) tableWorkers = 1;
    }
    const bool workersColumn = tableWorkers > 1;
    md << "| scene | steps | runs | vel/pos | lockbox ms/step | float ms/step | ratio | lockbox p95 | float p95 | "
          "bodies | contacts lockbox/float | lockbox top costs |";
    if (workersColumn) md << " lockbox " << tableWorkers << " workers ms/step (speed-up) |";
    md << "\n| --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |"
       << (workersColumn ? " ---: |" : "") << "\n";
    char buf[512];
    for (const CompareRow& r : rows) {
        if (r.lockboxOk) {
            std::snprintf(buf, sizeof buf, "| %s | %d | %s | %d/%d | %s | %s | %.2f | %s | %s | %d | %d/%d | %s |\n",
                          r.name.c_str(), r.steps, RunsText(r).c_str(), r.vel, r.pos, MsText(r.lbMs).c_str(),
                          MsText(r.flMs).c_str(), r.lbMs / r.flMs, MsText(r.lbP95).c_str(), MsText(r.flP95).c_str(),
                          r.bodies, r.lbContacts, r.flContacts, r.topCosts.c_str());
            if (workersColumn) {
                md << std::string(buf, std::strlen(buf) - 1);
                std::snprintf(buf, sizeof buf, " %s (%.2fx) |\n", MsText(r.lbWorkersMs).c_str(),
                              r.lbMs / r.lbWorkersMs);
            }
        } else {
            std::snprintf(buf, sizeof buf,
                          "| %s | %d | %s | %d/%d | n/a | %s | n/a | n/a | %s | %d | -/%d | "
                          "needs joints |\n",
                          r.name.c_str(), r.steps, RunsText(r).c_str(), r.vel, r.pos, MsText(r.flMs).c_str(),
                          MsText(r.flP95).c_str(), r.bodies, r.flContacts);
            if (workersColumn) {
                md << std::string(buf, std::strlen(buf) - 1);
                std::snprintf(buf, sizeof buf, " n/a |\n");
            }
        }
        md << buf;
    }
    md << "\n";
    if (perScene.count("bullet")) {
        const auto& [lb, fl] = perScene["bullet"];
        std::snprintf(buf, sizeof buf, "bullet (six variants summed): %s / %s ms = ratio %.2f.\n\n", MsText(lb).c_str(),
                      MsText(fl).c_str(), lb / fl);
        md << buf;
    }
    std::snprintf(buf, sizeof buf,
                  "**Geometric mean of the ratios (lockbox / float), %d scenes: %.2f** (goal: <= 0.9).\n", n, geomean);
    md << buf;
    std::printf("geomean_ratio=%.3f scenes=%d machine=%s\n", geomean, n, machine.c_str());
    if (!outDir.empty()) {
        std::ofstream tables(dir / "compare.md");
        if (!(tables << md.str() << "\n" << StageTable(rows, order, machine))) {
            std::fprintf(stderr, "lockbox_bench: cannot write %s\n", (dir / "compare.md").string().c_str());
            return false;
        }
        std::printf("wrote %s and %s\n", (dir / "compare.csv").string().c_str(), (dir / "compare.md").string().c_str());
        return n > 0;
    }
    const std::string doc = std::string(LOCKBOX_BENCH_RESULTS_DIR) + "/../../docs/benchmarks.md";
    SpliceMarkdown(doc, "compare", md.str(), "Benchmarks");
    SpliceMarkdown(doc, "stages", StageTable(rows, order, machine), "Benchmarks");
    return n > 0;
}

}  // namespace lockbox::scenes
