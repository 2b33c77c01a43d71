// rrlab sweep, merge and report on the command line: exit codes and messages.
#include <gtest/gtest.h>

#include <set>

#include <rrlab/generators/generators.hpp>

#include "sweep_test_support.hpp"

namespace rrlab::sweep {
namespace {

using testing::rrlab;

TEST(SweepCli, SweepMergeReport) {
  testing::TempDir dir;
  const std::string spec = dir.write("spec.json", testing::small_spec("cli").dump());
  const auto a = rrlab("sweep " + spec + " --db " + dir.file("a.db") + " --shard 0/2 --out " + dir.file("a.csv"));
  ASSERT_EQ(a.code, 0) << a.err;
  const nlohmann::json summary = nlohmann::json::parse(a.out);
  EXPECT_EQ(summary["stored"], 6);
  EXPECT_EQ(summary["shard"], "0/2");
  std::ifstream csv(dir.file("a.csv"));
  std::string header, first;
  std::getline(csv, header);
  std::getline(csv, first);
  EXPECT_EQ(header.substr(0, 71), "key,scenario_key,config,family,seed,success,failure_mode,failure_t,run,");
  for (const char* column : {"difficulty_clearance", "difficulty_limit_margin", "difficulty_min_manipulability",
                             "rms_qddot", "max_qddot", "rms_jerk", "max_jerk", "position_limit_steps",
                             "velocity_limit_steps", "step_us_p50", "step_us_p99"})
    EXPECT_NE(header.find(column), std::string::npos) << column;
  EXPECT_EQ(first.substr(0, 40), "cli/file:01_planar7_obstacles/pinv/1,fil");

  const auto b = rrlab("sweep " + spec + " --db " + dir.file("b.db") + " --shard 1/2 --jobs 2");
  ASSERT_EQ(b.code, 0) << b.err;
  const auto merged = rrlab("merge " + dir.file("all.db") + " " + dir.file("a.db") + " " + dir.file("b.db"));
  ASSERT_EQ(merged.code, 0) << merged.err;
  const auto twice = rrlab("merge " + dir.file("all.db") + " " + dir.file("a.db") + " " + dir.file("b.db"));
  EXPECT_EQ(nlohmann::json::parse(twice.out)["merged"][0]["copied"], 0);

  const auto md = rrlab("report " + dir.file("all.db") + " --sweep cli --format md");
  ASSERT_EQ(md.code, 0) << md.err;
  EXPECT_NE(md.out.find("| pinv | file:01_planar7_obstacles | 2 |"), std::string::npos) << md.out;  // per scenario file
  EXPECT_NE(md.out.find("| pinv | file:11_sezgin_ex1_box | 2 |"), std::string::npos) << md.out;
  const auto html = rrlab("report " + dir.file("all.db") + " --format html --out " + dir.file("r.html"));
  ASSERT_EQ(html.code, 0) << html.err;
  EXPECT_TRUE(std::filesystem::file_size(dir.file("r.html")) > 1000);
}

// The report's unsolved cases and the command it prints for them: the
// command writes exactly the listed cases, as the sweep generated them.
TEST(SweepCli, TheUnsolvedCasesCommandWritesExactlyTheListedCases) {
  testing::TempDir dir;
  const nlohmann::json spec = nlohmann::json::parse(R"({
    "name": "frontier", "scenarios": [{"generator": "planar_clutter", "count": 5, "seed": 11}],
    "methods": ["pinv", "dls", "witness"],
    "success": {"max_tracking_error": 0.01, "collision": false, "joint_limits": true}})");
  const auto swept = rrlab("sweep " + dir.write("spec.json", spec.dump()) + " --db " + dir.file("f.db"));
  ASSERT_EQ(swept.code, 0) << swept.err;
  const auto md = rrlab("report " + dir.file("f.db") + " --format md");
  ASSERT_EQ(md.code, 0) << md.err;
  // "- **planar_clutter**, unsolved: N of 5 (the witness solves M): KEY, KEY" and the command below it
  const size_t line = md.out.find("- **planar_clutter**, unsolved: ");
  ASSERT_NE(line, std::string::npos) << md.out;  // pinv fails every case by construction, dls nearly every one
  const std::string listing = md.out.substr(line, md.out.find('\n', line) - line);
  std::set<std::string> listed;
  const std::string prefix = "gen:planar_clutter:11:";
  for (size_t at = listing.find(prefix); at != std::string::npos; at = listing.find(prefix, at + 1))
    listed.insert("planar_clutter-" + listing.substr(at + prefix.size(), listing.find_first_not_of("0123456789", at + prefix.size()) - at - prefix.size()) + ".json");
  ASSERT_FALSE(listed.empty()) << listing;
  const size_t command_at = md.out.find("`rrlab generate ", line);
  ASSERT_NE(command_at, std::string::npos) << md.out;
  std::string command = md.out.substr(command_at + 7, md.out.find('`', command_at + 1) - command_at - 7);
  const std::string out_flag = " --out ";
  ASSERT_NE(command.find(out_flag), std::string::npos) << command;
  command = command.substr(0, command.find(out_flag)) + out_flag + dir.file("cases");
  const auto made = rrlab(command);
  ASSERT_EQ(made.code, 0) << command << "\n" << made.err;
  std::set<std::string> written;
  for (const auto& entry : std::filesystem::directory_iterator(dir.file("cases"))) {
    written.insert(entry.path().filename().string());
    const std::string name = entry.path().stem().string();
    const int index = std::stoi(name.substr(name.rfind('-') + 1));
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(entry.path())), generate_scenario("planar_clutter", nlohmann::json::object(), 11, index));
  }
  EXPECT_EQ(written, listed) << command;
}

TEST(SweepCli, BadInputExitsTwoNamingTheProblem) {
  testing::TempDir dir;
  nlohmann::json bad = testing::small_spec();
  bad["methods"] = nlohmann::json::parse(R"(["pinv", "dls", {"name": "dls", "params": {"lambda": [0.1, 11]}}])");
  const std::string spec = dir.write("bad.json", bad.dump());
  const std::string good = dir.write("good.json", testing::small_spec().dump());
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"sweep " + spec + " --db " + dir.file("x.db"), "methods[2].params.lambda[1]: must be in [0, 10]"},
      {"sweep " + dir.file("none.json") + " --db " + dir.file("x.db"), "cannot read sweep spec"},
      {"sweep " + good + " --db " + dir.file("x.db") + " --shard 2/2", "--shard: the shard index must be in [0, 1]"},
      {"sweep " + good + " --db " + dir.file("x.db") + " --jobs 0", "--jobs"},
      {"report " + dir.file("none.db") + " --format md", "no database file"},
      {"report " + dir.file("x.db") + " --format pdf", "--format"},
      {"merge " + dir.file("out.db") + " " + dir.file("none.db"), "no database file"},
  };
  for (const Case& c : cases) {
    const auto r = rrlab(c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
  }
}

}  // namespace
}  // namespace rrlab::sweep
