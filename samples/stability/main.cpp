// stability: runs the numerical stability suite and prints one line per judged
// figure, `case=NAME metric=WHAT value=V limit=L PASS|FAIL`, then the headroom table (per case,
// then per library scene). Exits 1 when any figure fails.
//
//   stability [--fast] [--case NAME] [--no-scenes] [--scene-steps N]
//
// --fast runs the shortened budget of the long cases (the fast test suite's); --case runs one
// case; --no-scenes skips the per-scene headroom table; --scene-steps caps each scene's steps.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox/stability/Cases.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox;
using namespace lockbox::stability;

int main(int argc, char** argv) {
    Budget budget = Budget::full;
    std::string only;
    bool scenesTable = true;
    int sceneSteps = -1;
    lockbox::cli::OptionReader args("stability", argc, argv);
    while (args.Next()) {
        if (args.Is("--fast"))
            budget = Budget::fast;
        else if (args.Is("--case"))
            args.Text(only);
        else if (args.Is("--no-scenes"))
            scenesTable = false;
        else if (args.Is("--scene-steps"))
            args.Int(-1, 100000000, sceneSteps);
        else
            args.Unknown();
    }
    if (args.Failed()) return args.Fail("usage: stability [--fast] [--case NAME] [--no-scenes] [--scene-steps N]\n");

    std::vector<CaseReport> reports;
    int failed = 0, figures = 0;
    for (const CaseInfo& c : AllCases()) {
        if (!only.empty() && only != c.name) continue;
        const auto t0 = std::chrono::steady_clock::now();
        reports.push_back(RunCase(c.name, budget));
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (const CaseResult& r : reports.back().results) {
            std::printf("%s\n", FormatLine(r).c_str());
            ++figures;
            failed += !r.pass;
        }
        std::printf("# case %d %s: %lld steps in %.2f s\n", c.id, std::string(c.name).c_str(),
                    static_cast<long long>(reports.back().steps), secs);
        std::fflush(stdout);
    }
    if (reports.empty()) {
        std::fprintf(stderr, "unknown case: %s\n", only.c_str());
        return 2;
    }

    std::printf("\nheadroom: largest magnitude / format limit per quantity class (Q16.16 or Q32.32)\n");
    std::printf("%s\n", HeadroomTableHeader().c_str());
    for (const CaseReport& r : reports) std::printf("%s\n", HeadroomTableRow(r.name, r.headroom).c_str());
    if (scenesTable && only.empty()) {
        std::printf("%s\n", HeadroomTableHeader().c_str());
        for (std::string_view name : scenes::AllSceneNames()) {
            const SceneHeadroom s = MeasureSceneHeadroom(name, sceneSteps);
            if (s.steps == 0) continue;
            std::printf("%s\n", HeadroomTableRow(s.scene, s.headroom).c_str());
            std::fflush(stdout);
        }
    }
    std::printf("\nsummary: %zu cases, %d figures, %d failed\n", reports.size(), figures, failed);
    return failed == 0 ? 0 : 1;
}
