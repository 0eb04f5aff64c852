// Fast differential test: ~500 seeded random pairs per pair type against float Box2D 2.4.1.
// The full run (>= 10,000 per type) is heavy/manifold_diff_heavy_test.cpp. See
// manifold_diff_common.h for the harness and the comparison rules.

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "manifold_diff_common.h"

namespace LOCKBOX_TEST_FILE {

using manifold_diff::Pair;

class ManifoldDiff : public ::testing::TestWithParam<Pair> {};

TEST_P(ManifoldDiff, AgreesWithFloatBox2D) {
    const Pair type = GetParam();
    constexpr int kPairs = 500;
    const manifold_diff::RunResult r = manifold_diff::Run(type, kPairs, 0x5EED0000u + static_cast<unsigned>(type));
    std::printf(
        "%s: %d pairs, %d touching, %d disagreements, %d excluded by version rule, max deviation of "
        "agreeing pairs %.3g\n%s%s",
        manifold_diff::PairName(type), r.pairs, r.touching, r.disagreements, r.versionRule, r.maxDeviation,
        r.report.c_str(), r.versionReport.c_str());
    // At most 0.1 % of the pairs may disagree: none out of 500.
    EXPECT_LE(r.disagreements * 1000, r.pairs) << r.report;
    // The by-design exclusions stay a small minority (they are printed above).
    EXPECT_LE(r.versionRule * 20, r.pairs);
    // The agreeing pairs agree far better than the 1e-3 bound.
    EXPECT_LT(r.maxDeviation, 1e-3);
    // The distribution exercises contacts, not just misses.
    EXPECT_GT(r.touching, r.pairs / 5);
}

std::string PairTestName(const ::testing::TestParamInfo<Pair>& info) {
    static const char* const kNames[] = {"CircleCircle", "PolygonCircle",   "PolygonPolygon",  "EdgeCircle",
                                         "EdgePolygon",  "EdgeCircleGhost", "EdgePolygonGhost"};
    return kNames[static_cast<int>(info.param)];
}

INSTANTIATE_TEST_SUITE_P(AllPairs, ManifoldDiff,
                         ::testing::Values(Pair::circleCircle, Pair::polygonCircle, Pair::polygonPolygon,
                                           Pair::edgeCircle, Pair::edgePolygon, Pair::edgeCircleGhost,
                                           Pair::edgePolygonGhost),
                         PairTestName);

}  // namespace LOCKBOX_TEST_FILE
