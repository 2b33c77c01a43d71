// "Which method when" with stated power: contenders only where the cases can
// separate the methods, never a configuration without a success beside one
// with, on small and large samples, in every format.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include <rrlab/sweep/sweep_report.hpp>
#include <rrlab/sweep/sweep_report_html.hpp>
#include <rrlab/sweep/sweep_report_json.hpp>
#include <rrlab/sweep/sweep_report_text.hpp>

namespace rrlab::sweep {
namespace {

// `cases` cases of family "fam"; each configuration succeeds where its
// predicate says; pinv steps take 1 µs, the others 3.
template <typename Succeeds>
std::vector<storage::SweepRunEntry> runs_of(int cases, const std::vector<std::string>& configs, Succeeds succeeds) {
  std::vector<storage::SweepRunEntry> runs;
  std::int64_t id = 0;
  for (int i = 0; i < cases; ++i)
    for (const std::string& config : configs) {
      storage::SweepRunEntry e;
      const std::string scenario = "gen:fam:1:" + std::to_string(i);
      const bool success = succeeds(config, i);
      e.row = {"s", "s/" + scenario + "/" + config, scenario, config, "fam", success,
               success ? std::nullopt : std::optional<std::string>("collision"), std::nullopt};
      e.run_id = ++id;
      e.seed = 1;
      const double step = config == "pinv" ? 1 : 3;
      e.summary_json = nlohmann::json{{"max_tracking_error", 0.001}, {"step_us", {{"p50", step}, {"p99", step}}}}.dump();
      runs.push_back(e);
    }
  return runs;
}

std::vector<std::string> listed(const SweepReport& r, const FamilyVerdict& v) {
  std::vector<std::string> names;
  for (size_t i : v.contenders) names.push_back(r.groups[i].config_key);
  return names;
}

// The family's row of "which method when" in a Markdown report.
std::string markdown_verdict_row(const SweepReport& r) {
  std::ostringstream md;
  write_report_markdown(md, r);
  const std::string text = md.str();
  const size_t section = text.find("### Which method when");
  const size_t row = text.find("\n| fam |", section);
  EXPECT_NE(row, std::string::npos) << text;
  return text.substr(row + 1, text.find('\n', row + 1) - row - 1);
}

// The must-pass case: on 3 cases pinv fails every one and closest_point passes
// every one. 3 cases cannot separate anything (p >= 0.25), and pinv, without
// a success, is never named as a contender (nor a cheap pick) anywhere.
TEST(SweepReportVerdict, ThreeCasesNeverRecommendPinv) {
  const SweepReport r = build_report(runs_of(3, {"pinv", "closest_point", "witness"}, [](const std::string& c, int) {
    return c != "pinv";
  }));
  ASSERT_EQ(r.verdicts.size(), 1u);
  const FamilyVerdict& v = r.verdicts[0];
  EXPECT_EQ(v.best, "closest_point");
  EXPECT_EQ(v.status, VerdictStatus::kTooFewCases);
  EXPECT_TRUE(v.contenders.empty());
  EXPECT_TRUE(std::isinf(v.detectable));
  EXPECT_GT(v.cases_needed, 150u);  // every case was discordant: the worst case

  const std::string row = markdown_verdict_row(r);
  EXPECT_EQ(row.find("pinv"), std::string::npos) << row;
  EXPECT_NE(row.find("too few cases to separate the methods"), std::string::npos) << row;
  EXPECT_NE(row.find("not separated from the others: closest_point (100.0%)"), std::string::npos) << row;

  std::ostringstream html;
  write_report_html(html, r);
  const std::string page = html.str();
  const size_t from = page.find("<h3>Which method when</h3>"), to = page.find("</table>", from);
  EXPECT_EQ(page.substr(from, to - from).find("<td>pinv"), std::string::npos);
  EXPECT_NE(page.substr(from, to - from).find("too few cases"), std::string::npos);

  const nlohmann::json json = report_json(r)["verdicts"][0];
  EXPECT_EQ(json["status"], "too_few_cases");
  EXPECT_EQ(json["best"], "closest_point");
  EXPECT_EQ(json["not_worse"], nlohmann::json::array());
  EXPECT_TRUE(json["detectable_difference"].is_null());
  EXPECT_EQ(json["cases_needed"], v.cases_needed);

  // nor is pinv a fallback: it solves nothing closest_point fails
  ASSERT_EQ(r.fallbacks.size(), 1u);
  EXPECT_EQ(r.fallbacks[0].first, "closest_point");
  EXPECT_EQ(r.fallbacks[0].second, "");
}

// 10 cases, 8 against 6: not significant, and 10 cases detect only large
// differences, so nothing is listed.
TEST(SweepReportVerdict, TenCasesAreTooFewToSeparateTwoMethods) {
  const SweepReport r = build_report(runs_of(10, {"x", "y"}, [](const std::string& c, int i) {
    return c == "x" ? i < 8 : i < 6;
  }));
  const FamilyVerdict& v = r.verdicts[0];
  EXPECT_EQ(v.status, VerdictStatus::kTooFewCases);
  EXPECT_GT(v.detectable, kSeparableDifference);
  EXPECT_GT(v.cases_needed, 10u);
  EXPECT_TRUE(v.contenders.empty());
}

// 200 cases where x and y differ on 4 (3 : 1): not significant, and these
// cases detect a few points: both are listed.
TEST(SweepReportVerdict, ManyCasesListTheContenders) {
  const SweepReport r = build_report(runs_of(200, {"x", "y", "pinv"}, [](const std::string& c, int i) {
    if (c == "pinv") return false;
    return c == "x" ? i >= 10 && i != 13 : i >= 13;
  }));
  const FamilyVerdict& v = r.verdicts[0];
  EXPECT_EQ(v.status, VerdictStatus::kContenders);
  EXPECT_EQ(listed(r, v), (std::vector<std::string>{"x", "y"}));
  EXPECT_LT(v.detectable, 0.06);
  EXPECT_NEAR(v.discordance, wilson_interval(4, 200).high, 1e-12);
  EXPECT_NE(markdown_verdict_row(r).find("| fam | 200 | "), std::string::npos);
  const nlohmann::json json = report_json(r)["verdicts"][0];
  EXPECT_EQ(json["status"], "contenders");
  EXPECT_EQ(json["not_worse"], nlohmann::json::array({"x", "y"}));
  EXPECT_FALSE(json.contains("cases_needed"));
}

// However many cases: one success against none is no significant difference,
// yet the configuration without a success is not listed beside it.
TEST(SweepReportVerdict, NoSuccessIsNeverBesideASuccessWhateverTheSample) {
  for (int cases : {3, 400}) {
    const SweepReport r = build_report(runs_of(cases, {"a", "b"}, [](const std::string& c, int i) {
      return c == "a" && i == 0;
    }));
    const FamilyVerdict& v = r.verdicts[0];
    EXPECT_EQ(v.best, "a");
    for (const std::string& name : listed(r, v)) EXPECT_NE(name, "b") << cases;
    EXPECT_EQ(markdown_verdict_row(r).find(" b "), std::string::npos) << cases;
  }
  // 400 cases with 1 discordant detect about 2 points: separated, a alone
  const SweepReport large = build_report(runs_of(400, {"a", "b"}, [](const std::string& c, int i) {
    return c == "a" && i == 0;
  }));
  EXPECT_EQ(large.verdicts[0].status, VerdictStatus::kContenders);
  EXPECT_EQ(listed(large, large.verdicts[0]), std::vector<std::string>{"a"});
}

// Shown worse by the test: separated, whatever the power against the runner-up.
TEST(SweepReportVerdict, ASignificantDifferenceSeparatesOnFewCases) {
  const SweepReport r = build_report(runs_of(20, {"a", "b"}, [](const std::string& c, int i) {
    return c == "a" ? i != 0 : false;
  }));
  const FamilyVerdict& v = r.verdicts[0];
  EXPECT_EQ(v.status, VerdictStatus::kContenders);
  EXPECT_GT(v.detectable, kSeparableDifference);  // 19 of 20 discordant: only large differences show
  EXPECT_EQ(listed(r, v), std::vector<std::string>{"a"});
}

TEST(SweepReportVerdict, NoConfigurationSucceeded) {
  const SweepReport r = build_report(runs_of(30, {"a", "b"}, [](const std::string&, int) { return false; }));
  EXPECT_EQ(r.verdicts[0].status, VerdictStatus::kNoSuccess);
  EXPECT_TRUE(r.verdicts[0].contenders.empty());
  EXPECT_NE(markdown_verdict_row(r).find("no configuration succeeded"), std::string::npos);
  EXPECT_EQ(report_json(r)["verdicts"][0]["status"], "no_success");
}

TEST(SweepReportVerdict, EveryFormatStatesTheRule) {
  const SweepReport r = build_report(runs_of(3, {"a"}, [](const std::string&, int) { return true; }));
  std::ostringstream md, html;
  write_report_markdown(md, r);
  write_report_html(html, r);
  const nlohmann::json json = report_json(r);
  for (const std::string& text : {md.str(), html.str(), json["rules"]["verdicts"].get<std::string>()}) {
    EXPECT_NE(text.find("80 % power"), std::string::npos);
    EXPECT_NE(text.find("too few cases to separate the methods"), std::string::npos);
    EXPECT_NE(text.find("never listed beside one with"), std::string::npos);
  }
}

}  // namespace
}  // namespace rrlab::sweep
