// Full differential test: 20,000 seeded random pairs per pair type against float Box2D 2.4.1
// (the fast version in ../manifold_diff_test.cpp runs 500). Disagreements are printed with
// their class and must stay at or below 0.1 % per type; pairs where 2.2.1 and 2.4.1 differ
// by design are printed and counted separately (see manifold_diff_common.h).

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "../manifold_diff_common.h"

namespace LOCKBOX_TEST_FILE {

using manifold_diff::Pair;

class ManifoldDiffHeavy : public ::testing::TestWithParam<Pair> {};

TEST_P(ManifoldDiffHeavy, AgreesWithFloatBox2D) {
    const Pair type = GetParam();
    constexpr int kPairs = 20000;
    const manifold_diff::RunResult r = manifold_diff::Run(type, kPairs, 0xB0C5000u + static_cast<unsigned>(type));
    std::printf(
        "%s: %d pairs, %d touching, %d disagreements, %d excluded by version rule, max deviation of "
        "agreeing pairs %.3g\n%s",
        manifold_diff::PairName(type), r.pairs, r.touching, r.disagreements, r.versionRule, r.maxDeviation,
        r.report.c_str());
    // Only the first part of the by-design list, to keep the log readable.
    std::printf("%s\n", r.versionReport.substr(0, 4000).c_str());
    EXPECT_LE(r.disagreements * 1000, r.pairs) << r.report;
    EXPECT_LE(r.versionRule * 20, r.pairs);
    EXPECT_LT(r.maxDeviation, 1e-3);
    EXPECT_GT(r.touching, r.pairs / 5);
}

std::string PairTestName(const ::testing::TestParamInfo<Pair>& info) {
    static const char* const kNames[] = {"CircleCircle", "PolygonCircle",   "PolygonPolygon",  "EdgeCircle",
                                         "EdgePolygon",  "EdgeCircleGhost", "EdgePolygonGhost"};
    return kNames[static_cast<int>(info.param)];
}

INSTANTIATE_TEST_SUITE_P(AllPairs, ManifoldDiffHeavy,
                         ::testing::Values(Pair::circleCircle, Pair::polygonCircle, Pair::polygonPolygon,
                                           Pair::edgeCircle, Pair::edgePolygon, Pair::edgeCircleGhost,
                                           Pair::edgePolygonGhost),
                         PairTestName);

}  // namespace LOCKBOX_TEST_FILE
