// The report's per-family statistics: failure modes, step time against pinv,
// paired comparisons with exact McNemar p-values and "which method when".
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include <rrlab/sweep/sweep_report.hpp>
#include <rrlab/sweep/sweep_report_html.hpp>
#include <rrlab/sweep/sweep_report_json.hpp>
#include <rrlab/sweep/sweep_report_text.hpp>
#include <rrlab/sweep/sweep_stats.hpp>

namespace rrlab::sweep {
namespace {

TEST(SweepStats, McNemarExactPValues) {
  EXPECT_DOUBLE_EQ(mcnemar_exact_p(0, 0), 1.0);
  EXPECT_NEAR(mcnemar_exact_p(0, 5), 2.0 / 32, 1e-12);         // 0.0625
  EXPECT_NEAR(mcnemar_exact_p(9, 1), 2.0 * 11 / 1024, 1e-12);  // 0.021484375
  EXPECT_NEAR(mcnemar_exact_p(3, 3), 1.0, 1e-12);
  EXPECT_NEAR(mcnemar_exact_p(400, 600), 3.0e-10, 0.3e-10);    // large n stays finite
}

TEST(SweepStats, ShiftedGeometricMean) {
  EXPECT_NEAR(shifted_geometric_mean({1, 3}, 1), std::sqrt(8.0) - 1, 1e-12);
  EXPECT_NEAR(shifted_geometric_mean({5, 5, 5}, 1), 5, 1e-12);
  EXPECT_TRUE(std::isnan(shifted_geometric_mean({}, 1)));
}

// 20 cases of one family: pinv passes 0-1, `a` all but 0, `b` 0-9, the
// witness all. pinv steps take 2 µs, a 8 µs, b 2 µs.
std::vector<storage::SweepRunEntry> family_runs() {
  std::vector<storage::SweepRunEntry> runs;
  std::int64_t id = 0;
  const auto add = [&](const std::string& config, int i, bool success, double step, const char* mode) {
    storage::SweepRunEntry e;
    const std::string scenario = "gen:fam:1:" + std::to_string(i);
    e.row = {"s", "s/" + scenario + "/" + config, scenario, config, "fam", success, std::nullopt, std::nullopt};
    if (!success) {
      e.row.failure_mode = mode;
      e.row.failure_t = 0.5 * i;
    }
    e.run_id = ++id;
    e.seed = 1;
    e.summary_json = nlohmann::json{{"max_tracking_error", 0.001}, {"step_us", {{"p50", step}, {"p99", step}}}}.dump();
    runs.push_back(e);
  };
  for (int i = 0; i < 20; ++i) {
    add("pinv", i, i <= 1, 2, i % 2 ? "collision" : "joint_limit");
    add("a", i, i != 0, 8, "stalled");
    add("b", i, i <= 9, 2, "tracking_lost");
    add("witness", i, true, 1, "");
  }
  return runs;
}

const GroupStats& group(const SweepReport& r, const std::string& config) {
  for (const GroupStats& g : r.groups)
    if (g.config_key == config) return g;
  throw std::runtime_error("no group " + config);
}

TEST(SweepReportFamilies, FailureModesAndStepTimeAgainstPinv) {
  const SweepReport r = build_report(family_runs());
  EXPECT_EQ(group(r, "pinv").failure_modes, (std::map<std::string, size_t>{{"collision", 9}, {"joint_limit", 9}}));
  EXPECT_EQ(group(r, "a").failure_modes, (std::map<std::string, size_t>{{"stalled", 1}}));
  EXPECT_TRUE(group(r, "witness").failure_modes.empty());
  EXPECT_NEAR(group(r, "a").step_ratio_to_pinv, 4.0, 1e-12);  // (8 + 1) / (2 + 1) shifted back: 8 / 2
  EXPECT_NEAR(group(r, "pinv").step_ratio_to_pinv, 1.0, 1e-12);
  EXPECT_EQ(failure_modes_text(group(r, "pinv")), "collision 9, joint_limit 9");
}

TEST(SweepReportFamilies, ComparisonsAndWhichMethodWhen) {
  const SweepReport r = build_report(family_runs());
  ASSERT_EQ(r.verdicts.size(), 1u);
  EXPECT_EQ(r.verdicts[0].best, "a");  // the witness lane is a reference, never the best
  ASSERT_EQ(r.verdicts[0].contenders.size(), 1u);
  EXPECT_EQ(r.groups[r.verdicts[0].contenders[0]].config_key, "a");
  const auto find = [&](const std::string& config, const std::string& role) {
    for (const FamilyComparison& c : r.comparisons)
      if (c.config_key == config && c.role == role) return c;
    throw std::runtime_error("no comparison " + config + " " + role);
  };
  const FamilyComparison b_best = find("b", "best");  // b wins case 0, loses 10-19
  EXPECT_EQ(b_best.cases, 20u);
  EXPECT_EQ(b_best.success.wins, 1u);
  EXPECT_EQ(b_best.success.losses, 10u);
  EXPECT_NEAR(b_best.mcnemar_p, 2.0 * 12 / 2048, 1e-12);
  const FamilyComparison a_pinv = find("a", "pinv");  // a wins 2-19, loses 0
  EXPECT_EQ(a_pinv.success.wins, 18u);
  EXPECT_EQ(a_pinv.success.losses, 1u);
  EXPECT_EQ(a_pinv.reference, "pinv");
  for (const FamilyComparison& c : r.comparisons) EXPECT_NE(c.config_key, "witness");

  std::ostringstream md;
  write_report_markdown(md, r);
  EXPECT_NE(md.str().find("### Which method when"), std::string::npos);
  // b is shown worse (p = 0.012): separated, though 20 cases detect only large differences
  EXPECT_NE(md.str().find("| fam | 20 | "), std::string::npos) << md.str();
  EXPECT_NE(md.str().find(" | a (95.0%, 8 µs, 4×) |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("| fam | b | best (a) | 20 | 1/10/9 | 0.0117 |"), std::string::npos) << md.str();
  const nlohmann::json json = report_json(r);
  EXPECT_EQ(json["verdicts"][0]["not_worse"], nlohmann::json::array({"a"}));
  EXPECT_EQ(json["groups"][0]["failure_modes"].is_object(), true);
}

// Two configurations whose difference the test cannot tell, on enough cases
// to detect a small one: both are named (tests/sweep/sweep_report_verdict_test.cpp: the rule).
TEST(SweepReportFamilies, AnInsignificantDifferenceKeepsBothContenders) {
  std::vector<storage::SweepRunEntry> runs;
  std::int64_t id = 0;
  for (int i = 0; i < 100; ++i)
    for (const char* config : {"x", "y"}) {
      storage::SweepRunEntry e;
      const std::string scenario = "gen:fam:1:" + std::to_string(i);
      const bool success = std::string(config) == "x" ? i < 80 : i < 78;
      e.row = {"s", "s/" + scenario + "/" + config, scenario, config, "fam", success, std::nullopt, std::nullopt};
      e.run_id = ++id;
      e.summary_json = R"({"max_tracking_error": 0.001})";
      runs.push_back(e);
    }
  const SweepReport r = build_report(runs);
  ASSERT_EQ(r.verdicts.size(), 1u);
  EXPECT_EQ(r.verdicts[0].best, "x");
  EXPECT_EQ(r.verdicts[0].contenders.size(), 2u);  // y loses 2, wins 0: p = 0.5
  EXPECT_LT(r.verdicts[0].detectable, kSeparableDifference);
  for (const GroupStats& g : r.groups) EXPECT_TRUE(std::isnan(g.step_ratio_to_pinv));  // no pinv
  EXPECT_EQ(r.groups[0].failure_modes.at("unrecorded"), 20u);
}

// Success against difficulty: 20 cases with clearances 0.01..0.20 m; "x"
// fails the 8 narrowest. Quartile bins, shared by every configuration, in the
// JSON report and drawn in the HTML one.
TEST(SweepReportFamilies, SuccessAgainstDifficultyInQuartileBins) {
  std::vector<storage::SweepRunEntry> runs;
  std::int64_t id = 0;
  for (int i = 0; i < 20; ++i)
    for (const char* config : {"x", "y"}) {
      storage::SweepRunEntry e;
      const std::string scenario = "gen:fam:1:" + std::to_string(i);
      const bool success = std::string(config) == "x" ? i >= 8 : true;
      e.row = {"s", "s/" + scenario + "/" + config, scenario, config, "fam", success, std::nullopt, std::nullopt};
      e.run_id = ++id;
      e.summary_json = R"({"max_tracking_error": 0.001})";
      e.difficulty_json = nlohmann::json{{"clearance", 0.01 * (i + 1)}, {"limit_margin", 0.5}}.dump();
      runs.push_back(e);
    }
  const SweepReport r = build_report(runs);
  const GroupStats& x = r.groups[0];
  ASSERT_EQ(x.config_key, "x");
  EXPECT_EQ(x.difficulty_measure, "clearance");  // obstacles: clearance, not the limit margin
  ASSERT_EQ(x.by_difficulty.size(), 4u);
  EXPECT_NEAR(x.by_difficulty[0].low, 0.01, 1e-12);
  EXPECT_NEAR(x.by_difficulty[3].high, 0.20, 1e-12);
  size_t n = 0;
  for (const DifficultyBin& b : x.by_difficulty) n += b.n;
  EXPECT_EQ(n, 20u);
  EXPECT_EQ(x.by_difficulty[0].successes, 0u);                       // the narrowest quarter all fail
  EXPECT_EQ(x.by_difficulty[3].successes, x.by_difficulty[3].n);     // the widest all pass
  EXPECT_EQ(r.groups[1].by_difficulty[0].low, x.by_difficulty[0].low);  // the same bins for y
  const nlohmann::json json = report_json(r);
  EXPECT_EQ(json["groups"][0]["difficulty"]["measure"], "clearance");
  EXPECT_EQ(json["groups"][0]["difficulty"]["bins"].size(), 4u);
  std::ostringstream html;
  write_report_html(html, r);
  EXPECT_NE(html.str().find("aria-label=\"success against clearance in fam\""), std::string::npos);
}

}  // namespace
}  // namespace rrlab::sweep
