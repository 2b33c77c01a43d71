#include <rrlab/sweep/sweep_report_json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include <rrlab/sweep/sweep_report_text.hpp>

namespace rrlab::sweep {

namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json tally(const WinLossTie& t) { return {{"wins", t.wins}, {"losses", t.losses}, {"ties", t.ties}}; }

// Each configuration's place in its sweep's ranking (0: the best).
using Ranks = std::map<std::pair<std::string, std::string>, size_t>;

Ranks ranks_of(const SweepReport& report) {
  Ranks ranks;
  std::map<std::string, size_t> next;
  for (const RankEntry& r : report.ranking) ranks[{r.sweep, r.config_key}] = next[r.sweep]++;
  return ranks;
}

// Which of `count` rows to show: all up to `max_rows`, else the best-ranked
// (`rank_of(i)`; ties in table order), in table order.
template <typename RankOf>
std::vector<size_t> rows_to_show(size_t count, size_t max_rows, RankOf rank_of) {
  std::vector<size_t> rows(count);
  std::iota(rows.begin(), rows.end(), size_t{0});
  if (count <= max_rows) return rows;
  std::stable_sort(rows.begin(), rows.end(), [&](size_t a, size_t b) { return rank_of(a) < rank_of(b); });
  rows.resize(max_rows);
  std::sort(rows.begin(), rows.end());
  return rows;
}

const char* status_name(VerdictStatus status) {
  switch (status) {
    case VerdictStatus::kTooFewCases: return "too_few_cases";
    case VerdictStatus::kNoSuccess: return "no_success";
    case VerdictStatus::kContenders: break;
  }
  return "contenders";
}

// Steps past limits after integration and the steps counted; null where no run counts.
nlohmann::json limit_steps_json(const LimitSteps& l) {
  if (l.counted_steps == 0) return nullptr;
  return {{"position", l.position},
          {"velocity", l.velocity_counted_steps ? nlohmann::json(l.velocity) : nlohmann::json(nullptr)},
          {"counted_steps", l.counted_steps},
          {"velocity_counted_steps", l.velocity_counted_steps}};
}

// Success by difficulty bin; an open last bin's high (+inf) is null.
template <typename Bins>
nlohmann::json bins_json(const Bins& bins) {
  nlohmann::json out = nlohmann::json::array();
  for (const DifficultyBin& b : bins)
    out.push_back({{"low", number(b.low)}, {"high", number(b.high)}, {"n", b.n}, {"successes", b.successes}});
  return out;
}

nlohmann::json name_or_null(const std::string& name) { return name.empty() ? nlohmann::json() : nlohmann::json(name); }

// One family's fallback row; its unsolved keys while `key_budget` lasts.
nlohmann::json fallback_json(const FamilyFallback& f, size_t& key_budget) {
  nlohmann::json keys = nlohmann::json::array();
  for (size_t k = 0; k < f.unsolved_listed.size() && key_budget > 0; ++k, --key_budget)
    keys.push_back({{"case", f.unsolved_listed[k].scenario_key}, {"seed", f.unsolved_listed[k].seed}});
  nlohmann::json commands = nlohmann::json::array();
  if (keys.size() == f.unsolved_listed.size())
    for (const std::string& command : unsolved_commands(f)) commands.push_back(command);
  return {{"sweep", f.sweep},
          {"family", f.family},
          {"cases", f.cases},
          {"solved_by_some", f.solved_by_some},
          {"first", name_or_null(f.first)},
          {"second", name_or_null(f.second)},
          {"pair_cases", f.pair_cases},
          {"first_solved", f.first_solved},
          {"pair_solved", f.pair_solved},
          {"cost_us", number(f.cost_us)},
          {"configs_considered", f.configs_considered},
          {"configs_total", f.configs_total},
          {"unsolved",
           {{"total", f.unsolved},
            {"witness_solves", f.witness_solves ? nlohmann::json(*f.witness_solves) : nlohmann::json()},
            {"listed", keys},
            {"generate", commands}}}};
}

}  // namespace

nlohmann::json report_json(const SweepReport& report, size_t max_rows) {
  const Ranks ranks = ranks_of(report);
  const auto rank = [&](const std::string& sweep, const std::string& config) {
    const auto it = ranks.find({sweep, config});
    return it == ranks.end() ? ranks.size() : it->second;
  };
  nlohmann::json truncated = nlohmann::json::object();
  const auto note_cut = [&](const char* table, size_t total, size_t shown) {
    if (shown < total) truncated[table] = {{"total", total}, {"shown", shown}};
  };
  nlohmann::json groups = nlohmann::json::array(), pairs = nlohmann::json::array(),
                 ranking = nlohmann::json::array();
  const std::vector<size_t> group_rows = rows_to_show(report.groups.size(), max_rows, [&](size_t i) {
    return rank(report.groups[i].sweep, report.groups[i].config_key);
  });
  note_cut("groups", report.groups.size(), group_rows.size());
  for (size_t row : group_rows) {
    const GroupStats& g = report.groups[row];
    nlohmann::json counts = nlohmann::json::object();
    for (const CountDifficulty& c : g.by_count) counts[c.measure] = bins_json(c.bins);
    groups.push_back({{"sweep", g.sweep},
                      {"config", g.config_key},
                      {"family", g.family},
                      {"n", g.n},
                      {"successes", g.successes},
                      {"success_rate", number(g.success_rate)},
                      {"success_interval", {number(g.success_interval.low), number(g.success_interval.high)}},
                      {"median_min_distance", number(g.median_min_distance)},
                      {"p10_min_distance", number(g.p10_min_distance)},
                      {"median_max_tracking_error", number(g.median_max_tracking_error)},
                      {"joint_limit_share", number(g.joint_limit_share)},
                      {"nonfinite_share", number(g.nonfinite_share)},
                      {"limit_steps", limit_steps_json(g.limit_steps)},
                      {"median_rms_jerk", number(g.median_rms_jerk)},
                      {"step_us_p50", number(g.step_us_p50)},
                      {"step_us_p99", number(g.step_us_p99)},
                      {"step_ratio_to_pinv", number(g.step_ratio_to_pinv)},
                      {"failure_modes", g.failure_modes},
                      {"difficulty", {{"measure", g.difficulty_measure.empty() ? nlohmann::json() : nlohmann::json(g.difficulty_measure)},
                                      {"bins", bins_json(g.by_difficulty)}}},
                      {"difficulty_counts", counts}});
  }
  const std::vector<size_t> pair_rows = rows_to_show(report.pairs.size(), max_rows, [&](size_t i) {
    return std::min(rank(report.pairs[i].sweep, report.pairs[i].a), rank(report.pairs[i].sweep, report.pairs[i].b));
  });
  note_cut("pairs", report.pairs.size(), pair_rows.size());
  for (size_t row : pair_rows) {
    const PairedComparison& p = report.pairs[row];
    pairs.push_back({{"sweep", p.sweep},
                     {"a", p.a},
                     {"b", p.b},
                     {"cases", p.cases},
                     {"success", tally(p.success)},
                     {"min_distance", tally(p.min_distance)}});
  }
  const std::vector<size_t> rank_rows = rows_to_show(report.ranking.size(), max_rows, [&](size_t i) {
    return rank(report.ranking[i].sweep, report.ranking[i].config_key);
  });
  note_cut("ranking", report.ranking.size(), rank_rows.size());
  for (size_t row : rank_rows) {
    const RankEntry& r = report.ranking[row];
    ranking.push_back({{"sweep", r.sweep},
                       {"config", r.config_key},
                       {"n", r.n},
                       {"success_rate", number(r.success_rate)},
                       {"median_max_tracking_error", number(r.median_max_tracking_error)}});
  }
  nlohmann::json comparisons = nlohmann::json::array(), verdicts = nlohmann::json::array();
  const std::vector<size_t> comparison_rows = rows_to_show(report.comparisons.size(), max_rows, [&](size_t i) {
    return rank(report.comparisons[i].sweep, report.comparisons[i].config_key);
  });
  note_cut("comparisons", report.comparisons.size(), comparison_rows.size());
  for (size_t row : comparison_rows) {
    const FamilyComparison& c = report.comparisons[row];
    comparisons.push_back({{"sweep", c.sweep},
                           {"family", c.family},
                           {"config", c.config_key},
                           {"against", c.reference},
                           {"role", c.role},
                           {"cases", c.cases},
                           {"success", tally(c.success)},
                           {"mcnemar_p", number(c.mcnemar_p)}});
  }
  for (const FamilyVerdict& v : report.verdicts) {
    nlohmann::json contenders = nlohmann::json::array();
    for (size_t k = 0; k < v.contenders.size() && k < kMaxVerdictNames; ++k)
      contenders.push_back(report.groups[v.contenders[k]].config_key);
    nlohmann::json verdict = {{"sweep", v.sweep},
                              {"family", v.family},
                              {"best", v.best},
                              {"status", status_name(v.status)},
                              {"not_worse", contenders},
                              {"cases", v.cases},
                              {"detectable_difference", number(v.detectable)},
                              {"discordance", number(v.discordance)}};
    if (v.contenders.size() > kMaxVerdictNames) verdict["not_worse_total"] = v.contenders.size();
    if (v.status == VerdictStatus::kTooFewCases) {
      verdict["cases_needed"] = v.cases_needed;
      verdict["separable_difference"] = kSeparableDifference;  // the difference cases_needed is for
    }
    verdicts.push_back(std::move(verdict));
  }
  nlohmann::json fallbacks = nlohmann::json::array();
  const std::vector<size_t> fallback_rows = rows_to_show(report.fallbacks.size(), max_rows, [](size_t) { return 0; });
  note_cut("fallbacks", report.fallbacks.size(), fallback_rows.size());
  size_t key_budget = kMaxUnsolvedKeys, keys_listed = 0;
  for (size_t row : fallback_rows) {
    fallbacks.push_back(fallback_json(report.fallbacks[row], key_budget));
    keys_listed += report.fallbacks[row].unsolved_listed.size();
  }
  note_cut("unsolved_keys", keys_listed, std::min(keys_listed, kMaxUnsolvedKeys));
  nlohmann::json out = {{"sweeps", report.sweeps},
                        {"groups", groups},
                        {"pairs", pairs},
                        {"ranking", ranking},
                        {"comparisons", comparisons},
                        {"verdicts", verdicts},
                        {"fallbacks", fallbacks},
                        {"rules", {{"verdicts", verdict_rule_text()}, {"fallbacks", fallback_rule_text()}}}};
  nlohmann::json omitted = nlohmann::json::object();
  for (const auto& [sweep, configs] : report.pairs_omitted) omitted[sweep] = configs;
  if (!omitted.empty()) out["pairs_omitted"] = {{"configurations", omitted}, {"max_paired", kMaxPairedConfigs}};
  if (!truncated.empty()) {
    truncated["max_rows"] = max_rows;
    truncated["note"] = "rows of the best-ranked configurations are shown; every run is in GET /api/sweeps/{id}/runs";
    out["truncated"] = std::move(truncated);
  }
  return out;
}

}  // namespace rrlab::sweep
