// A sweep report as JSON (the REST answer of a finished sweep): the same
// numbers as the md/html/csv writers; NaN (no run with a finite distance) as null.
#pragma once

#include <nlohmann/json.hpp>

#include <rrlab/sweep/sweep_report.hpp>

namespace rrlab::sweep {

// At most this many rows per table (groups, comparisons, ranking, pairs) and
// names per verdict: a sweep of 100,000 configurations still answers in a
// few MB. Rows are kept best-ranked first (each sweep's ranking); a cut
// table is named under "truncated" with its total and the rows shown, and
// every run stays readable through GET /api/sweeps/{id}/runs.
inline constexpr size_t kMaxReportRows = 5000;
inline constexpr size_t kMaxVerdictNames = 200;
// Unsolved case keys listed over all families (each lists at most
// kMaxUnsolvedListed): past it a family gives its count alone.
inline constexpr size_t kMaxUnsolvedKeys = 2000;

nlohmann::json report_json(const SweepReport& report, size_t max_rows = kMaxReportRows);

}  // namespace rrlab::sweep
