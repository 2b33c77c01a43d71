// rrlab sweep, merge and report on the command line: exit codes and messages.
#include <gtest/gtest.h>

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
                             "step_us_p50", "step_us_p99"})
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
