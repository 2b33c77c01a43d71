// A sweep report as Markdown (every table) or CSV (the per configuration ×
// family table, one row per group, for machines).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <rrlab/sweep/sweep_report.hpp>

namespace rrlab::sweep {

void write_report_markdown(std::ostream& out, const SweepReport& report);
void write_report_csv(std::ostream& out, const SweepReport& report);

// Shared by the formats: %.4g, "—" for NaN; a share as a percentage.
std::string short_number(double value);
std::string percent(double share);
// "collision 6, stalled 2" (most frequent first), "—" when no run failed.
std::string failure_modes_text(const GroupStats& g);
// "3 / 0": steps past a position / velocity limit after integration, summed
// over the runs; "—" for a part no run counts (older summaries; no velocity limits).
std::string limit_steps_text(const GroupStats& g);
// "a (95.0%, 8 µs, 4×); b (...)": a verdict's contenders with success and step time.
std::string contenders_text(const SweepReport& report, const FamilyVerdict& verdict);
// The verdict as a row reads it: its contenders, or why none are listed.
std::string verdict_text(const SweepReport& report, const FamilyVerdict& verdict);
// "8.1 points (discordance ≤ 9.0%)", or why no difference can be detected.
std::string detectable_text(const FamilyVerdict& verdict);
// The rule of "which method when" and of the fallback section, in prose
// (the same sentences in every format).
std::string verdict_rule_text();
std::string fallback_rule_text();
// "a, then b" with what each solves; the unsolved cases' count and listing.
std::string fallback_choice_text(const FamilyFallback& fallback);
std::string unsolved_text(const FamilyFallback& fallback);
// Success against the obstacle counts: the rule in prose (every format), a
// bin's label ("0", "4+"), and each (family, measure, group) of a sweep in
// that order (the groups' indices into report.groups).
std::string count_rule_text();
std::string count_bin_label(const DifficultyBin& bin);
struct CountRow {
  std::string family;
  size_t measure = 0;  // index into GroupStats::by_count
  size_t group = 0;
};
std::vector<CountRow> count_rows(const SweepReport& report, const std::string& sweep);
// Why a sweep's table of every two configurations is left out ("" when it is not).
std::string pairs_omitted_text(const SweepReport& report, const std::string& sweep);
// A p-value with 4 decimals, or in exponent form below 1e-4.
std::string p_value(double p);

}  // namespace rrlab::sweep
