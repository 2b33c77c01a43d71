#include <rrlab/scenario/scenario.hpp>

#include <gtest/gtest.h>

#include <filesystem>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

using nlohmann::json;

json valid() {
  return json::parse(R"({
    "name": "t", "dt": 0.01, "duration": 1.0, "angle_unit": "deg",
    "robot": {"kind": "planar", "base": [0, 1],
              "links": [{"length": 1.0, "radius": 0.02}, {"length": 1.0}, {"length": 0.5}],
              "q0": [57.4, -101.3, -95.6],
              "limits": {"lower": [-180, -170, -170], "upper": [180, 170, 170], "velocity": [90, 90, null]}},
    "obstacles": [{"id": "box1", "shape": "polygon", "points": [[1.8,0.1],[1.8,1.2],[2.4,1.2],[2.4,0.1]]},
                  {"id": "tri", "shape": "polygon", "points": [[0,3],[1,3],[0.5,4]], "velocity": [0.1, 0]}],
    "task": {"space": "xy", "trajectory": {"type": "polyline", "points": [[0.5,0.5],[2.5,-0.2]], "time_law": "quintic"}},
    "method": {"name": "sr_task_priority", "params": {"secondary": "joint_centring", "lambda": 0.02}}
  })");
}

TEST(ScenarioLoader, ReadsTheContractExample) {
  const Scenario sc = parse_scenario(valid());
  EXPECT_EQ(sc.model.dof(), 3);
  EXPECT_NEAR(sc.q0[0], 57.4 * M_PI / 180, 1e-12);
  EXPECT_NEAR(sc.model.limits.velocity[0], M_PI / 2, 1e-12);
  EXPECT_TRUE(std::isinf(sc.model.limits.velocity[2]));
  EXPECT_EQ(sc.scene.obstacles.size(), 2u);
  EXPECT_TRUE(sc.scene.obstacles[1].moving());
  EXPECT_EQ(sc.task.trajectory.time_law, TimeLaw::quintic);
  EXPECT_EQ(sc.steps(), 100);
  ASSERT_EQ(sc.method.params.size(), 2u);
  for (const auto& [name, value] : sc.method.params)
    if (name == "secondary") EXPECT_DOUBLE_EQ(value, 1.0);  // label → index
    else EXPECT_DOUBLE_EQ(value, 0.02);
}

TEST(ScenarioLoader, SelfCollisionPairsFollowTheMatrixTheOverridesAndTheSwitch) {
  json doc = valid();
  EXPECT_EQ(parse_scenario(doc).model.self_pairs, (std::vector<SelfPair>{{0, 2}}));  // three planar links
  doc["robot"]["allowed_collisions"] = {{3, 1}};  // either order
  EXPECT_TRUE(parse_scenario(doc).model.self_pairs.empty());
  doc = valid();
  doc["robot"]["self_collision"] = false;
  EXPECT_TRUE(parse_scenario(doc).model.self_pairs.empty());
}

TEST(ScenarioLoader, EveryShippedScenarioLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("scenarios"))) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW(load_scenario_file(entry.path().string())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 3);
}

struct Malformed {
  std::string what;
  std::function<void(json&)> edit;
  std::string path;     // the error must name this path
  std::string message;  // and contain this
};

class MalformedScenario : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedScenario, IsRejectedNamingThePath) {
  json doc = valid();
  GetParam().edit(doc);
  try {
    parse_scenario(doc);
    FAIL() << GetParam().what << ": accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.path(), GetParam().path) << e.what();
    EXPECT_NE(std::string(e.what()).find(GetParam().message), std::string::npos) << e.what();
  }
}

json many_links(int n) {
  json links = json::array();
  for (int i = 0; i < n; ++i) links.push_back({{"length", 0.1}});
  return links;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedScenario,
    ::testing::Values(
        Malformed{"negative length", [](json& d) { d["robot"]["links"][1]["length"] = -1.0; },
                  "robot.links[1].length", "must be > 0"},
        Malformed{"q0 size", [](json& d) { d["robot"]["q0"] = {1, 2}; }, "robot.q0",
                  "has 2 values but the robot has 3 joints"},
        Malformed{"unknown method", [](json& d) { d["method"]["name"] = "magic"; }, "method.name",
                  "unknown method \"magic\""},
        Malformed{"NaN (as a string)", [](json& d) { d["dt"] = "NaN"; }, "dt", "must be a number"},
        Malformed{"infinite", [](json& d) { d["robot"]["links"][0]["radius"] = std::numeric_limits<double>::infinity(); },
                  "robot.links[0].radius", "finite"},
        Malformed{"unknown key", [](json& d) { d["robot"]["links"][0]["lenght"] = 1.0; },
                  "robot.links[0].lenght", "unknown key"},
        Malformed{"unknown top key", [](json& d) { d["extra"] = 1; }, "extra", "unknown key"},
        Malformed{"empty polygon", [](json& d) { d["obstacles"][0]["points"] = json::array(); },
                  "obstacles[0].points", "at least 3"},
        Malformed{"self-intersecting polygon",
                  [](json& d) { d["obstacles"][0]["points"] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}}; },
                  "obstacles[0].points", "cross"},
        Malformed{"too many joints", [](json& d) { d["robot"]["links"] = many_links(65); d["robot"].erase("q0"); d["robot"].erase("limits"); },
                  "robot.links", "at most 64"},
        Malformed{"too many steps", [](json& d) { d["duration"] = 1e6; }, "duration", "at most 10000000"},
        Malformed{"wrong type", [](json& d) { d["robot"]["base"] = "origin"; }, "robot.base", "must be an array"},
        Malformed{"unknown kind", [](json& d) { d["robot"]["kind"] = "hexapod"; }, "robot.kind", "unknown value"},
        Malformed{"param out of range", [](json& d) { d["method"]["params"]["lambda"] = 50; },
                  "method.params.lambda", "must be in [0, 10]"},
        Malformed{"unknown param", [](json& d) { d["method"]["params"]["speed"] = 1; }, "method.params.speed",
                  "unknown parameter"},
        Malformed{"bad choice label", [](json& d) { d["method"]["params"]["secondary"] = "dance"; },
                  "method.params.secondary", "must be one of"},
        Malformed{"q0 outside limits", [](json& d) { d["robot"]["q0"][1] = -175; }, "robot.q0[1]", "outside the joint limits"},
        Malformed{"duplicate id", [](json& d) { d["obstacles"][1]["id"] = "box1"; }, "obstacles[1].id", "duplicate"},
        Malformed{"zero dt", [](json& d) { d["dt"] = 0; }, "dt", "must be in (0, 1]"},
        Malformed{"pose task on planar robot", [](json& d) { d["task"]["space"] = "pose"; }, "task.space",
                  "planar robot"},
        Malformed{"path point size", [](json& d) { d["task"]["trajectory"]["points"][1] = {1, 2, 3}; },
                  "task.trajectory.points[1]", "must have 2 numbers"},
        Malformed{"missing robot", [](json& d) { d.erase("robot"); }, "robot", "is required"},
        Malformed{"negative velocity limit", [](json& d) { d["robot"]["limits"]["velocity"][0] = -1; },
                  "robot.limits.velocity[0]", "must be > 0"},
        Malformed{"zero-area polygon", [](json& d) { d["obstacles"][0]["points"] = {{0, 0}, {1, 0}, {2, 0}}; },
                  "obstacles[0].points", "area"},
        Malformed{"unstable gain", [](json& d) { d["task"]["gain"] = 500; }, "task.gain", "1/dt"},
        Malformed{"witness dt", [](json& d) { d["witness"] = {{"dt", 0}, {"q", {d["robot"]["q0"], d["robot"]["q0"]}}}; },
                  "witness.dt", "must be in [1e-6 s, duration]"},
        Malformed{"witness too short",
                  [](json& d) { d["witness"] = {{"dt", 0.25}, {"q", {d["robot"]["q0"], d["robot"]["q0"]}}}; },
                  "witness.q", "needs 5"},
        Malformed{"witness row size", [](json& d) { d["witness"] = {{"dt", 1.0}, {"q", {d["robot"]["q0"], {1, 2}}}}; },
                  "witness.q[1]", "must have 3 numbers"},
        Malformed{"witness not at q0", [](json& d) { d["witness"] = {{"dt", 1.0}, {"q", {{0, 0, 0}, {0, 0, 0}}}}; },
                  "witness.q[0]", "must be robot.q0"},
        Malformed{"witness difficulty",
                  [](json& d) {
                    d["witness"] = {{"dt", 1.0}, {"q", {d["robot"]["q0"], d["robot"]["q0"]}}, {"difficulty", {{"gap", "wide"}}}};
                  },
                  "witness.difficulty.gap", "must be a number"},
        Malformed{"self_collision not a bool", [](json& d) { d["robot"]["self_collision"] = "yes"; },
                  "robot.self_collision", "must be true or false"},
        Malformed{"allowed pair past the links", [](json& d) { d["robot"]["allowed_collisions"] = {{1, 4}}; },
                  "robot.allowed_collisions[0][1]", "a link number from 1 to 3"},
        Malformed{"allowed pair of one link", [](json& d) { d["robot"]["allowed_collisions"] = {{2, 2}}; },
                  "robot.allowed_collisions[0]", "one link twice"},
        Malformed{"allowed pair not a pair", [](json& d) { d["robot"]["allowed_collisions"] = {{1}}; },
                  "robot.allowed_collisions[0]", "2"},
        Malformed{"allowed pair not whole", [](json& d) { d["robot"]["allowed_collisions"] = {{1, 2.5}}; },
                  "robot.allowed_collisions[0][1]", "a link number"},
        Malformed{"witness key", [](json& d) { d["witness"] = {{"dt", 1.0}, {"q", {d["robot"]["q0"]}}, {"t", 1}}; },
                  "witness.t", "unknown key"}),
    [](const ::testing::TestParamInfo<Malformed>& info) {
      std::string name = info.param.what;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

TEST(ScenarioLoader, InvalidJsonTextIsAnError) {
  EXPECT_THROW(parse_scenario_text("{\"dt\": NaN}"), ScenarioError);
  EXPECT_THROW(parse_scenario_text("{"), ScenarioError);
  // found by tests/fuzz/scenario_fuzz.cpp: a number beyond double was the JSON
  // library's out_of_range exception, not a ScenarioError
  EXPECT_THROW(parse_scenario_text("{\"dt\": 1e666}"), ScenarioError);
}

TEST(ScenarioLoader, MissingFileIsAnError) {
  EXPECT_THROW(load_scenario_file("/nonexistent/scenario.json"), ScenarioError);
}

}  // namespace
}  // namespace rrlab
