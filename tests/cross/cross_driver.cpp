// Standalone cross-build driver (tests/cross/run.sh): prints the fixed-function hashes and the
// golden scene hashes of the light scenes (steps 1, 60, 600), compares them with the golden
// values, and exits 1 on any mismatch. Built without CMake or GoogleTest so that every
// compiler, flag set and architecture builds the same sources the same way.
//
// Usage: cross_driver <path to tests/golden/hashes.txt> [--with-heavy] [--max-step N]
//   --max-step N  record and compare only the steps <= N (slow emulated builds); the printed
//                 line then holds only those fields and is compared with the same fields of
//                 the golden line.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "FunctionHash.h"
#include "GoldenScenes.h"

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <golden hashes.txt> [--with-heavy]\n", argv[0]);
        return 2;
    }
    bool withHeavy = false;
    int maxStep = 1 << 30;
    for (int i = 2; i < argc; ++i) {
        if (std::strcmp(argv[i], "--with-heavy") == 0) withHeavy = true;
        if (std::strcmp(argv[i], "--max-step") == 0 && i + 1 < argc) maxStep = std::atoi(argv[++i]);
    }
    int mismatches = 0;

    for (const auto& k : lockbox::function_hash::kKernels) {
        const uint64_t got = k.hash();
        const bool ok = got == k.golden;
        mismatches += ok ? 0 : 1;
        std::printf("%s function %s=0x%016llx\n", ok ? "ok  " : "FAIL", k.name,
                    static_cast<unsigned long long>(got));
    }

    const auto golden = lockbox::golden::ReadGolden(argv[1]);
    if (golden.empty()) {
        std::fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    for (const auto& p : lockbox::golden::GoldenPlan()) {
        if (p.heavy && !withHeavy) continue;
        const auto it = golden.find(p.name);
        std::string line;
        const bool ok = lockbox::golden::MatchesGolden(p, maxStep, it == golden.end() ? std::string() : it->second, &line);
        mismatches += ok ? 0 : 1;
        std::printf("%s %s\n", ok ? "ok  " : "FAIL", line.c_str());
        std::fflush(stdout);
    }
    std::printf("%s: %d mismatch(es)\n", mismatches == 0 ? "PASS" : "FAIL", mismatches);
    return mismatches == 0 ? 0 : 1;
}
