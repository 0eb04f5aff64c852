// Standalone cross-build driver (tests/cross/run.sh): prints the fixed-function hashes, the
// golden scene hashes of the light scenes (steps 1, 60, 600) and, once b2World::Save exists,
// the XXH3-64 of two scenes' snapshot bytes; compares them with the golden values, and exits 1
// on any mismatch. Built without CMake or GoogleTest so that every compiler, flag set and
// architecture builds the same sources the same way. run.sh also compares the printed lines
// of every cell with each other, so the output (stdout) holds results only; timings go to
// stderr.
//
// Usage: cross_driver <path to tests/golden/hashes.txt> [--with-heavy] [--max-step N]
//                     [--scenes a,b:N,...] [--limits a:N,...] [--snapshot-golden FILE]
//   --max-step N         record and compare only the steps <= N (slow emulated builds); the
//                        printed line then holds only those fields and is compared with the
//                        same fields of the golden line.
//   --scenes LIST        only these scenes (comma-separated names; they run in registry
//                        order); `name:N` also limits that scene to the steps <= N.
//   --limits LIST        `name:N` entries: limit these scenes to the steps <= N (the other
//                        scenes run as usual).
//   --replays LIST       comma-separated replay files to verify (ReplayVerify.h)
//   --scene-files DIR    the folder of the hand-written scene files (`file/<name>` golden
//                        lines; default: scenes/files/handmade beside tests/golden)
//   --snapshot-golden F  the file holding the golden `snapshot ...` lines (SnapshotHash.h). A
//                        missing line prints "new " and is not a failure (run.sh still
//                        requires every cell to print the same line).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "FunctionHash.h"
#include "GoldenScenes.h"
#include "ReplayVerify.h"
#include "SnapshotHash.h"

namespace {

// Seconds since `from`, for the timing lines on stderr (never compared).
double Since(std::chrono::steady_clock::time_point from) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - from).count();
}

// Looks `name` up in `list` (comma-separated `scene` or `scene:N` entries). Returns whether it
// is there, and lowers *limit to N when its entry has one.
bool Listed(std::string_view list, std::string_view name, int* limit) {
    while (!list.empty()) {
        const size_t comma = list.find(',');
        const std::string_view entry = list.substr(0, comma);
        const size_t colon = entry.find(':');
        if (entry.substr(0, colon) == name) {
            if (colon != std::string_view::npos) {
                const int own = std::atoi(std::string(entry.substr(colon + 1)).c_str());
                if (own < *limit) *limit = own;
            }
            return true;
        }
        if (comma == std::string_view::npos) break;
        list.remove_prefix(comma + 1);
    }
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: %s <golden hashes.txt> [--with-heavy] [--max-step N] [--scenes a,b:N] "
                     "[--limits a:N] [--snapshot-golden FILE]\n",
                     argv[0]);
        return 2;
    }
    bool withHeavy = false;
    int maxStep = 1 << 30;
    std::string scenesList;
    std::string limitsList;
    std::string snapshotGolden;
    std::string replays;
    for (int i = 2; i < argc; ++i) {
        if (std::strcmp(argv[i], "--with-heavy") == 0) withHeavy = true;
        if (std::strcmp(argv[i], "--max-step") == 0 && i + 1 < argc) maxStep = std::atoi(argv[++i]);
        if (std::strcmp(argv[i], "--scenes") == 0 && i + 1 < argc) scenesList = argv[++i];
        if (std::strcmp(argv[i], "--limits") == 0 && i + 1 < argc) limitsList = argv[++i];
        if (std::strcmp(argv[i], "--snapshot-golden") == 0 && i + 1 < argc) snapshotGolden = argv[++i];
        if (std::strcmp(argv[i], "--replays") == 0 && i + 1 < argc) replays = argv[++i];
        if (std::strcmp(argv[i], "--scene-files") == 0 && i + 1 < argc) lockbox::golden::SceneFileDir() = argv[++i];
    }
    if (lockbox::golden::SceneFileDir().empty()) {
        lockbox::golden::SceneFileDir() = lockbox::golden::GoldenPathFrom(argv[1], "/../../scenes/files/handmade");
    }
    int mismatches = 0;

    auto t0 = std::chrono::steady_clock::now();
    for (const auto& k : lockbox::function_hash::kKernels) {
        const uint64_t got = k.hash();
        const bool ok = got == k.golden;
        mismatches += ok ? 0 : 1;
        std::printf("%s function %s=0x%016llx\n", ok ? "ok  " : "FAIL", k.name, static_cast<unsigned long long>(got));
    }
    std::fflush(stdout);
    std::fprintf(stderr, "time functions %.2f s\n", Since(t0));

    const auto golden = lockbox::golden::ReadGolden(argv[1]);
    if (golden.empty()) {
        std::fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    for (const auto& p : lockbox::golden::GoldenPlan()) {
        if (p.heavy && !withHeavy) continue;
        int limit = maxStep;
        if (!scenesList.empty() && !Listed(scenesList, p.name, &limit)) continue;
        Listed(limitsList, p.name, &limit);
        t0 = std::chrono::steady_clock::now();
        const auto it = golden.find(p.name);
        std::string line;
        const bool ok =
            lockbox::golden::MatchesGolden(p, limit, it == golden.end() ? std::string() : it->second, &line);
        mismatches += ok ? 0 : 1;
        std::printf("%s %s\n", ok ? "ok  " : "FAIL", line.c_str());
        std::fflush(stdout);
        std::fprintf(stderr, "time %s %.2f s\n", p.name.c_str(), Since(t0));
    }

#if defined(LOCKBOX_CROSS_HAS_SNAPSHOT)
    for (const std::string_view scene : lockbox::snapshot_hash::kScenes) {
        namespace sh = lockbox::snapshot_hash;
        t0 = std::chrono::steady_clock::now();
        const std::string line = sh::SnapshotLine(scene, sh::kSteps);
        const std::string want = snapshotGolden.empty() ? std::string() : sh::ReadSnapshotGolden(snapshotGolden, scene);
        const bool ok = !line.empty() && (want.empty() || want == line);
        mismatches += ok ? 0 : 1;
        std::printf("%s %s\n", !ok ? "FAIL" : want.empty() ? "new " : "ok  ", line.c_str());
        std::fflush(stdout);
        std::fprintf(stderr, "time snapshot %.2f s\n", Since(t0));
    }
#else
    (void)snapshotGolden;
#endif

#if defined(LOCKBOX_CROSS_HAS_REPLAY)
    for (std::string_view list = replays; !list.empty();) {
        const size_t comma = list.find(',');
        t0 = std::chrono::steady_clock::now();
        const std::string path(list.substr(0, comma));
        mismatches += lockbox::replay_verify::VerifyLine(path) ? 0 : 1;
        std::fflush(stdout);
        std::fprintf(stderr, "time replay %s %.2f s\n", path.c_str(), Since(t0));
        if (comma == std::string_view::npos) break;
        list.remove_prefix(comma + 1);
    }
#else
    if (!replays.empty()) {
        std::printf("FAIL replays given, but this build has no replay support\n");
        ++mismatches;
    }
#endif

    std::printf("%s: %d mismatch(es)\n", mismatches == 0 ? "PASS" : "FAIL", mismatches);
    return mismatches == 0 ? 0 : 1;
}
