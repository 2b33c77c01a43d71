// rrlab generate: the files are the sweep's cases, and each witness plays
// back through `rrlab run --method witness` without collision or limit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rrlab_command.hpp"
#include "scenario/generators.hpp"

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

}  // namespace
