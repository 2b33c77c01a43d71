// Report numbers against a small case computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include <rrlab/sweep/sweep_report.hpp>
#include <rrlab/sweep/sweep_report_html.hpp>
#include <rrlab/sweep/sweep_report_json.hpp>
#include <rrlab/sweep/sweep_report_text.hpp>
#include <rrlab/sweep/sweep_stats.hpp>

namespace rrlab::sweep {
namespace {

TEST(SweepStats, WilsonIntervalOfSevenInTen) {
  const Interval i = wilson_interval(7, 10);
  EXPECT_NEAR(i.low, 0.3968, 1e-4);
  EXPECT_NEAR(i.high, 0.8922, 1e-4);
  const Interval none = wilson_interval(0, 0);
  EXPECT_EQ(none.low, 0);
  EXPECT_EQ(none.high, 1);
  const Interval all = wilson_interval(10, 10);
  EXPECT_NEAR(all.low, 0.7225, 1e-4);
  EXPECT_NEAR(all.high, 1, 1e-12);
}

TEST(SweepStats, QuantilesInterpolateBetweenOrderStatistics) {
  EXPECT_DOUBLE_EQ(quantile({3, 1, 2}, 0.5), 2);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 0.1), 1.9);  // h = 0.9
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

// Configuration a: 10 cases, successes on cases 0..6, min distance
// (i + 1) / 10 shuffled, max tracking error (i + 1) / 100, joint limits
// violated on 2 runs, non-finite steps on 1, RMS jerk 2 (i + 1), step_us.p50 = i + 1,
// 100 steps of which i past a position limit and (i even) 1 past a velocity limit.
// Configuration b on the same cases: successes on 3..7, min distance a's
// + 0.1 on 0..3, a's + 1e-12 on 4..6, a's − 0.1 on 7..9, no RMS jerk (runs too
// short), no limit-step counts (summaries older than them).
std::vector<storage::SweepRunEntry> hand_case() {
  const double distance[10] = {0.5, 0.1, 0.9, 0.3, 0.7, 0.2, 0.8, 0.4, 1.0, 0.6};
  std::vector<storage::SweepRunEntry> runs;
  for (int i = 0; i < 10; ++i) {
    const std::string scenario = "file:s" + std::to_string(i);
    nlohmann::json a = {{"min_distance", distance[i]},
                        {"max_tracking_error", (i + 1) / 100.0},
                        {"joint_limit_violated", i < 2},
                        {"nonfinite_steps", i == 9 ? 3 : 0},
                        {"rms_jerk", 2.0 * (i + 1)},
                        {"steps", 100},
                        {"position_limit_steps", i},
                        {"velocity_limit_steps", i % 2 == 0 ? 1 : 0},
                        {"step_us", {{"mean", 1}, {"p50", i + 1}, {"p99", 10 * (i + 1)}}}};
    const double db = i <= 3 ? distance[i] + 0.1 : i <= 6 ? distance[i] + 1e-12 : distance[i] - 0.1;
    nlohmann::json b = a;
    b["min_distance"] = db;
    b["max_tracking_error"] = 0.5;
    b["rms_jerk"] = nullptr;
    b.erase("position_limit_steps");
    b.erase("velocity_limit_steps");
    runs.push_back({{"w", "w/" + scenario + "/a/own", scenario, "a", "hand", i <= 6}, 2 * i + 1, 1, a.dump()});
    runs.push_back({{"w", "w/" + scenario + "/b/own", scenario, "b", "hand", i >= 3 && i <= 7}, 2 * i + 2, 1, b.dump()});
  }
  return runs;
}

TEST(SweepReport, GroupNumbers) {
  const SweepReport report = build_report(hand_case());
  ASSERT_EQ(report.groups.size(), 2u);
  const GroupStats& a = report.groups[0];
  EXPECT_EQ(a.config_key, "a");
  EXPECT_EQ(a.family, "hand");
  EXPECT_EQ(a.n, 10u);
  EXPECT_EQ(a.successes, 7u);
  EXPECT_DOUBLE_EQ(a.success_rate, 0.7);
  EXPECT_NEAR(a.success_interval.low, 0.3968, 1e-4);
  EXPECT_NEAR(a.success_interval.high, 0.8922, 1e-4);
  EXPECT_NEAR(a.median_min_distance, 0.55, 1e-12);
  EXPECT_NEAR(a.p10_min_distance, 0.19, 1e-12);
  EXPECT_NEAR(a.median_max_tracking_error, 0.055, 1e-12);
  EXPECT_DOUBLE_EQ(a.joint_limit_share, 0.2);
  EXPECT_DOUBLE_EQ(a.nonfinite_share, 0.1);
  EXPECT_DOUBLE_EQ(a.step_us_p50, 5.5);
  EXPECT_DOUBLE_EQ(a.step_us_p99, 55);
  EXPECT_DOUBLE_EQ(a.median_rms_jerk, 11);
  EXPECT_EQ(a.limit_steps.counted_steps, 1000);
  EXPECT_EQ(a.limit_steps.position, 45);
  EXPECT_EQ(a.limit_steps.velocity_counted_steps, 1000);
  EXPECT_EQ(a.limit_steps.velocity, 5);
  EXPECT_EQ(report.groups[1].limit_steps.counted_steps, 0);
  EXPECT_EQ(report.groups[1].successes, 5u);
  EXPECT_TRUE(std::isnan(report.groups[1].median_rms_jerk));
}

TEST(SweepReport, PairedComparisonsAndRanking) {
  const SweepReport report = build_report(hand_case());
  ASSERT_EQ(report.pairs.size(), 1u);
  const PairedComparison& p = report.pairs[0];
  EXPECT_EQ(p.a, "a");
  EXPECT_EQ(p.b, "b");
  EXPECT_EQ(p.cases, 10u);
  EXPECT_EQ(p.success.wins, 3u);  // cases 0, 1, 2
  EXPECT_EQ(p.success.losses, 1u);  // case 7
  EXPECT_EQ(p.success.ties, 6u);
  EXPECT_EQ(p.min_distance.wins, 3u);  // 7, 8, 9
  EXPECT_EQ(p.min_distance.losses, 4u);  // 0..3
  EXPECT_EQ(p.min_distance.ties, 3u);  // within 1e-9
  ASSERT_EQ(report.ranking.size(), 2u);
  EXPECT_EQ(report.ranking[0].config_key, "a");
  EXPECT_EQ(report.ranking[1].config_key, "b");
}

TEST(SweepReport, RankingBreaksTiesOnTrackingError) {
  std::vector<storage::SweepRunEntry> runs;
  runs.push_back({{"w", "k1", "file:s", "a", "file", true}, 1, 1, R"({"max_tracking_error": 0.2})"});
  runs.push_back({{"w", "k2", "file:s", "b", "file", true}, 2, 1, R"({"max_tracking_error": 0.1})"});
  const SweepReport report = build_report(runs);
  EXPECT_EQ(report.ranking[0].config_key, "b");
}

TEST(SweepReport, ScenarioFilesAreReportedEachOnItsOwn) {
  std::vector<storage::SweepRunEntry> runs;
  runs.push_back({{"w", "k1", "file:s1", "a", "file", true}, 1, 1, R"({"max_tracking_error": 0.2})"});
  runs.push_back({{"w", "k2", "file:s2", "a", "file", false}, 2, 1, R"({"max_tracking_error": 0.1})"});
  runs.push_back({{"w", "k3", "gen:planar_limits:1:0", "a", "planar_limits", true}, 3, 1, R"({})"});
  runs.push_back({{"w", "k4", "gen:planar_limits:1:1", "a", "planar_limits", true}, 4, 1, R"({})"});
  const SweepReport report = build_report(runs);
  ASSERT_EQ(report.groups.size(), 3u);
  EXPECT_EQ(report.groups[0].family, "file:s1");
  EXPECT_EQ(report.groups[0].successes, 1u);
  EXPECT_EQ(report.groups[1].family, "file:s2");
  EXPECT_EQ(report.groups[1].successes, 0u);
  EXPECT_EQ(report.groups[2].family, "planar_limits");
  EXPECT_EQ(report.groups[2].n, 2u);
}

TEST(SweepReport, FormatsCarryTheNumbers) {
  const SweepReport report = build_report(hand_case());
  std::ostringstream md, csv, html;
  write_report_markdown(md, report);
  write_report_csv(csv, report);
  write_report_html(html, report);
  EXPECT_NE(md.str().find("| a | hand | 10 | 70.0% | 39.7%–89.2% | 0.55 | 0.19 | 0.055 | 20.0% | 45 / 5 | 10.0% | 11 | 5.5 | 55 |"),
            std::string::npos)
      << md.str();
  EXPECT_NE(md.str().find("| a | b | 10 | 3/1/6 | 3/4/3 |"), std::string::npos) << md.str();
  EXPECT_NE(csv.str().find("w,a,hand,10,7,0.7,0.396"), std::string::npos) << csv.str();
  EXPECT_NE(csv.str().find(",0.2,45,5,1000,0.1,11,5.5,55,"), std::string::npos) << csv.str();
  EXPECT_NE(csv.str().find(",0.2,,,,0.1,"), std::string::npos) << csv.str();  // b: no counts
  EXPECT_NE(md.str().find("| — | 10.0% | — | 5.5 |"), std::string::npos) << md.str();  // b: no counts, no jerk
  EXPECT_NE(html.str().find("<th>jerk RMS median</th>"), std::string::npos);
  const nlohmann::json json = report_json(report);
  EXPECT_EQ(json["groups"][0]["median_rms_jerk"], 11.0);
  EXPECT_TRUE(json["groups"][1]["median_rms_jerk"].is_null());
  EXPECT_EQ(json["groups"][0]["limit_steps"]["position"], 45);
  EXPECT_EQ(json["groups"][0]["limit_steps"]["velocity"], 5);
  EXPECT_TRUE(json["groups"][1]["limit_steps"].is_null());
  EXPECT_NE(html.str().find("<th>steps past limits q / q̇</th>"), std::string::npos);
  const std::string page = html.str();
  EXPECT_NE(page.find("<svg"), std::string::npos);
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(page.find("src="), std::string::npos);
  EXPECT_EQ(page.find("href="), std::string::npos);
}

}  // namespace
}  // namespace rrlab::sweep
