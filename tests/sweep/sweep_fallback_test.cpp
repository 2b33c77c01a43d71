// What to try when the first choice fails: the pair chosen by its rule, the
// witness kept out, the unsolved cases listed (bounded) with the commands
// that write them, and the section in every report format.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include <rrlab/sweep/sweep_fallback.hpp>
#include <rrlab/sweep/sweep_report.hpp>
#include <rrlab/sweep/sweep_report_html.hpp>
#include <rrlab/sweep/sweep_report_json.hpp>
#include <rrlab/sweep/sweep_report_text.hpp>

namespace rrlab::sweep {
namespace {

// Outcomes from one string per configuration ('1' solved, '0' failed, '-' not
// run), a case per character; the witness lane's likewise (empty: none).
FamilyOutcomes outcomes(const std::vector<std::pair<std::string, std::string>>& configs, const std::vector<double>& step_us,
                        const std::string& witness = "", const std::string& family = "gen:fam:1:") {
  FamilyOutcomes o;
  for (const auto& [name, cases] : configs) o.configs.push_back(name);
  o.step_us = step_us;
  for (size_t c = 0; c < configs.front().second.size(); ++c) {
    FamilyOutcomes::Case& one = o.cases.emplace_back();
    one.scenario_key = family + std::to_string(c);
    one.seed = 7;
    for (const auto& [name, cases] : configs) one.outcome.push_back(cases[c] == '-' ? -1 : cases[c] == '1' ? 1 : 0);
    if (!witness.empty()) one.witness = witness[c] == '1' ? 1 : 0;
  }
  return o;
}

TEST(SweepFallback, ThePairThatSolvesMostThenTheCheapest) {
  // a solves 6 of 10, b 5 (3 where a fails), c the 4 a fails, d 2 of them
  const FamilyFallback f = family_fallback(outcomes({{"a", "1111110000"},
                                                     {"b", "1100001110"},
                                                     {"c", "0000001111"},
                                                     {"d", "0000000011"}},
                                                    {2, 1, 8, 1}));
  EXPECT_EQ(f.cases, 10u);
  EXPECT_EQ(f.solved_by_some, 10u);
  EXPECT_EQ(f.unsolved, 0u);
  // a|c solves all 10, and so does nothing else: c first (cost 8 + 2 * 0.6) or a first (2 + 8 * 0.4 = 5.2)
  EXPECT_EQ(f.first, "a");
  EXPECT_EQ(f.second, "c");
  EXPECT_EQ(f.pair_cases, 10u);
  EXPECT_EQ(f.first_solved, 6u);
  EXPECT_EQ(f.pair_solved, 10u);
  EXPECT_NEAR(f.cost_us, 2 + 8 * 0.4, 1e-12);
}

TEST(SweepFallback, EqualSharesGoToTheLowerCost) {
  // b and c each add the same two cases to a; c's steps cost less
  const FamilyFallback f =
      family_fallback(outcomes({{"a", "111100"}, {"b", "000011"}, {"c", "000011"}}, {1, 5, 3}));
  EXPECT_EQ(f.first, "a");
  EXPECT_EQ(f.second, "c");
  EXPECT_NEAR(f.cost_us, 1 + 3 * 2.0 / 6, 1e-12);
}

TEST(SweepFallback, OneConfigurationWhenNoSecondAddsACase) {
  const FamilyFallback f = family_fallback(outcomes({{"a", "1110"}, {"pinv", "0000"}, {"b", "1100"}}, {3, 1, 2}));
  EXPECT_EQ(f.first, "a");
  EXPECT_EQ(f.second, "");
  EXPECT_EQ(f.pair_solved, 3u);
  EXPECT_NEAR(f.cost_us, 3, 1e-12);
}

TEST(SweepFallback, AFamilyNothingSolvesNamesNoFirstChoiceInText) {
  const FamilyFallback f = family_fallback(outcomes({{"dls", "000"}, {"pinv", "000"}}, {2, 1}));
  EXPECT_EQ(f.solved_by_some, 0u);
  EXPECT_EQ(fallback_choice_text(f), "none: no configuration solves any of the 3 cases");
}

TEST(SweepFallback, TheWitnessIsNoMethodItMarksTheFrontier) {
  // the witness is no configuration here: the caller leaves it out of `configs`
  const FamilyFallback f = family_fallback(outcomes({{"a", "1100"}, {"b", "1000"}}, {1, 1}, "1110"));
  EXPECT_EQ(f.solved_by_some, 2u);
  EXPECT_EQ(f.unsolved, 2u);
  ASSERT_TRUE(f.witness_solves);
  EXPECT_EQ(*f.witness_solves, 1u);  // case 2: solvable, solved by none (the frontier); case 3: by nothing
  ASSERT_EQ(f.unsolved_listed.size(), 2u);
  EXPECT_EQ(f.unsolved_listed[0].scenario_key, "gen:fam:1:2");
  EXPECT_FALSE(family_fallback(outcomes({{"a", "10"}}, {1})).witness_solves);  // no witness runs
}

TEST(SweepFallback, CasesNotRunCountOnlyWhereBothRan) {
  const FamilyFallback f = family_fallback(outcomes({{"a", "11-0"}, {"b", "0-11"}}, {1, 1}));
  EXPECT_EQ(f.cases, 4u);
  EXPECT_EQ(f.first, "a");
  EXPECT_EQ(f.second, "b");
  EXPECT_EQ(f.pair_cases, 2u);  // cases 0 and 3
  EXPECT_EQ(f.pair_solved, 2u);
}

TEST(SweepFallback, UnsolvedCasesAreListedInOrderAndBounded) {
  std::string a(120, '0');
  a[5] = '1';
  const FamilyFallback f = family_fallback(outcomes({{"a", a}}, {1}));
  EXPECT_EQ(f.unsolved, 119u);
  ASSERT_EQ(f.unsolved_listed.size(), kMaxUnsolvedListed);
  EXPECT_EQ(f.unsolved_listed[0].scenario_key, "gen:fam:1:0");
  EXPECT_EQ(f.unsolved_listed[5].scenario_key, "gen:fam:1:6");  // by index, not as text ("10" after "9")
  EXPECT_EQ(f.unsolved_listed[9].scenario_key, "gen:fam:1:10");
  const std::vector<std::string> commands = unsolved_commands(f);
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_EQ(commands[0].substr(0, 55), "rrlab generate fam --seed 1 --cases 0,1,2,3,4,6,7,8,9,1");
  EXPECT_NE(commands[0].find(",50 --out unsolved/fam-seed1"), std::string::npos) << commands[0];
}

// Each case's own run seed differs (a spec without "seeds"): keys alone. A case
// run under several seeds: each listing names its seed, the command it once.
TEST(SweepFallback, RunSeedsAreNamedOnlyWhereACaseRepeats) {
  FamilyOutcomes own = outcomes({{"a", "00"}}, {1});
  own.cases[0].seed = 11;
  own.cases[1].seed = 12;
  FamilyFallback f = family_fallback(own);
  EXPECT_FALSE(f.several_seeds);
  EXPECT_EQ(unsolved_text(f), "2 of 2: gen:fam:1:0, gen:fam:1:1");
  FamilyOutcomes seeds = outcomes({{"a", "000"}}, {1});
  seeds.cases[1].scenario_key = "gen:fam:1:0";
  seeds.cases[1].seed = 8;
  f = family_fallback(seeds);
  EXPECT_TRUE(f.several_seeds);
  EXPECT_EQ(unsolved_text(f), "3 of 3: gen:fam:1:0 (seed 7), gen:fam:1:0 (seed 8), gen:fam:1:2 (seed 7)");
  EXPECT_EQ(unsolved_commands(f), std::vector<std::string>{"rrlab generate fam --seed 1 --cases 0,2 --out unsolved/fam-seed1"});
}

TEST(SweepFallback, PairsAmongTheFirstConfigurationsOnly) {
  std::vector<std::pair<std::string, std::string>> configs;
  for (int i = 0; i < 70; ++i) configs.push_back({"c" + std::to_string(i), i == 69 ? "01" : "10"});
  const FamilyFallback f = family_fallback(outcomes(configs, std::vector<double>(70, 1.0)));
  EXPECT_EQ(f.configs_total, 70u);
  EXPECT_EQ(f.configs_considered, kMaxFallbackConfigs);
  EXPECT_EQ(f.solved_by_some, 2u);  // every configuration counts here
  EXPECT_EQ(f.pair_solved, 1u);     // c69, past the first 64, is no fallback
}

TEST(SweepFallback, CommandsPerGeneratorAndSeed) {
  FamilyFallback f;
  f.unsolved_listed = {{"gen:planar_clutter:1:3", 1}, {"gen:planar_clutter:1:3", 2}, {"gen:planar_clutter:1:17", 1},
                       {"gen:planar_clutter:2:4", 1}, {"perturb:22_kapoor_square_circle:5:0", 1},
                       {"file:01_planar7_obstacles", 1}};
  EXPECT_EQ(unsolved_commands(f),
            (std::vector<std::string>{
                "rrlab generate planar_clutter --seed 1 --cases 3,17 --out unsolved/planar_clutter-seed1",
                "rrlab generate planar_clutter --seed 2 --cases 4 --out unsolved/planar_clutter-seed2",
                "rrlab generate --perturb 22_kapoor_square_circle --seed 5 --cases 0 --out "
                "unsolved/22_kapoor_square_circle-seed5"}));
}

// The section in the report: built from stored runs, the witness lane apart.
TEST(SweepFallback, TheReportsSectionInEveryFormat) {
  std::vector<storage::SweepRunEntry> runs;
  std::int64_t id = 0;
  const std::map<std::string, std::string> solved = {{"a", "1100"}, {"b", "0010"}, {"witness", "1111"}};
  for (const auto& [config, cases] : solved)
    for (int i = 0; i < 4; ++i) {
      storage::SweepRunEntry e;
      const std::string scenario = "gen:fam:3:" + std::to_string(i);
      e.row = {"s", "s/" + scenario + "/" + config, scenario, config, "fam", cases[size_t(i)] == '1', std::nullopt, std::nullopt};
      e.run_id = ++id;
      e.seed = 1;
      e.summary_json = nlohmann::json{{"max_tracking_error", 0.001}, {"step_us", {{"p50", 2}, {"p99", 2}}}}.dump();
      runs.push_back(e);
    }
  const SweepReport r = build_report(runs);
  ASSERT_EQ(r.fallbacks.size(), 1u);
  const FamilyFallback& f = r.fallbacks[0];
  EXPECT_EQ(f.first, "a");
  EXPECT_EQ(f.second, "b");
  EXPECT_EQ(f.configs_total, 2u);  // not the witness
  EXPECT_EQ(f.unsolved, 1u);
  EXPECT_EQ(*f.witness_solves, 1u);

  std::ostringstream md, html;
  write_report_markdown(md, r);
  write_report_html(html, r);
  const std::string command = "rrlab generate fam --seed 3 --cases 3 --out unsolved/fam-seed3";
  EXPECT_NE(md.str().find("### What to try when the first choice fails"), std::string::npos);
  EXPECT_NE(md.str().find("| fam | a 2/4, then b: 3/4 (75.0%, +1) | 3 | 3/4 | 1 |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("unsolved: 1 of 4 (the witness solves 1): gen:fam:3:3"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("`" + command + "`"), std::string::npos) << md.str();
  EXPECT_NE(html.str().find("<pre>" + command + "</pre>"), std::string::npos);
  EXPECT_NE(html.str().find("offline upper bound"), std::string::npos);
  const nlohmann::json json = report_json(r);
  const nlohmann::json& row = json["fallbacks"][0];
  EXPECT_EQ(row["first"], "a");
  EXPECT_EQ(row["second"], "b");
  EXPECT_EQ(row["pair_solved"], 3);
  EXPECT_EQ(row["unsolved"]["total"], 1);
  EXPECT_EQ(row["unsolved"]["witness_solves"], 1);
  EXPECT_EQ(row["unsolved"]["listed"], nlohmann::json::parse(R"([{"case": "gen:fam:3:3", "seed": 1}])"));
  EXPECT_EQ(row["unsolved"]["generate"], nlohmann::json::array({command}));
  EXPECT_NE(json["rules"]["fallbacks"].get<std::string>().find("offline upper bound"), std::string::npos);
}

}  // namespace
}  // namespace rrlab::sweep
