#include "sweep/sweep_report_json.hpp"

#include <cmath>

namespace rrlab::sweep {

namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json tally(const WinLossTie& t) { return {{"wins", t.wins}, {"losses", t.losses}, {"ties", t.ties}}; }

}  // namespace

nlohmann::json report_json(const SweepReport& report) {
  nlohmann::json groups = nlohmann::json::array(), pairs = nlohmann::json::array(),
                 ranking = nlohmann::json::array();
  for (const GroupStats& g : report.groups) {
    nlohmann::json bins = nlohmann::json::array();
    for (const DifficultyBin& b : g.by_difficulty)
      bins.push_back({{"low", number(b.low)}, {"high", number(b.high)}, {"n", b.n}, {"successes", b.successes}});
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
                      {"step_us_p50", number(g.step_us_p50)},
                      {"step_us_p99", number(g.step_us_p99)},
                      {"step_ratio_to_pinv", number(g.step_ratio_to_pinv)},
                      {"failure_modes", g.failure_modes},
                      {"difficulty", {{"measure", g.difficulty_measure.empty() ? nlohmann::json() : nlohmann::json(g.difficulty_measure)},
                                      {"bins", bins}}}});
  }
  for (const PairedComparison& p : report.pairs)
    pairs.push_back({{"sweep", p.sweep},
                     {"a", p.a},
                     {"b", p.b},
                     {"cases", p.cases},
                     {"success", tally(p.success)},
                     {"min_distance", tally(p.min_distance)}});
  for (const RankEntry& r : report.ranking)
    ranking.push_back({{"sweep", r.sweep},
                       {"config", r.config_key},
                       {"n", r.n},
                       {"success_rate", number(r.success_rate)},
                       {"median_max_tracking_error", number(r.median_max_tracking_error)}});
  nlohmann::json comparisons = nlohmann::json::array(), verdicts = nlohmann::json::array();
  for (const FamilyComparison& c : report.comparisons)
    comparisons.push_back({{"sweep", c.sweep},
                           {"family", c.family},
                           {"config", c.config_key},
                           {"against", c.reference},
                           {"role", c.role},
                           {"cases", c.cases},
                           {"success", tally(c.success)},
                           {"mcnemar_p", number(c.mcnemar_p)}});
  for (const FamilyVerdict& v : report.verdicts) {
    nlohmann::json contenders = nlohmann::json::array();
    for (size_t i : v.contenders) contenders.push_back(report.groups[i].config_key);
    verdicts.push_back({{"sweep", v.sweep}, {"family", v.family}, {"best", v.best}, {"not_worse", contenders}});
  }
  return {{"sweeps", report.sweeps}, {"groups", groups},           {"pairs", pairs},
          {"ranking", ranking},      {"comparisons", comparisons}, {"verdicts", verdicts}};
}

}  // namespace rrlab::sweep
