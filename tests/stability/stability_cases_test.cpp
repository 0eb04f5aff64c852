// The stability suite's fast budget: every case, with the limits written in
// samples/stability/src (the same functions the `stability` program prints).

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/stability/Cases.h"

namespace LOCKBOX_TEST_FILE {

using lockbox::stability::AllCases;
using lockbox::stability::Budget;
using lockbox::stability::FormatLine;
using lockbox::stability::RunCase;

std::vector<std::string> CaseNames() {
    std::vector<std::string> names;
    for (const auto& c : AllCases()) names.emplace_back(c.name);
    return names;
}

class StabilityCase : public ::testing::TestWithParam<std::string> {};

TEST_P(StabilityCase, MeetsEveryLimit) {
    const auto report = RunCase(GetParam(), Budget::fast);
    ASSERT_FALSE(report.results.empty());
    for (const auto& r : report.results) EXPECT_TRUE(r.pass) << FormatLine(r);
    // Every case walks at least one world with the telemetry on.
    EXPECT_GT(report.steps, 0);
}

INSTANTIATE_TEST_SUITE_P(Fast, StabilityCase, ::testing::ValuesIn(CaseNames()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(StabilitySuite, HasTheFifteenCasesInIssueOrder) {
    const auto& cases = AllCases();
    ASSERT_EQ(cases.size(), 15u);
    for (size_t i = 0; i < cases.size(); ++i) EXPECT_EQ(cases[i].id, static_cast<int>(i + 1));
}

TEST(StabilitySuite, UnknownCaseFails) {
    const auto report = RunCase("no_such_case", Budget::fast);
    ASSERT_EQ(report.results.size(), 1u);
    EXPECT_FALSE(report.results[0].pass);
}

TEST(StabilitySuite, LineFormat) {
    lockbox::stability::CaseResult r{"tall_stack", "sleep_step", 185, 600, true, false};
    EXPECT_EQ(FormatLine(r), "case=tall_stack metric=sleep_step value=185 limit=600 PASS");
    r.pass = false;
    r.limitation = true;
    EXPECT_EQ(FormatLine(r), "case=tall_stack metric=sleep_step value=185 limit=600 FAIL (limitation)");
}

}  // namespace LOCKBOX_TEST_FILE
