#pragma once
/// The numerical stability suite (docs/stability.md): fifteen hard cases, each run on
/// lockbox in Q16.16/Q32.32 and judged by figures with written limits. The `stability` program
/// prints them and the tests in tests/stability assert them, through these same functions, so
/// each limit is defined once (in the case's source file).
///
/// Metrics are doubles for reporting only: they are read from a world after a step and never
/// written back, so they cannot change a simulation.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/state/Headroom.h"

namespace lockbox::stability {

/// How much simulated time a case spends where the suite allows a choice. The limits are the
/// same for both; `full` is the suite's own length (the program and the heavy tests), `fast`
/// shortens the long cases so the fast test suite fits its time budget (see AllCases()).
enum class Budget { fast, full };

/// One judged figure: `case=NAME metric=WHAT value=V limit=L PASS|FAIL`.
struct CaseResult {
    std::string name;    ///< case name, e.g. "tall_stack"
    std::string metric;  ///< what was measured, e.g. "top_drift_m"
    double value = 0;    ///< measured value (display unit in the metric name)
    double limit = 0;    ///< the case passes when value <= limit
    bool pass = false;   ///< value <= limit
    /// True when the limit is a documented limitation's measured figure (a regression bound),
    /// not a property the engine promises; docs/stability.md lists each one.
    bool limitation = false;
};

/// Everything one case produced.
struct CaseReport {
    std::string name;                 ///< case name
    std::vector<CaseResult> results;  ///< judged figures, in print order
    b2Headroom headroom;              ///< running maximum over every world and step of the case
    int64_t steps = 0;                ///< world steps taken (all worlds of the case)
    /// True when every result passed.
    bool Passed() const noexcept;
};

/// A case of the suite.
struct CaseInfo {
    int id;                    ///< the case number in docs/stability.md, 1..15
    std::string_view name;     ///< command-line and test name
    std::string_view summary;  ///< one line
    /// True when the case's `fast` budget differs from `full` (the full run is a heavy test).
    bool hasFastBudget;
};

/// The fifteen cases in the suite's order (docs/stability.md).
const std::vector<CaseInfo>& AllCases();

/// Runs one case by name; an unknown name gives a report with one failing "unknown_case" line.
CaseReport RunCase(std::string_view name, Budget budget);

/// Runs every case in order.
std::vector<CaseReport> RunAllCases(Budget budget);

/// The case line: `case=NAME metric=WHAT value=V limit=L PASS|FAIL` (values with 6
/// significant digits; a documented limitation adds ` (limitation)` after the verdict).
std::string FormatLine(const CaseResult& r);

/// Headroom of one library scene run (lockbox::scenes, default settings).
struct SceneHeadroom {
    std::string scene;    ///< scene name
    int steps = 0;        ///< steps run
    b2Headroom headroom;  ///< running maximum over the run
};

/// Runs a library scene with headroom telemetry on; steps < 0 uses the scene's default.
/// An unknown scene gives steps = 0.
SceneHeadroom MeasureSceneHeadroom(std::string_view scene, int steps = -1);

/// Header line of the headroom table (fractions of each format's limit, then saturations).
std::string HeadroomTableHeader();
/// One headroom table row: label, then per class the fraction of its limit (%.2e), then the
/// saturation count.
std::string HeadroomTableRow(std::string_view label, const b2Headroom& h);

}  // namespace lockbox::stability
