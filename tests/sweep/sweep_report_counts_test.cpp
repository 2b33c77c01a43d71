// Success against the obstacle counts of witness.difficulty (blocking and
// tight obstacles) in integer bins 0, 1, 2, 3, 4+, from synthetic runs: the
// bins, a count left out where every case falls in one bin, counts that are
// not non-negative integers ignored, and the JSON, Markdown and HTML reports.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include <rrlab/sweep/sweep_report.hpp>
#include <rrlab/sweep/sweep_report_html.hpp>
#include <rrlab/sweep/sweep_report_json.hpp>
#include <rrlab/sweep/sweep_report_text.hpp>

namespace rrlab::sweep {
namespace {

// Family "fam", 12 cases: blocking_obstacles i % 6 (case 11: a million),
// tight_obstacles 1 on every case; "x" succeeds below 2 blocking obstacles,
// "y" always. Family "bare": no counts, or counts that are not counts.
std::vector<storage::SweepRunEntry> count_runs() {
  std::vector<storage::SweepRunEntry> runs;
  std::int64_t id = 0;
  const auto add = [&](const std::string& family, int i, const std::string& config, bool success, nlohmann::json difficulty) {
    storage::SweepRunEntry e;
    const std::string scenario = "gen:" + family + ":1:" + std::to_string(i);
    e.row = {"s", "s/" + scenario + "/" + config, scenario, config, family, success, std::nullopt, std::nullopt};
    e.run_id = ++id;
    e.seed = 1;
    e.summary_json = R"({"max_tracking_error": 0.001})";
    e.difficulty_json = difficulty.dump();
    runs.push_back(e);
  };
  for (int i = 0; i < 12; ++i) {
    const nlohmann::json d = {{"clearance", 0.01 * (i + 1)}, {"blocking_obstacles", i == 11 ? 1000000 : i % 6}, {"tight_obstacles", 1}};
    add("fam", i, "x", i % 6 < 2, d);
    add("fam", i, "y", true, d);
  }
  const nlohmann::json not_counts[] = {{{"clearance", 0.1}},
                                       {{"blocking_obstacles", -1}},
                                       {{"blocking_obstacles", 1.5}},
                                       {{"blocking_obstacles", "2"}, {"tight_obstacles", nullptr}}};
  for (int i = 0; i < 4; ++i) add("bare", i, "x", true, not_counts[i]);
  return runs;
}

const GroupStats& group_of(const SweepReport& r, const std::string& config, const std::string& family) {
  for (const GroupStats& g : r.groups)
    if (g.config_key == config && g.family == family) return g;
  throw std::runtime_error("no group " + config + " · " + family);
}

TEST(SweepReportCounts, BinsZeroToFourOrMorePerConfiguration) {
  const SweepReport r = build_report(count_runs());
  const GroupStats& x = group_of(r, "x", "fam");
  ASSERT_EQ(x.by_count.size(), 1u);  // tight_obstacles: every case in one bin, left out
  const CountDifficulty& blocking = x.by_count[0];
  EXPECT_EQ(blocking.measure, "blocking_obstacles");
  const size_t n[kCountBins] = {2, 2, 2, 2, 4}, successes[kCountBins] = {2, 2, 0, 0, 0};
  for (size_t k = 0; k < kCountBins; ++k) {
    EXPECT_EQ(blocking.bins[k].n, n[k]) << k;
    EXPECT_EQ(blocking.bins[k].successes, successes[k]) << k;
    EXPECT_EQ(blocking.bins[k].low, double(k));
  }
  EXPECT_EQ(blocking.bins[3].high, 3.0);
  EXPECT_TRUE(std::isinf(blocking.bins[4].high));  // 4, 5 and a million obstacles: one bin, whatever the count
  const GroupStats& y = group_of(r, "y", "fam");
  ASSERT_EQ(y.by_count.size(), 1u);  // the same measures for every configuration of the family
  EXPECT_EQ(y.by_count[0].bins[4].successes, 4u);
  EXPECT_TRUE(group_of(r, "x", "bare").by_count.empty());  // no counts, or counts that are not non-negative integers
}

TEST(SweepReportCounts, EveryFormatShowsThem) {
  const SweepReport r = build_report(count_runs());
  const nlohmann::json json = report_json(r);
  for (const nlohmann::json& g : json["groups"]) {
    if (g["family"] == "bare") {
      EXPECT_TRUE(g["difficulty_counts"].empty());
      continue;
    }
    ASSERT_TRUE(g["difficulty_counts"].contains("blocking_obstacles")) << g.dump();
    EXPECT_FALSE(g["difficulty_counts"].contains("tight_obstacles"));
    const nlohmann::json& bins = g["difficulty_counts"]["blocking_obstacles"];
    ASSERT_EQ(bins.size(), kCountBins);
    EXPECT_EQ(bins[0], (nlohmann::json{{"low", 0.0}, {"high", 0.0}, {"n", 2}, {"successes", 2}}));
    EXPECT_EQ(bins[4]["low"], 4.0);
    EXPECT_TRUE(bins[4]["high"].is_null());  // open: 4 or more
  }
  std::ostringstream md;
  write_report_markdown(md, r);
  EXPECT_NE(md.str().find("### Success against obstacle counts"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("| family | count | method config | 0 | 1 | 2 | 3 | 4+ |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("| fam | blocking_obstacles | x | 2/2 | 2/2 | 0/2 | 0/2 | 0/4 |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("| fam | blocking_obstacles | y | 2/2 | 2/2 | 2/2 | 2/2 | 4/4 |"), std::string::npos) << md.str();
  EXPECT_EQ(md.str().find("tight_obstacles |"), std::string::npos);
  std::ostringstream html;
  write_report_html(html, r);
  EXPECT_NE(html.str().find("<h3>Success against obstacle counts</h3>"), std::string::npos);
  EXPECT_NE(html.str().find("aria-label=\"success against blocking_obstacles in fam\""), std::string::npos);
  EXPECT_NE(html.str().find(">4+</text>"), std::string::npos);
  EXPECT_NE(html.str().find("aria-label=\"success against clearance in fam\""), std::string::npos);  // the quartiles' chart stays
}

TEST(SweepReportCounts, BinLabels) {
  EXPECT_EQ(count_bin_label({0, 0, 0, 0}), "0");
  EXPECT_EQ(count_bin_label({4, std::numeric_limits<double>::infinity(), 0, 0}), "4+");
  EXPECT_EQ(count_bin_label({2, 3, 0, 0}), "2–3");
}

}  // namespace
}  // namespace rrlab::sweep
