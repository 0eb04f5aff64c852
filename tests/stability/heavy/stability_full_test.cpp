// The stability suite's full budget for the cases whose fast budget is shorter:
// pyramids with base 40, every library scene (the heavy ones included) compared at two
// quadrants' placements, and the 30- and 10-minute long runs. Release only (label heavy).

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/stability/Cases.h"

namespace LOCKBOX_TEST_FILE {

using lockbox::stability::AllCases;
using lockbox::stability::Budget;
using lockbox::stability::FormatLine;
using lockbox::stability::RunCase;

std::vector<std::string> LongCaseNames() {
    std::vector<std::string> names;
    for (const auto& c : AllCases())
        if (c.hasFastBudget) names.emplace_back(c.name);
    return names;
}

class StabilityCaseFull : public ::testing::TestWithParam<std::string> {};

TEST_P(StabilityCaseFull, MeetsEveryLimit) {
    const auto report = RunCase(GetParam(), Budget::full);
    ASSERT_FALSE(report.results.empty());
    for (const auto& r : report.results) EXPECT_TRUE(r.pass) << FormatLine(r);
}

INSTANTIATE_TEST_SUITE_P(Full, StabilityCaseFull, ::testing::ValuesIn(LongCaseNames()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace LOCKBOX_TEST_FILE
