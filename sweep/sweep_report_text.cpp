#include <rrlab/sweep/sweep_report_text.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#include <algorithm>
#include <array>
#include <tuple>

namespace rrlab::sweep {

namespace {

std::string csv_number(double value) {
  if (std::isnan(value)) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", value);
  return buf;
}

// CSV field: quoted when it holds a comma, quote or newline.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Markdown cell: a | would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// A share as percentage points: "20 points".
std::string points(double share) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.1f", 100 * share);
  std::string text = buf;
  if (text.ends_with(".0")) text.resize(text.size() - 2);
  return text + " points";
}

std::string wlt(const WinLossTie& t) {
  return std::to_string(t.wins) + "/" + std::to_string(t.losses) + "/" + std::to_string(t.ties);
}

// "What to try when the first choice fails": the pair per family, then each
// family's unsolved cases with the commands that write them.
void write_fallbacks_markdown(std::ostream& out, const SweepReport& report, const std::string& sweep) {
  out << "\n### What to try when the first choice fails\n\n" << fallback_rule_text() << "\n\n"
      << "| family | first choice, then fallback (solved/cases) | cost µs/step | solved by some configuration | unsolved |\n"
         "|---|---|---:|---:|---:|\n";
  for (const FamilyFallback& f : report.fallbacks) {
    if (f.sweep != sweep) continue;
    out << "| " << cell(f.family) << " | " << cell(fallback_choice_text(f)) << " | " << short_number(f.cost_us) << " | "
        << f.solved_by_some << "/" << f.cases << " | " << f.unsolved << " |\n";
  }
  for (const FamilyFallback& f : report.fallbacks) {
    if (f.sweep != sweep || f.unsolved == 0) continue;
    out << "\n- **" << cell(f.family) << "**, unsolved: " << unsolved_text(f) << "\n";
    for (const std::string& command : unsolved_commands(f)) out << "  - `" << command << "`\n";
  }
}

// Success against the obstacle counts: one row per family, measure and
// configuration, a column per bin ("successes/n").
void write_counts_markdown(std::ostream& out, const SweepReport& report, const std::string& sweep) {
  const std::vector<CountRow> rows = count_rows(report, sweep);
  if (rows.empty()) return;
  out << "\n### Success against obstacle counts\n\n" << count_rule_text() << "\n\n| family | count | method config |";
  const std::array<DifficultyBin, kCountBins>& first = report.groups[rows.front().group].by_count[rows.front().measure].bins;
  for (const DifficultyBin& b : first) out << ' ' << count_bin_label(b) << " |";
  out << "\n|---|---|---|";
  for (size_t k = 0; k < kCountBins; ++k) out << "---:|";
  out << '\n';
  for (const CountRow& row : rows) {
    const GroupStats& g = report.groups[row.group];
    const CountDifficulty& c = g.by_count[row.measure];
    out << "| " << cell(row.family) << " | " << c.measure << " | " << cell(g.config_key) << " |";
    for (const DifficultyBin& b : c.bins)
      out << ' ' << (b.n ? std::to_string(b.successes) + "/" + std::to_string(b.n) : "—") << " |";
    out << '\n';
  }
}

}  // namespace

std::string count_rule_text() {
  return "Success against two counts of each generated case's witness.difficulty: blocking_obstacles, the distinct "
         "obstacles the minimum-norm (pinv) arm meets over the run, and tight_obstacles, the obstacles within twice "
         "the family's clearance of the witness arm. Bins of 0, 1, 2, 3 and " + std::to_string(kCountBins - 1) +
         " or more obstacles; a cell is the configuration's successes of the family's cases in that bin. A count "
         "is shown for a family whose cases fill at least two bins.";
}

std::string count_bin_label(const DifficultyBin& bin) {
  const std::string low = std::to_string(long(bin.low));
  if (!std::isfinite(bin.high)) return low + "+";
  return bin.high == bin.low ? low : low + "–" + std::to_string(long(bin.high));
}

std::vector<CountRow> count_rows(const SweepReport& report, const std::string& sweep) {
  std::vector<CountRow> rows;
  for (size_t i = 0; i < report.groups.size(); ++i) {
    const GroupStats& g = report.groups[i];
    if (g.sweep != sweep) continue;
    for (size_t m = 0; m < g.by_count.size(); ++m) rows.push_back({g.family, m, i});
  }
  // the groups are by configuration, then family: by family, then measure, configurations in that order
  std::stable_sort(rows.begin(), rows.end(), [](const CountRow& x, const CountRow& y) {
    return std::tie(x.family, x.measure) < std::tie(y.family, y.measure);
  });
  return rows;
}

std::string failure_modes_text(const GroupStats& g) {
  std::vector<std::pair<size_t, std::string>> modes;
  for (const auto& [mode, count] : g.failure_modes) modes.emplace_back(count, mode);
  std::stable_sort(modes.begin(), modes.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::string text;
  for (const auto& [count, mode] : modes) text += (text.empty() ? "" : ", ") + mode + " " + std::to_string(count);
  return text.empty() ? "—" : text;
}

std::string limit_steps_text(const GroupStats& g) {
  const LimitSteps& l = g.limit_steps;
  if (l.counted_steps == 0) return "—";
  return std::to_string(l.position) + " / " + (l.velocity_counted_steps ? std::to_string(l.velocity) : std::string("—"));
}

std::string contenders_text(const SweepReport& report, const FamilyVerdict& verdict) {
  std::string list;
  for (size_t i : verdict.contenders) {
    const GroupStats& g = report.groups[i];
    list += (list.empty() ? "" : "; ") + g.config_key + " (" + percent(g.success_rate) + ", " +
            short_number(g.step_us_p50) + " µs" +
            (std::isnan(g.step_ratio_to_pinv) ? "" : ", " + short_number(g.step_ratio_to_pinv) + "×") + ")";
  }
  return list;
}

std::string verdict_text(const SweepReport& report, const FamilyVerdict& verdict) {
  switch (verdict.status) {
    case VerdictStatus::kNoSuccess:
      return "no configuration succeeded on any case";
    case VerdictStatus::kTooFewCases:
      return "too few cases to separate the methods (a difference of " + points(kSeparableDifference) + " needs about " +
             std::to_string(verdict.cases_needed) + " cases); best observed, not separated from the others: " +
             verdict.best + " (" + percent(report.groups[verdict.best_group].success_rate) + ")";
    case VerdictStatus::kContenders:
      break;
  }
  return contenders_text(report, verdict);
}

std::string detectable_text(const FamilyVerdict& verdict) {
  if (!std::isfinite(verdict.detectable)) return "none: too few cases for p < 0.05";
  return points(verdict.detectable) + " (discordance ≤ " + percent(verdict.discordance) + ")";
}

std::string verdict_rule_text() {
  return "Per family: the best configuration (success rate, then median max tracking error; never the witness "
         "lane) and every one whose success is not significantly below it (paired on the same cases: not fewer "
         "wins than losses with an exact McNemar p < 0.05) and that succeeds at least once (a configuration without "
         "a success is never listed beside one with), with step time. Detects: the smallest difference in success "
         "the cases detect with 80 % power at two-sided p < 0.05 (the exact McNemar test's power, at the "
         "discordance, the share of cases where exactly one of the two succeeds, taken at its 95 % upper Wilson "
         "bound), over the comparisons with the best that found no difference, at their largest discordance (where every other "
         "configuration is significantly worse, the runner-up's, for information: the best stands alone; with one "
         "configuration, every case taken as discordant). Where it exceeds " +
         points(kSeparableDifference) +
         " while some configuration is not shown worse, there are too few cases to separate the methods: none is "
         "listed, the best observed is named as not separated, and the row gives about how many cases a difference "
         "of " + points(kSeparableDifference) + " needs.";
}

std::string fallback_rule_text() {
  return "Per family: the first choice A and the fallback B that together solve the most cases (a case counts when A "
         "solves it or, failing A, B does), then the lowest cost per step (A's step time plus B's times A's failure "
         "share), one configuration before two (B only when it solves a case A fails); pairs among the family's " +
         std::to_string(kMaxFallbackConfigs) +
         " most successful configurations. An offline upper bound: B is credited with what it did when run from "
         "the start, not from where A failed. The witness lane is the certificate, not a method: never a "
         "candidate, never counted as solving. Unsolved: the cases no configuration solves; those the witness "
         "solves are the frontier. The commands write exactly the listed cases (the first " +
         std::to_string(kMaxUnsolvedListed) +
         " of a family); add the sweep entry's options, if it had any, as --option KEY=VALUE.";
}

std::string fallback_choice_text(const FamilyFallback& f) {
  if (f.first.empty()) return "—";
  if (f.solved_by_some == 0) return "none: no configuration solves any of the " + std::to_string(f.cases) + " cases";
  const std::string first = f.first + " " + std::to_string(f.first_solved) + "/" + std::to_string(f.pair_cases);
  if (f.second.empty()) return first + ", alone: no configuration solves a case it fails";
  return first + ", then " + f.second + ": " + std::to_string(f.pair_solved) + "/" + std::to_string(f.pair_cases) +
         " (" + percent(double(f.pair_solved) / double(f.pair_cases)) + ", +" +
         std::to_string(f.pair_solved - f.first_solved) + ")";
}

std::string unsolved_text(const FamilyFallback& f) {
  std::string text = std::to_string(f.unsolved) + " of " + std::to_string(f.cases);
  if (f.witness_solves) text += " (the witness solves " + std::to_string(*f.witness_solves) + ")";
  if (f.unsolved == 0) return text;
  text += ": ";
  for (size_t i = 0; i < f.unsolved_listed.size(); ++i) {
    const CaseRef& ref = f.unsolved_listed[i];
    text += (i ? ", " : "") + ref.scenario_key + (f.several_seeds ? " (seed " + std::to_string(ref.seed) + ")" : "");
  }
  if (f.unsolved_listed.size() < f.unsolved)
    text += " (the first " + std::to_string(f.unsolved_listed.size()) + " of " + std::to_string(f.unsolved) + ")";
  return text;
}

std::string pairs_omitted_text(const SweepReport& report, const std::string& sweep) {
  const auto omitted = report.pairs_omitted.find(sweep);
  if (omitted == report.pairs_omitted.end()) return "";
  return "Left out: this sweep has " + std::to_string(omitted->second) + " configurations, more than the " +
         std::to_string(kMaxPairedConfigs) +
         " whose every pair is compared (their number grows with the square); each configuration is paired with "
         "pinv and with its family's best above.";
}

std::string p_value(double p) {
  char buf[40];
  if (p < 1e-4)
    std::snprintf(buf, sizeof buf, "%.1e", p);
  else
    std::snprintf(buf, sizeof buf, "%.4f", p);
  return buf;
}

std::string short_number(double value) {
  if (std::isnan(value)) return "—";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.4g", value);
  return buf;
}

std::string percent(double share) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100 * share);
  return buf;
}

void write_report_markdown(std::ostream& out, const SweepReport& report) {
  out << "# Sweep report\n\n"
      << "Success as judged by each sweep's criteria when the run was stored; interval: 95 % Wilson score. "
         "Min distance over runs with obstacles (p10: 10th percentile). Step time: median over runs of each "
         "run's step_us.p50 and of each run's step_us.p99 (wall clock, µs). Jerk: median over runs of each run's "
         "RMS joint jerk (rad/s³; the Euclidean norm over joints of q's third difference / dt³). Steps past limits: "
         "steps whose integrated q ended past a joint position limit / whose applied velocity exceeded a velocity "
         "limit, summed over the runs (— where the runs' summaries predate the count, or have no velocity limits).\n";
  if (report.sweeps.empty()) out << "\nNo sweep runs stored.\n";
  for (const std::string& sweep : report.sweeps) {
    out << "\n## " << sweep << "\n\n"
        << "| method config | family | n | success | 95% CI | min dist median | min dist p10 | max track err median "
           "| joint-limit viol. | steps past limits q / q̇ | non-finite | jerk RMS median | step µs p50 | step µs p99 "
           "| step × pinv | first failures |\n"
        << "|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const GroupStats& g : report.groups) {
      if (g.sweep != sweep) continue;
      out << "| " << cell(g.config_key) << " | " << cell(g.family) << " | " << g.n << " | " << percent(g.success_rate)
          << " | " << percent(g.success_interval.low) << "–" << percent(g.success_interval.high) << " | "
          << short_number(g.median_min_distance) << " | " << short_number(g.p10_min_distance) << " | "
          << short_number(g.median_max_tracking_error) << " | " << percent(g.joint_limit_share) << " | "
          << limit_steps_text(g) << " | " << percent(g.nonfinite_share) << " | " << short_number(g.median_rms_jerk) << " | "
          << short_number(g.step_us_p50) << " | " << short_number(g.step_us_p99)
          << " | " << short_number(g.step_ratio_to_pinv) << " | " << cell(failure_modes_text(g)) << " |\n";
    }
    write_counts_markdown(out, report, sweep);
    out << "\n### Which method when\n\n" << verdict_rule_text() << "\n\n"
        << "| family | cases | detects | configurations (success, step µs p50, × pinv) |\n|---|---:|---|---|\n";
    for (const FamilyVerdict& v : report.verdicts) {
      if (v.sweep != sweep) continue;
      out << "| " << cell(v.family) << " | " << v.cases << " | " << detectable_text(v) << " | "
          << cell(verdict_text(report, v)) << " |\n";
    }
    write_fallbacks_markdown(out, report, sweep);
    out << "\n### Against pinv and the family's best\n\nPaired on the same cases of a family: the "
           "configuration's wins/losses/ties on success, and the exact McNemar p-value of the wins against "
           "the losses.\n\n"
        << "| family | method config | against | cases | success W/L/T | McNemar p |\n|---|---|---|---:|---|---:|\n";
    for (const FamilyComparison& c : report.comparisons) {
      if (c.sweep != sweep) continue;
      out << "| " << cell(c.family) << " | " << cell(c.config_key) << " | " << c.role << " (" << cell(c.reference)
          << ") | " << c.cases << " | " << wlt(c.success) << " | " << p_value(c.mcnemar_p) << " |\n";
    }
    out << "\n### Ranking\n\nBy success rate, then median max tracking error.\n\n"
        << "| rank | method config | n | success | max track err median |\n|---:|---|---:|---:|---:|\n";
    int rank = 0;
    for (const RankEntry& r : report.ranking) {
      if (r.sweep != sweep) continue;
      out << "| " << ++rank << " | " << cell(r.config_key) << " | " << r.n << " | " << percent(r.success_rate) << " | "
          << short_number(r.median_max_tracking_error) << " |\n";
    }
    out << "\n### Paired comparisons\n\nOn the same cases (scenario and seed): A's wins/losses/ties against B, on "
           "success, and on min distance (larger wins, ties within 1e-9).\n\n";
    if (const std::string omitted = pairs_omitted_text(report, sweep); !omitted.empty()) {
      out << omitted << "\n";
      continue;
    }
    out << "| A | B | cases | success W/L/T | min distance W/L/T |\n|---|---|---:|---|---|\n";
    for (const PairedComparison& p : report.pairs) {
      if (p.sweep != sweep) continue;
      out << "| " << cell(p.a) << " | " << cell(p.b) << " | " << p.cases << " | " << wlt(p.success) << " | "
          << wlt(p.min_distance) << " |\n";
    }
  }
}

namespace {
// "position,velocity,counted": empty where no run counts
std::string limit_steps_csv(const LimitSteps& l) {
  if (l.counted_steps == 0) return ",,";
  return std::to_string(l.position) + ',' + (l.velocity_counted_steps ? std::to_string(l.velocity) : std::string()) +
         ',' + std::to_string(l.counted_steps);
}
}  // namespace

void write_report_csv(std::ostream& out, const SweepReport& report) {
  out << "sweep,config,family,n,successes,success_rate,ci_low,ci_high,min_distance_median,min_distance_p10,"
         "max_tracking_error_median,joint_limit_share,position_limit_steps,velocity_limit_steps,counted_steps,"
         "nonfinite_share,rms_jerk_median,step_us_p50_median,"
         "step_us_p99_median,"
         "step_ratio_to_pinv,first_failures\n";
  for (const GroupStats& g : report.groups) {
    out << csv_field(g.sweep) << ',' << csv_field(g.config_key) << ',' << csv_field(g.family) << ',' << g.n << ','
        << g.successes << ',' << csv_number(g.success_rate) << ',' << csv_number(g.success_interval.low) << ','
        << csv_number(g.success_interval.high) << ',' << csv_number(g.median_min_distance) << ','
        << csv_number(g.p10_min_distance) << ',' << csv_number(g.median_max_tracking_error) << ','
        << csv_number(g.joint_limit_share) << ',' << limit_steps_csv(g.limit_steps) << ','
        << csv_number(g.nonfinite_share) << ','
        << csv_number(g.median_rms_jerk) << ','
        << csv_number(g.step_us_p50) << ',' << csv_number(g.step_us_p99) << ',' << csv_number(g.step_ratio_to_pinv)
        << ',' << csv_field(failure_modes_text(g) == "—" ? "" : failure_modes_text(g)) << '\n';
  }
}

}  // namespace rrlab::sweep
