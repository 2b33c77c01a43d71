#include <rrlab/sweep/sweep_report.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <rrlab/methods/witness_playback.hpp>
#include <rrlab/sweep/sweep_power.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::sweep {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using GroupKey = std::tuple<std::string, std::string, std::string>;  // sweep, config, family

// What a report reads of one run's stored summary.
struct RunFacts {
  const storage::SweepRunEntry* entry;
  double min_distance = kInf;  // null (no obstacles, or not finite): +inf
  double max_tracking_error = std::numeric_limits<double>::quiet_NaN();
  bool joint_limit_violated = false;
  long nonfinite_steps = 0;
  long steps = 0;
  long position_limit_steps = -1, velocity_limit_steps = -1;  // -1: not in the summary (older, or no velocity limits)
  double rms_jerk = std::numeric_limits<double>::quiet_NaN();  // null (too short, or older summaries): NaN
  double step_p50 = 0, step_p99 = 0;
  double clearance = std::numeric_limits<double>::quiet_NaN();     // the witness's, generated cases
  double limit_margin = std::numeric_limits<double>::quiet_NaN();  // the witness's, generated cases
  std::array<int, kCountMeasures.size()> counts;                    // kCountMeasures; -1: not given
};

// An obstacle count of the difficulty: a non-negative integer, else -1.
int count_or_none(const nlohmann::json& d, const char* key) {
  if (!d.contains(key) || !d[key].is_number()) return -1;
  const double v = d[key].get<double>();
  return v >= 0 && v <= 1e9 && v == std::floor(v) ? int(v) : -1;
}

double number_or(const nlohmann::json& j, const char* key, double def) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : def;
}

RunFacts facts_of(const storage::SweepRunEntry& e) {
  RunFacts f{&e};
  f.counts.fill(-1);
  if (e.difficulty_json) {
    try {
      const nlohmann::json d = parse_json(*e.difficulty_json);
      f.clearance = number_or(d, "clearance", f.clearance);
      f.limit_margin = number_or(d, "limit_margin", f.limit_margin);
      for (size_t m = 0; m < kCountMeasures.size(); ++m) f.counts[m] = count_or_none(d, kCountMeasures[m]);
    } catch (const std::exception&) {  // a difficulty that is not JSON counts as none
    }
  }
  if (!e.summary_json) return f;
  nlohmann::json s;
  try {
    s = parse_json(*e.summary_json);
  } catch (const std::exception&) {  // not JSON, or nested too deep
    throw std::runtime_error("run " + std::to_string(e.run_id) + " (" + e.row.key + "): its summary is not JSON");
  }
  f.min_distance = number_or(s, "min_distance", kInf);
  f.max_tracking_error = number_or(s, "max_tracking_error", std::numeric_limits<double>::quiet_NaN());
  f.joint_limit_violated = s.value("joint_limit_violated", false);
  f.nonfinite_steps = s.value("nonfinite_steps", 0L);
  f.steps = s.contains("steps") && s["steps"].is_number_integer() ? s["steps"].get<long>() : 0;
  for (auto [key, out] : {std::pair{"position_limit_steps", &f.position_limit_steps},
                          std::pair{"velocity_limit_steps", &f.velocity_limit_steps}})
    if (s.contains(key) && s[key].is_number_integer() && s[key].get<long>() >= 0) *out = s[key].get<long>();
  f.rms_jerk = number_or(s, "rms_jerk", f.rms_jerk);
  if (s.contains("step_us") && s["step_us"].is_object()) {
    f.step_p50 = number_or(s["step_us"], "p50", 0);
    f.step_p99 = number_or(s["step_us"], "p99", 0);
  }
  return f;
}

GroupStats group_stats(const std::vector<const RunFacts*>& runs) {
  GroupStats g;
  const storage::SweepRunRow& row = runs.front()->entry->row;
  g.sweep = row.sweep;
  g.config_key = row.config_key;
  g.family = report_family(row);
  g.n = runs.size();
  std::vector<double> distances, errors, jerks, p50s, p99s;
  size_t limits = 0, nonfinite = 0;
  for (const RunFacts* f : runs) {
    g.successes += f->entry->row.success ? 1 : 0;
    if (!f->entry->row.success) ++g.failure_modes[f->entry->row.failure_mode.value_or("unrecorded")];
    if (std::isfinite(f->min_distance)) distances.push_back(f->min_distance);
    if (!std::isnan(f->max_tracking_error)) errors.push_back(f->max_tracking_error);
    if (!std::isnan(f->rms_jerk)) jerks.push_back(f->rms_jerk);
    limits += f->joint_limit_violated ? 1 : 0;
    nonfinite += f->nonfinite_steps > 0 ? 1 : 0;
    if (f->position_limit_steps >= 0) {
      g.limit_steps.counted_steps += f->steps;
      g.limit_steps.position += f->position_limit_steps;
    }
    if (f->velocity_limit_steps >= 0) {
      g.limit_steps.velocity_counted_steps += f->steps;
      g.limit_steps.velocity += f->velocity_limit_steps;
    }
    p50s.push_back(f->step_p50);
    p99s.push_back(f->step_p99);
  }
  g.success_rate = double(g.successes) / double(g.n);
  g.success_interval = wilson_interval(g.successes, g.n);
  g.median_min_distance = quantile(distances, 0.5);
  g.p10_min_distance = quantile(distances, 0.1);
  g.median_max_tracking_error = quantile(errors, 0.5);
  g.median_rms_jerk = quantile(jerks, 0.5);
  g.joint_limit_share = double(limits) / double(g.n);
  g.nonfinite_share = double(nonfinite) / double(g.n);
  g.step_us_p50 = quantile(p50s, 0.5);
  g.step_us_p99 = quantile(p99s, 0.5);
  return g;
}

int compare_distance(double a, double b) {
  if (a == b || std::abs(a - b) <= kDistanceTie || (std::isnan(a) && std::isnan(b))) return 0;
  if (std::isnan(b)) return 1;
  if (std::isnan(a)) return -1;
  return a > b ? 1 : -1;
}

void tally(WinLossTie& t, int outcome) {
  if (outcome > 0) ++t.wins;
  else if (outcome < 0) ++t.losses;
  else ++t.ties;
}


constexpr int kDifficultyBins = 4;

// Success against difficulty for every group of each (sweep, family): bins at
// the quartiles of the family's runs' measure, shared by its configurations.
void difficulty_bins(const std::map<GroupKey, std::vector<const RunFacts*>>& groups, std::vector<GroupStats>& stats) {
  std::map<std::pair<std::string, std::string>, std::vector<const RunFacts*>> families;
  for (const auto& [key, runs] : groups) {
    std::vector<const RunFacts*>& family = families[{std::get<0>(key), std::get<2>(key)}];
    family.insert(family.end(), runs.begin(), runs.end());
  }
  std::map<std::pair<std::string, std::string>, std::vector<GroupStats*>> family_groups;
  for (GroupStats& g : stats) family_groups[{g.sweep, g.family}].push_back(&g);
  for (const auto& [where, runs] : families) {
    const bool obstacles = std::any_of(runs.begin(), runs.end(), [](const RunFacts* f) { return std::isfinite(f->clearance); });
    const auto measure = [obstacles](const RunFacts* f) { return obstacles ? f->clearance : f->limit_margin; };
    std::vector<double> values;
    for (const RunFacts* f : runs)
      if (std::isfinite(measure(f))) values.push_back(measure(f));
    if (values.size() < size_t(2 * kDifficultyBins)) continue;
    std::vector<double> edges;
    for (int k = 0; k <= kDifficultyBins; ++k) edges.push_back(quantile(values, double(k) / kDifficultyBins));
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    if (edges.size() < 2) continue;
    for (GroupStats* group : family_groups[where]) {
      GroupStats& g = *group;
      g.difficulty_measure = obstacles ? "clearance" : "limit_margin";
      g.by_difficulty.clear();
      for (size_t k = 0; k + 1 < edges.size(); ++k) g.by_difficulty.push_back({edges[k], edges[k + 1], 0, 0});
      for (const RunFacts* f : groups.at({g.sweep, g.config_key, g.family})) {
        const double v = measure(f);
        if (!std::isfinite(v)) continue;
        // the bin whose upper edge is the first at or above v (the lowest edge belongs to the first bin)
        const size_t k = std::min(size_t(std::lower_bound(edges.begin() + 1, edges.end(), v) - (edges.begin() + 1)),
                                  g.by_difficulty.size() - 1);
        ++g.by_difficulty[k].n;
        g.by_difficulty[k].successes += f->entry->row.success ? 1 : 0;
      }
    }
  }
}

// Success against the obstacle counts, every configuration of a (sweep,
// family) binned alike (bins 0 .. kCountBins - 1, the last open); a measure
// is kept where the family's cases fill two bins or more. Memory: the groups'
// bins, whatever the runs.
void count_bins(const std::map<GroupKey, std::vector<const RunFacts*>>& groups, std::vector<GroupStats>& stats) {
  constexpr size_t kMeasures = kCountMeasures.size();
  std::map<std::pair<std::string, std::string>, std::array<std::array<bool, kCountBins>, kMeasures>> filled;
  for (GroupStats& g : stats) {
    std::array<CountDifficulty, kMeasures> counts;
    for (size_t m = 0; m < kMeasures; ++m) {
      counts[m].measure = kCountMeasures[m];
      for (size_t k = 0; k < kCountBins; ++k)
        counts[m].bins[k] = {double(k), k + 1 < kCountBins ? double(k) : kInf, 0, 0};
    }
    for (const RunFacts* f : groups.at({g.sweep, g.config_key, g.family}))
      for (size_t m = 0; m < kMeasures; ++m) {
        if (f->counts[m] < 0) continue;
        DifficultyBin& bin = counts[m].bins[std::min(size_t(f->counts[m]), kCountBins - 1)];
        ++bin.n;
        bin.successes += f->entry->row.success ? 1 : 0;
      }
    auto& family = filled[{g.sweep, g.family}];
    for (size_t m = 0; m < kMeasures; ++m)
      for (size_t k = 0; k < kCountBins; ++k) family[m][k] = family[m][k] || counts[m].bins[k].n > 0;
    g.by_count.assign(counts.begin(), counts.end());
  }
  for (GroupStats& g : stats) {
    const auto& family = filled.at({g.sweep, g.family});
    for (size_t m = kMeasures; m-- > 0;)  // by_count holds every measure here, in order
      if (std::count(family[m].begin(), family[m].end(), true) < 2) g.by_count.erase(g.by_count.begin() + long(m));
  }
}

constexpr const char* kPinv = "pinv";

// The group key's configuration is pinv with its defaults.
bool is_pinv(const std::string& config_key) { return config_key == kPinv || config_key == "pinv{}"; }

std::vector<double> step_p50s(const std::vector<const RunFacts*>& runs) {
  std::vector<double> out;
  for (const RunFacts* f : runs) out.push_back(f->step_p50);
  return out;
}


// Each group's step time against pinv's on the same sweep and family: one
// pass to find pinv's groups, one to divide (linear in the groups).
void step_ratios(const std::map<GroupKey, std::vector<const RunFacts*>>& groups, std::vector<GroupStats>& stats) {
  std::map<std::pair<std::string, std::string>, double> pinv_means;  // (sweep, family) -> pinv's mean
  for (const auto& [key, runs] : groups)
    if (is_pinv(std::get<1>(key)))
      pinv_means[{std::get<0>(key), std::get<2>(key)}] = shifted_geometric_mean(step_p50s(runs), kStepTimeShift);
  for (GroupStats& g : stats) {
    const auto pinv = pinv_means.find({g.sweep, g.family});
    if (pinv == pinv_means.end() || !(pinv->second > 0)) continue;
    g.step_ratio_to_pinv =
        shifted_geometric_mean(step_p50s(groups.at({g.sweep, g.config_key, g.family})), kStepTimeShift) / pinv->second;
  }
}

// A sweep's cases (scenario key and seed), each with its runs by configuration.
using CaseRuns = std::map<std::pair<std::string, std::uint64_t>, std::map<std::string, const RunFacts*>>;

// `cases`: the family's cases only (a case belongs to one family).
FamilyComparison compare_on_family(const CaseRuns& cases, const std::string& sweep, const std::string& family,
                                   const std::string& config, const std::string& reference, const char* role) {
  FamilyComparison c{sweep, family, config, reference, role, 0, {}, 1};
  for (const auto& [case_key, runs] : cases) {
    const auto a = runs.find(config), b = runs.find(reference);
    if (a == runs.end() || b == runs.end()) continue;
    ++c.cases;
    tally(c.success, int(a->second->entry->row.success) - int(b->second->entry->row.success));
  }
  c.mcnemar_p = mcnemar_exact_p(c.success.wins, c.success.losses);
  return c;
}

bool better(const GroupStats& x, const GroupStats& y) {
  if (x.success_rate != y.success_rate) return x.success_rate > y.success_rate;
  const double ex = std::isnan(x.median_max_tracking_error) ? kInf : x.median_max_tracking_error;
  const double ey = std::isnan(y.median_max_tracking_error) ? kInf : y.median_max_tracking_error;
  if (ex != ey) return ex < ey;
  return x.config_key < y.config_key;
}

// The family's fallback pair and unsolved cases (sweep_fallback.hpp), its
// configurations in the verdict's `order` (the witness lane apart).
FamilyFallback fallback_of(const CaseRuns& cases, const SweepReport& report, const std::string& sweep,
                           const std::string& family, const std::vector<size_t>& order) {
  FamilyOutcomes outcomes;
  std::map<std::string, size_t> column;
  for (size_t i : order) {
    column[report.groups[i].config_key] = outcomes.configs.size();
    outcomes.configs.push_back(report.groups[i].config_key);
    outcomes.step_us.push_back(report.groups[i].step_us_p50);
  }
  outcomes.cases.reserve(cases.size());
  for (const auto& [case_key, runs] : cases) {
    FamilyOutcomes::Case& one = outcomes.cases.emplace_back();
    one.scenario_key = case_key.first;
    one.seed = case_key.second;
    one.outcome.assign(outcomes.configs.size(), -1);
    for (const auto& [config, run] : runs) {
      const std::int8_t outcome = run->entry->row.success ? 1 : 0;
      if (config == kWitnessMethod) one.witness = outcome;
      else if (const auto at = column.find(config); at != column.end()) one.outcome[at->second] = outcome;
    }
  }
  FamilyFallback fallback = family_fallback(outcomes);
  fallback.sweep = sweep;
  fallback.family = family;
  return fallback;
}

// The verdict's power (FamilyVerdict): `basis` are the comparisons with the
// best it rests on, taken together at their fewest cases and largest
// discordance (one power search per family, however many configurations);
// none: the best alone, every case taken as discordant.
void state_power(FamilyVerdict& verdict, const std::vector<FamilyComparison>& basis) {
  size_t cases = verdict.cases;
  double psi = basis.empty() ? 1.0 : 0.0;
  for (const FamilyComparison& c : basis) {
    cases = std::min(cases, c.cases);
    psi = std::max(psi, wilson_interval(c.success.wins + c.success.losses, c.cases).high);
  }
  verdict.detectable = min_detectable_difference(cases, psi);
  verdict.discordance = psi;
}

// Per sweep and family: every configuration against pinv and against the
// best, and the configurations not significantly worse than the best
// (`cases`: (sweep, family) -> the family's cases). Two comparisons per
// configuration, each over the family's cases: linear in the runs.
void compare_within_families(std::map<std::pair<std::string, std::string>, CaseRuns>& cases, SweepReport& report) {
  static_assert(kSignificance == kPowerAlpha, "the power is the power of the report's test");
  std::map<std::pair<std::string, std::string>, std::vector<size_t>> families;  // (sweep, family) -> groups
  for (size_t i = 0; i < report.groups.size(); ++i)
    families[{report.groups[i].sweep, report.groups[i].family}].push_back(i);
  for (const auto& [where, members] : families) {
    const auto& [sweep, family] = where;
    std::vector<size_t> order = members;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t x, size_t y) { return better(report.groups[x], report.groups[y]); });
    // the witness lane is a reference (it solves every case by construction), never the best
    std::erase_if(order, [&](size_t i) { return report.groups[i].config_key == kWitnessMethod; });
    if (order.empty()) continue;
    const GroupStats& top = report.groups[order.front()];
    const std::string& best = top.config_key;
    std::string pinv;
    for (size_t i : members)
      if (is_pinv(report.groups[i].config_key)) pinv = report.groups[i].config_key;
    FamilyVerdict verdict{sweep, family, best, {}};
    verdict.cases = top.n;
    verdict.best_group = order.front();
    std::vector<size_t> listed;
    std::vector<FamilyComparison> no_difference, runner_up;
    for (size_t i : order) {
      const std::string& config = report.groups[i].config_key;
      if (!pinv.empty() && config != pinv)
        report.comparisons.push_back(compare_on_family(cases[where], sweep, family, config, pinv, "pinv"));
      if (config == best) {
        listed.push_back(i);
        continue;
      }
      const FamilyComparison against_best = compare_on_family(cases[where], sweep, family, config, best, "best");
      report.comparisons.push_back(against_best);
      if (runner_up.empty()) runner_up.push_back(against_best);
      const bool worse = against_best.success.losses > against_best.success.wins && against_best.mcnemar_p < kSignificance;
      if (worse) continue;
      no_difference.push_back(against_best);
      // never a configuration without a success beside one with
      if (report.groups[i].successes > 0) listed.push_back(i);
    }
    state_power(verdict, no_difference.empty() ? runner_up : no_difference);
    if (top.successes == 0) {
      verdict.status = VerdictStatus::kNoSuccess;
    } else if (!no_difference.empty() && !(verdict.detectable <= kSeparableDifference)) {
      verdict.status = VerdictStatus::kTooFewCases;
      verdict.cases_needed = cases_needed(kSeparableDifference, verdict.discordance);
    } else {
      verdict.contenders = std::move(listed);
    }
    report.verdicts.push_back(std::move(verdict));
    report.fallbacks.push_back(fallback_of(cases[where], report, sweep, family, order));
  }
}
}  // namespace

SweepReport build_report(const std::vector<storage::SweepRunEntry>& entries, const std::atomic<bool>* cancel) {
  std::vector<RunFacts> facts;
  facts.reserve(entries.size());
  for (const storage::SweepRunEntry& e : entries) {
    if (cancel && (facts.size() & 255) == 0 && cancel->load()) return {};
    facts.push_back(facts_of(e));
  }

  SweepReport report;
  std::map<GroupKey, std::vector<const RunFacts*>> groups;
  std::map<std::string, std::map<std::string, std::vector<const RunFacts*>>> by_config;  // sweep -> config -> runs
  std::map<std::string, CaseRuns> cases;                                   // sweep -> its cases
  std::map<std::pair<std::string, std::string>, CaseRuns> family_cases;   // (sweep, family) -> its cases
  for (const RunFacts& f : facts) {
    const storage::SweepRunRow& row = f.entry->row;
    const std::string family = report_family(row);
    groups[{row.sweep, row.config_key, family}].push_back(&f);
    by_config[row.sweep][row.config_key].push_back(&f);
    cases[row.sweep][{row.scenario_key, f.entry->seed}][row.config_key] = &f;
    family_cases[{row.sweep, family}][{row.scenario_key, f.entry->seed}][row.config_key] = &f;
  }
  for (const auto& [key, runs] : groups) report.groups.push_back(group_stats(runs));
  step_ratios(groups, report.groups);
  difficulty_bins(groups, report.groups);
  count_bins(groups, report.groups);

  for (const auto& [sweep, configs] : by_config) {
    report.sweeps.push_back(sweep);
    std::vector<RankEntry> ranking;
    for (const auto& [config, runs] : configs) {
      GroupStats all = group_stats(runs);
      ranking.push_back({sweep, config, all.n, all.success_rate, all.median_max_tracking_error});
    }
    std::stable_sort(ranking.begin(), ranking.end(), [](const RankEntry& x, const RankEntry& y) {
      if (x.success_rate != y.success_rate) return x.success_rate > y.success_rate;
      const double ex = std::isnan(x.median_max_tracking_error) ? kInf : x.median_max_tracking_error;
      const double ey = std::isnan(y.median_max_tracking_error) ? kInf : y.median_max_tracking_error;
      return ex < ey;
    });
    report.ranking.insert(report.ranking.end(), ranking.begin(), ranking.end());

    // every two configurations: quadratic, so only for a sweep of a few
    if (configs.size() > kMaxPairedConfigs) {
      report.pairs_omitted[sweep] = configs.size();
      continue;
    }
    for (auto a = configs.begin(); a != configs.end(); ++a) {
      for (auto b = std::next(a); b != configs.end(); ++b) {
        PairedComparison pair{sweep, a->first, b->first, 0, {}, {}};
        for (const auto& [case_key, runs] : cases[sweep]) {
          const auto ra = runs.find(a->first), rb = runs.find(b->first);
          if (ra == runs.end() || rb == runs.end()) continue;
          ++pair.cases;
          tally(pair.success, int(ra->second->entry->row.success) - int(rb->second->entry->row.success));
          tally(pair.min_distance, compare_distance(ra->second->min_distance, rb->second->min_distance));
        }
        report.pairs.push_back(pair);
      }
    }
  }
  compare_within_families(family_cases, report);
  return report;
}

std::string report_family(const storage::SweepRunRow& row) {
  return row.family == "file" ? row.scenario_key : row.family;
}

}  // namespace rrlab::sweep
