// rrlab generate: the files are the sweep's cases, and each witness plays
// back through `rrlab run --method witness` without collision or limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include <rrlab/generators/generators.hpp>
#include <rrlab/generators/perturbation.hpp>
#include <rrlab/scenario/scenario.hpp>

#include "rrlab_command.hpp"

namespace {

using nlohmann::json;

TEST(CliGenerate, WritesTheSweepsCasesAndTheirWitnessesPlayBack) {
  const auto dir = std::filesystem::temp_directory_path() / "rrlab_cli_generate_test";
  std::filesystem::remove_all(dir);
  const rrlab::testing::CliRun made = rrlab::testing::run_cli(
      "generate narrow_passage --seed 3 --count 2 --first 5 --option dof=[4,6] --option time_law=linear --out " +
      dir.string());
  ASSERT_EQ(made.code, 0) << made.err;
  for (int index : {5, 6}) {
    const auto file = dir / ("narrow_passage-" + std::to_string(index) + ".json");
    EXPECT_NE(made.out.find(file.string()), std::string::npos) << made.out;
    const json doc = json::parse(std::ifstream(file));
    EXPECT_EQ(doc, rrlab::generate_scenario("narrow_passage", {{"dof", {4, 6}}, {"time_law", "linear"}}, 3, index));
    const rrlab::testing::CliRun played = rrlab::testing::run_cli("run " + file.string() + " --method witness");
    ASSERT_EQ(played.code, 0) << played.err;
    const json summary = json::parse(played.out);
    EXPECT_EQ(summary["method"], "witness");
    EXPECT_EQ(summary["collided"], false);
    EXPECT_EQ(summary["joint_limit_violated"], false);
    EXPECT_LT(summary["max_tracking_error"].get<double>(), 5e-4);
    EXPECT_GE(summary["min_distance"].get<double>(), doc["witness"]["difficulty"]["clearance"].get<double>() - 1e-6);
  }
  std::filesystem::remove_all(dir);
}

TEST(CliGenerate, WritesAPerturbationFamilysCasesAsTheSweepMakesThem) {
  const auto dir = std::filesystem::temp_directory_path() / "rrlab_cli_perturb_test";
  std::filesystem::remove_all(dir);
  const rrlab::testing::CliRun made = rrlab::testing::run_cli(
      "generate --perturb 22_kapoor_square_circle --seed 2 --count 2 --option obstacles.shift=0.03 "
      "--option speed=[0.8,1.25] --option q0_self_motion=0.2 --option path.shift=0.02 --out " + dir.string());
  ASSERT_EQ(made.code, 0) << made.err;
  const std::string catalogue = std::string(RRLAB_SOURCE_DIR) + "/scenarios";
  const json base = rrlab::read_json_file(catalogue + "/22_kapoor_square_circle.json", "scenario");
  const rrlab::PerturbationOptions options = rrlab::parse_perturbation_options(
      json::parse(R"({"obstacles": {"shift": 0.03}, "speed": [0.8, 1.25], "q0_self_motion": 0.2, "path": {"shift": 0.02}})"), "");
  for (int index : {0, 1}) {
    const json expected = rrlab::perturb_scenario(base, catalogue, "22_kapoor_square_circle", options, 2, index);
    const auto file = dir / (expected["name"].get<std::string>() + ".json");
    EXPECT_EQ(json::parse(std::ifstream(file)), expected);
    const rrlab::testing::CliRun ran = rrlab::testing::run_cli("run " + file.string() + " --method dls");
    EXPECT_EQ(ran.code, 0) << ran.err;
  }
  const rrlab::testing::CliRun neither = rrlab::testing::run_cli("generate --out " + dir.string());
  EXPECT_EQ(neither.code, 2);
  EXPECT_NE(neither.err.find("FAMILY or --perturb"), std::string::npos) << neither.err;
  const rrlab::testing::CliRun bad = rrlab::testing::run_cli(
      "generate --perturb 22_kapoor_square_circle --option obstacles.shift=-1 --out " + dir.string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("obstacles.shift"), std::string::npos) << bad.err;
  std::filesystem::remove_all(dir);
}

// issue 41: this case's first draw moves the start past joint 7's limit; the
// command used to refuse it as a bad scenario (exit 2), it now draws again
TEST(CliGenerate, APerturbedStartPastAJointLimitIsDrawnAgain) {
  const auto dir = std::filesystem::temp_directory_path() / "rrlab_cli_perturb_redraw_test";
  std::filesystem::remove_all(dir);
  const rrlab::testing::CliRun made = rrlab::testing::run_cli(
      "generate --perturb 16_chen_sim1_planar12 --seed 7 --first 38 --count 1 --option q0_self_motion=1.0 "
      "--option speed=[0.5,3] --out " + dir.string());
  ASSERT_EQ(made.code, 0) << made.err;
  const std::string catalogue = std::string(RRLAB_SOURCE_DIR) + "/scenarios";
  const json base = rrlab::read_json_file(catalogue + "/16_chen_sim1_planar12.json", "scenario");
  const json expected = rrlab::perturb_scenario(
      base, catalogue, "16_chen_sim1_planar12",
      rrlab::parse_perturbation_options(json::parse(R"({"q0_self_motion": 1.0, "speed": [0.5, 3]})"), ""), 7, 38);
  const auto file = dir / (expected["name"].get<std::string>() + ".json");
  EXPECT_EQ(json::parse(std::ifstream(file)), expected);
  EXPECT_GE(expected["perturbation"]["attempt"].get<int>(), 1);
  const rrlab::testing::CliRun ran = rrlab::testing::run_cli("run " + file.string() + " --method pinv --steps 3");
  EXPECT_EQ(ran.code, 0) << ran.err;
  std::filesystem::remove_all(dir);
}

// shift_reach keys: the shifts sized by the scene, recorded in the case
TEST(CliGenerate, PerturbationShiftsSizedToTheScene) {
  const auto dir = std::filesystem::temp_directory_path() / "rrlab_cli_perturb_reach_test";
  std::filesystem::remove_all(dir);
  const rrlab::testing::CliRun made = rrlab::testing::run_cli(
      "generate --perturb 13_sezgin_ex3_narrow_gap --seed 1 --count 1 --option obstacles.shift_reach=0.05 "
      "--option path.shift_reach=0.01 --option path.shift_gap=0.9 --out " + dir.string());
  ASSERT_EQ(made.code, 0) << made.err;
  const json doc = json::parse(std::ifstream(dir / "sezgin_ex3_narrow_gap-p0.json"));
  const json& sized = doc["perturbation"]["sized_to_scene"];
  EXPECT_EQ(sized["reach"], 3.0);
  EXPECT_NEAR(sized["obstacle_shift"].get<double>(), 0.5 * sized["free_gap"].get<double>(), 1e-6);
  EXPECT_NEAR(sized["path_shift"].get<double>(), 0.03, 1e-9);
  const rrlab::testing::CliRun both = rrlab::testing::run_cli(
      "generate --perturb 13_sezgin_ex3_narrow_gap --option obstacles.shift=0.03 --option obstacles.shift_reach=0.05 --out " +
      (dir / "bad").string());
  EXPECT_EQ(both.code, 2);
  EXPECT_NE(both.err.find("obstacles.shift_reach: give shift (m) or shift_reach"), std::string::npos) << both.err;
  std::filesystem::remove_all(dir);
}

// --cases: exactly the given indices (a report's unsolved cases), as the
// sweep entry makes them; clear errors for what it cannot take.
TEST(CliGenerate, WritesExactlyTheGivenCases) {
  const auto dir = std::filesystem::temp_directory_path() / "rrlab_cli_generate_cases_test";
  std::filesystem::remove_all(dir);
  const rrlab::testing::CliRun made =
      rrlab::testing::run_cli("generate planar_limits --seed 4 --cases 7,2 --option dof=[4,5] --out " + dir.string());
  ASSERT_EQ(made.code, 0) << made.err;
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"planar_limits-2.json", "planar_limits-7.json"}));
  for (int index : {2, 7})
    EXPECT_EQ(json::parse(std::ifstream(dir / ("planar_limits-" + std::to_string(index) + ".json"))),
              rrlab::generate_scenario("planar_limits", {{"dof", {4, 5}}}, 4, index));
  struct Bad {
    std::string args, message;
  };
  for (const Bad& bad : {Bad{"--cases 3,3", "--cases: index 3 is given twice"},
                         Bad{"--cases 3,x", "--cases: must be a whole number"},
                         Bad{"--cases 3,-1", "--cases: must be a whole number"},
                         Bad{"--cases 3 --count 2", "excludes"},
                         Bad{"--cases 3 --first 2", "excludes"}}) {
    const rrlab::testing::CliRun run =
        rrlab::testing::run_cli("generate planar_limits " + bad.args + " --out " + (dir / "bad").string());
    EXPECT_EQ(run.code, 2) << bad.args;
    EXPECT_NE(run.err.find(bad.message), std::string::npos) << bad.args << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad")) << bad.args;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
