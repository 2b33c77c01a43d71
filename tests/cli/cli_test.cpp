// The rrlab executable: summary JSON, CSV columns, exit codes and messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>

#include "rrlab_command.hpp"

namespace {

using nlohmann::json;

using Result = rrlab::testing::CliRun;
Result rrlab(const std::string& args) { return rrlab::testing::run_cli(args); }

std::string scenario(const std::string& name) { return std::string(RRLAB_SOURCE_DIR) + "/scenarios/" + name; }

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(Cli, RunPrintsTheSummaryJson) {
  const Result r = rrlab("run " + scenario("01_planar7_obstacles.json") + " --steps 50");
  ASSERT_EQ(r.code, 0) << r.err;
  const json s = json::parse(r.out);
  for (const char* key : {"scenario", "method", "steps", "collided", "min_distance", "max_tracking_error",
                          "final_tracking_error", "joint_limit_violated", "min_joint_limit_margin",
                          "max_qdot_ratio", "max_qddot_ratio", "max_condition_number", "rms_qddot", "max_qddot",
                          "rms_jerk", "max_jerk", "position_limit_steps", "velocity_limit_steps", "final_q",
                          "step_us"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_EQ(s["steps"], 50);
  EXPECT_TRUE(s["rms_jerk"].is_number());
  EXPECT_EQ(s["final_q"].size(), 7u);
  EXPECT_TRUE(s["step_us"].contains("p99"));
}

TEST(Cli, EveryScenarioRunsWithEveryBaseline) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(RRLAB_SOURCE_DIR) + "/scenarios"))
    if (entry.path().extension() == ".json") files.push_back(entry.path().filename().string());
  ASSERT_GE(files.size(), 4u);
  for (const std::string& file : files)
    for (const char* method : {"pinv", "dls", "gpm", "task_priority", "sr_task_priority", "closest_point"}) {
      const Result r = rrlab("run " + scenario(file) + " --method " + method + " --steps 100");
      EXPECT_EQ(r.code, 0) << file << " " << method << ": " << r.err;
      EXPECT_EQ(json::parse(r.out)["method"], method);
    }
}

TEST(Cli, RunStoresInADatabaseAndReplayVerifies) {
  const auto dir = std::filesystem::temp_directory_path() / "rrlab_cli_db_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string db = (dir / "runs.db").string();
  const Result r = rrlab("run " + scenario("04_planar7_joystick.json") + " --steps 120 --db " + db);
  ASSERT_EQ(r.code, 0) << r.err;
  const json summary = json::parse(r.out);
  ASSERT_TRUE(summary.contains("run"));
  const std::string id = std::to_string(summary["run"].get<long>());
  const Result verify = rrlab("replay " + id + " --db " + db + " --verify");
  EXPECT_EQ(verify.code, 0) << verify.err;
  EXPECT_EQ(json::parse(verify.out)["frames_compared"], 120);
  EXPECT_EQ(rrlab("replay 99 --db " + db).code, 2);
  EXPECT_EQ(rrlab("replay " + id + " --db " + (dir / "missing" / "x.db").string()).code, 2);
  EXPECT_EQ(rrlab("replay " + id + " --db " + (dir / "absent.db").string()).code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "absent.db"));  // replay never creates a database
  std::filesystem::remove_all(dir);
}

TEST(Cli, ReplayVerifyOfASweepRunWithoutFramesComparesItsSummary) {
  const auto dir = std::filesystem::temp_directory_path() / "rrlab_cli_frameless_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string db = (dir / "runs.db").string();
  // a sweep stores its runs without frames: the re-simulation steps as far as the summary and compares it
  const std::string spec = write_temp("rrlab_cli_frameless_sweep.json", json{
      {"name", "frameless"}, {"scenarios", {{{"generator", "planar_clutter"}, {"count", 1}, {"seed", 7}}}},
      {"methods", {"dls"}}, {"steps", 20}, {"success", {{"max_tracking_error", 0.01}}}}.dump());
  const Result sweep = rrlab("sweep " + spec + " --db " + db);
  ASSERT_EQ(sweep.code, 0) << sweep.err;

  const Result verify = rrlab("replay 1 --db " + db + " --verify");
  EXPECT_EQ(verify.code, 0) << verify.out << verify.err;
  const json out = json::parse(verify.out);
  EXPECT_EQ(out["identical"], true) << out;
  EXPECT_EQ(out["compared"], true);
  EXPECT_EQ(out["frames_compared"], 0);
  EXPECT_EQ(out["summary_compared"], true);
  EXPECT_EQ(out["summary"]["steps"], 20);
  std::filesystem::remove_all(dir);
}

TEST(Cli, OutWritesTheCsvColumns) {
  const auto csv = std::filesystem::temp_directory_path() / "rrlab_cli_test.csv";
  const Result r = rrlab("run " + scenario("01_planar7_obstacles.json") + " --method dls --param lambda=0.1 --steps 20 --out " +
                         csv.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("step,t,q1,q2,q3,q4,q5,q6,q7,qdot1,qdot2,qdot3,qdot4,qdot5,qdot6,qdot7,ee_x,ee_y,ee_z,"
                         "ee_quat_w,ee_quat_x,ee_quat_y,ee_quat_z,target_x,target_y,target_z,task_error,",
                         0),
            0u)
      << header;
  EXPECT_NE(header.find(",step_us,lambda"), std::string::npos) << header;
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 20);
  std::filesystem::remove(csv);
}

// `rrlab --version`: the project(VERSION) of CMakeLists.txt, then the git
// commit cmake saw (absent outside a git checkout).
TEST(Cli, VersionPrintsTheProjectVersionAndCommit) {
  const Result r = rrlab("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out.rfind(std::string("rrlab ") + RRLAB_PROJECT_VERSION, 0), 0u) << r.out;
  const std::string commit = RRLAB_GIT_COMMIT;
  if (!commit.empty()) {
    EXPECT_NE(r.out.find("(git " + commit + ")"), std::string::npos) << r.out;
  }
  EXPECT_EQ(r.out.back(), '\n');
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1);
}

TEST(Cli, MethodsListsSpecs) {
  const Result r = rrlab("methods");
  ASSERT_EQ(r.code, 0);
  const json m = json::parse(r.out);
  ASSERT_GE(m.size(), 6u);
  bool found = false;
  for (const json& method : m)
    if (method["name"] == "dls") {
      found = true;
      EXPECT_EQ(method["params"][0]["name"], "lambda");
      EXPECT_TRUE(method["params"][1].contains("choices"));
    }
  EXPECT_TRUE(found);
}

struct BadInput {
  std::string name, args_or_json, expect;
  bool is_json = true;
};

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, ExitsTwoNamingThePath) {
  const BadInput& c = GetParam();
  std::string args = c.args_or_json;
  if (c.is_json) args = "run " + write_temp("rrlab_bad_" + c.name + ".json", c.args_or_json);
  const Result r = rrlab(args);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

const std::string kRobot = R"("robot": {"kind": "planar", "links": [{"length": 1}, {"length": 1}, {"length": 1}]})";
const std::string kTask = R"("task": {"trajectory": {"type": "circle", "center": [1, 1], "radius": 0.2}})";

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInput,
    ::testing::Values(
        BadInput{"neglen", R"({"robot": {"kind": "planar", "links": [{"length": -1}]}, )" + kTask + "}",
                 "robot.links[0].length: must be > 0"},
        BadInput{"q0", R"({"robot": {"kind": "planar", "links": [{"length": 1}], "q0": [1, 2]}, )" + kTask + "}",
                 "robot.q0: has 2 values but the robot has 1 joints"},
        BadInput{"method", "{" + kRobot + ", " + kTask + R"(, "method": {"name": "warp"}})",
                 "method.name: unknown method \"warp\""},
        BadInput{"nan", "{" + kRobot + ", " + kTask + R"(, "dt": NaN})", "is not valid JSON"},
        BadInput{"key", "{" + kRobot + ", " + kTask + R"(, "colour": "red"})", "colour: unknown key"},
        BadInput{"polygon", "{" + kRobot + ", " + kTask + R"(, "obstacles": [{"shape": "polygon", "points": []}]})",
                 "obstacles[0].points"},
        BadInput{"bowtie",
                 "{" + kRobot + ", " + kTask +
                     R"(, "obstacles": [{"shape": "polygon", "points": [[0,0],[1,1],[1,0],[0,1]]}]})",
                 "obstacles[0].points"},
        BadInput{"radius", "{" + kRobot + R"(, "task": {"trajectory": {"type": "circle", "center": [1, 1], "radius": 0}}})",
                 "task.trajectory.radius: must be > 0"},
        BadInput{"shape", "{" + kRobot + ", " + kTask + R"(, "obstacles": [{"shape": "cloud"}]})",
                 "obstacles[0].shape: unknown value"},
        BadInput{"missing_file", "run /nonexistent/x.json", "cannot read scenario file", false},
        BadInput{"bad_param", "run " + scenario("01_planar7_obstacles.json") + " --method dls --param lambda=-3",
                 "--param lambda: must be in [0, 10]", false},
        BadInput{"unknown_param", "run " + scenario("01_planar7_obstacles.json") + " --param zeta=1",
                 "--param zeta: unknown parameter", false},
        BadInput{"cli_method", "run " + scenario("01_planar7_obstacles.json") + " --method teleport",
                 "--method: unknown method", false},
        BadInput{"steps", "run " + scenario("01_planar7_obstacles.json") + " --steps 0",
                 "--steps: must be a whole number in [1, 10000000], got '0'", false},
        BadInput{"no_command", "", "", false},
        BadInput{"witness_without_one", "run " + scenario("01_planar7_obstacles.json") + " --method witness",
                 "no witness", false},
        BadInput{"generate_option", "generate planar_clutter --option dof=2 --out /tmp/rrlab_generate_bad",
                 "options.dof: 2 is outside the allowed range [3, 64]", false},
        BadInput{"generate_option_syntax", "generate planar_clutter --option dof --out /tmp/rrlab_generate_bad",
                 "--option: expects KEY=VALUE", false},
        BadInput{"generate_family", "generate torus_maze --out /tmp/rrlab_generate_bad", "unknown family", false}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

// A scenario file or sweep spec nested 60,000 levels deep (a stack overflow
// in the JSON library before the depth limit): exit 2 naming the byte.
TEST(Cli, DeepScenarioFilesAndSweepSpecs) {
  std::string deep;
  for (int i = 0; i < 60000; ++i) deep += "{\"a\": ";
  deep += "1" + std::string(60000, '}');
  const std::string file = write_temp("rrlab_deep_scenario.json", deep);
  const std::string db = (std::filesystem::temp_directory_path() / "rrlab_deep_sweep.db").string();
  for (const std::string& command : {"run " + file, "sweep " + file + " --db " + db}) {
    const Result r = rrlab(command);
    EXPECT_EQ(r.code, 2) << command << ": " << r.err;
    EXPECT_NE(r.err.find("nested deeper than 64 levels at byte 385"), std::string::npos) << command << ": " << r.err;
  }
  std::filesystem::remove(file);
  std::filesystem::remove(db);
}

}  // namespace
