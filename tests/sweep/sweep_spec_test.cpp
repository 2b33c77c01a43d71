// Sweep specs: what parses, and errors that name the JSON path.
#include <gtest/gtest.h>

#include <rrlab/sweep/sweep_spec.hpp>

#include "sweep_test_support.hpp"

namespace rrlab::sweep {
namespace {

using nlohmann::json;
using testing::parse_spec;
using testing::small_spec;

// The error's text starts with `prefix` ("path: message...").
void expect_error(const json& doc, const std::string& prefix) {
  try {
    parse_spec(doc);
    ADD_FAILURE() << "no error, expected " << prefix;
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()).substr(0, prefix.size()), prefix) << e.what();
  }
}

TEST(SweepSpec, ParsesScenariosConfigsSeedsAndCriteria) {
  const SweepSpec spec = parse_spec(small_spec());
  EXPECT_EQ(spec.name, "small");
  ASSERT_EQ(spec.scenarios.size(), 2u);
  EXPECT_EQ(spec.scenarios[0].family, "file");
  EXPECT_EQ(spec.scenarios[0].case_key(0), "file:01_planar7_obstacles");
  ASSERT_EQ(spec.configs.size(), 3u);
  EXPECT_EQ(spec.configs[0].key, "pinv");
  EXPECT_EQ(spec.configs[1].key, "dls{lambda=0.02}");
  EXPECT_EQ(spec.configs[2].key, "dls{lambda=0.10000000000000001}");  // %.17g: exactly the double
  EXPECT_EQ(spec.seeds, (std::vector<std::uint64_t>{1, 2}));
  EXPECT_EQ(*spec.success.max_tracking_error, 0.01);
  EXPECT_FALSE(spec.success.collision);
  EXPECT_EQ(*spec.steps, 60);
}

TEST(SweepSpec, GridIsTheCartesianProductInTheMethodsParameterOrder) {
  json doc = small_spec();
  // written damping first: keys follow dls's own order (lambda, damping), labels printed as labels
  doc["methods"] = json::parse(R"([{"name": "dls", "params": {"damping": ["fixed", "adaptive"], "lambda": [0.5, 1]}}])");
  const SweepSpec spec = parse_spec(doc);
  ASSERT_EQ(spec.configs.size(), 4u);
  EXPECT_EQ(spec.configs[0].key, "dls{lambda=0.5,damping=fixed}");
  EXPECT_EQ(spec.configs[1].key, "dls{lambda=0.5,damping=adaptive}");
  EXPECT_EQ(spec.configs[2].key, "dls{lambda=1,damping=fixed}");
  EXPECT_EQ(spec.configs[3].key, "dls{lambda=1,damping=adaptive}");
  EXPECT_EQ(spec.configs[3].params[1].value, 1.0);  // the enumeration's index
}

TEST(SweepSpec, PathsAreRelativeToTheSpecFile) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir.path / "sub");
  std::filesystem::copy_file(testing::scenarios_dir() / "01_planar7_obstacles.json", dir.path / "sub" / "mine.json");
  json doc = small_spec();
  doc["scenarios"] = {"sub/mine.json"};
  const std::string file = dir.write("spec.json", doc.dump());
  const SweepSpec spec = load_sweep_spec(file, testing::scenarios_dir());
  EXPECT_EQ(spec.scenarios[0].case_key(0), "file:mine");
}

TEST(SweepSpec, APerturbEntryIsAFamilyOfItsScenario) {
  json doc = small_spec();
  doc["scenarios"] = json::parse(R"([{"perturb": "10_sezgin_ex1_lshape", "count": 3, "seed": 7,
                                      "obstacles": {"shift": 0.03, "rotate_deg": 5}, "speed": [0.5, 2],
                                      "q0_self_motion": 0.3, "path": {"shift": 0.02}}])");
  const SweepSpec spec = parse_spec(doc);
  ASSERT_EQ(spec.scenarios.size(), 1u);
  const ScenarioEntry& entry = spec.scenarios[0];
  EXPECT_TRUE(entry.perturbs());
  EXPECT_EQ(entry.family, "perturb:10_sezgin_ex1_lshape");
  EXPECT_EQ(entry.case_key(2), "perturb:10_sezgin_ex1_lshape:7:2");
  EXPECT_EQ(entry.count, 3);
  EXPECT_EQ(entry.perturbation.obstacle_shift.metres, 0.03);
  EXPECT_EQ(entry.perturbation.speed_max, 2.0);
  EXPECT_EQ(entry.perturbation.path_shift.metres, 0.02);
  EXPECT_EQ(entry.perturbation_scale.reach, 0);  // metres: nothing measured
  // the same base with another seed is another family of cases; with the same seed, a repeat
  doc["scenarios"].push_back(doc["scenarios"][0]);
  expect_error(doc, "scenarios[1]: gives the same case keys (perturb:10_sezgin_ex1_lshape:7)");
  doc["scenarios"][1]["seed"] = 8;
  EXPECT_EQ(parse_spec(doc).scenarios.size(), 2u);
}

// shift_reach keys: the scenario's reach and free gap are measured once, when
// the spec is read, and every case is the one perturb_scenario() makes
TEST(SweepSpec, APerturbEntrySizedToTheSceneMeasuresItOnce) {
  json doc = small_spec();
  doc["scenarios"] = json::parse(R"([{"perturb": "13_sezgin_ex3_narrow_gap", "count": 2, "seed": 3,
                                      "obstacles": {"shift_reach": 0.05}, "path": {"shift_reach": 0.01, "shift_gap": 0.2}}])");
  const SweepSpec spec = parse_spec(doc);
  const ScenarioEntry& entry = spec.scenarios[0];
  EXPECT_DOUBLE_EQ(entry.perturbation_scale.reach, 3.0);
  EXPECT_DOUBLE_EQ(entry.perturbation_scale.free_gap, perturbation_scale(*entry.scenario).free_gap);
  EXPECT_EQ(entry.perturbation.obstacle_shift.reach, 0.05);
  EXPECT_EQ(entry.perturbation.path_shift.gap, 0.2);
  for (int index : {0, 1})
    EXPECT_EQ(perturb_scenario(entry.scenario->json, entry.dir, entry.name, entry.perturbation, entry.perturbation_scale, 3, index),
              perturb_scenario(entry.scenario->json, entry.dir, entry.name, entry.perturbation, 3, index));
  doc["scenarios"][0]["obstacles"]["shift"] = 0.03;
  expect_error(doc, "scenarios[0].obstacles.shift_reach: give shift (m) or shift_reach (a fraction of the reach), not both");
}

TEST(SweepSpec, ErrorsNameTheJsonPath) {
  const auto with = [](const std::string& key, const json& value) {
    json doc = small_spec();
    doc[key] = value;
    return doc;
  };
  expect_error(with("methods", json::parse(R"(["pinv", "dls", {"name": "dls", "params": {"lambda": [0.1, 11]}}])")),
               "methods[2].params.lambda[1]: must be in [0, 10]");
  expect_error(with("methods", json::parse(R"(["pinv", "nope"])")), "methods[1]: ");
  expect_error(with("methods", json::parse(R"([{"name": "dls", "params": {"nope": 1}}])")), "methods[0].params.nope: unknown parameter");
  expect_error(with("methods", json::parse(R"([{"name": "dls", "params": {"damping": "soft"}}])")), "methods[0].params.damping: must be one of");
  expect_error(with("methods", json::parse(R"([{"name": "dls", "params": {"lambda": []}}])")), "methods[0].params.lambda: must list");
  expect_error(with("methods", json::parse(R"(["dls", {"name": "dls"}])")), "methods[1]: repeats the configuration dls of methods[0]");
  expect_error(with("methods", json::parse(R"([{"name": "dls", "lr": 1}])")), "methods[0].lr: unknown key");
  expect_error(with("methods", json::array()), "methods: must list");
  expect_error(with("scenarios", json::parse(R"(["01_planar7_obstacles", "nope"])")), "scenarios[1]: no catalogue scenario 'nope'");
  expect_error(with("scenarios", json::parse(R"(["missing/file.json"])")), "scenarios[0]: no scenario file");
  expect_error(with("scenarios", json::parse(R"([{"perturb": "nope", "count": 2}])")),
               "scenarios[0].perturb: no catalogue scenario 'nope'");
  expect_error(with("scenarios", json::parse(R"([{"perturb": "01_planar7_obstacles", "count": 2, "speed": [3, 1]}])")),
               "scenarios[0].speed: must be [min, max]");
  expect_error(with("scenarios", json::parse(R"([{"perturb": "01_planar7_obstacles", "count": 2, "shift": 1}])")),
               "scenarios[0].shift: unknown key (allowed here: perturb, count, seed, obstacles, speed, q0_self_motion, path)");
  expect_error(with("scenarios", json::parse(R"(["01_planar7_obstacles", "01_planar7_obstacles"])")),
               "scenarios[1]: gives the same case keys (file:01_planar7_obstacles) as scenarios[0]");
  expect_error(with("scenarios", json::parse(R"(["01_planar7_obstacles", {"generator": "jungle", "count": 3}])")),
               "scenarios[1].generator: unknown family \"jungle\"");
  expect_error(with("scenarios", json::parse(R"([{"generator": "planar_clutter", "count": 0}])")), "scenarios[0].count: must be an integer");
  expect_error(with("scenarios", json::parse(R"([{"generator": "planar_clutter", "count": 2, "seed": -1}])")), "scenarios[0].seed: must be a non-negative integer");
  expect_error(with("scenarios", json::parse(R"([7])")), "scenarios[0]: must be a path");
  expect_error(with("seeds", json::parse(R"([1, 1])")), "seeds[1]: repeats seed 1");
  expect_error(with("seeds", json::parse(R"([1, 2.5])")), "seeds[1]: must be a non-negative integer");
  expect_error(with("success", json::parse(R"({"max_tracking_error": -1})")), "success.max_tracking_error: must be >= 0");
  expect_error(with("success", json::parse(R"({"collisions": false})")), "success.collisions: unknown key");
  expect_error(with("success", json::parse(R"({"collision": "no"})")), "success.collision: must be true or false");
  expect_error(with("steps", 0), "steps: must be an integer in [1, ");
  expect_error(with("name", "a b"), "name: must match");
  expect_error(with("extra", 1), "extra: unknown key");
  json no_success = small_spec();
  no_success.erase("success");
  expect_error(no_success, "success: is required");
  // a configuration a listed scenario cannot take (the box scene has 7 links)
  expect_error(with("methods", json::parse(R"([{"name": "ccp_voronoi", "params": {"ccp_link": 9}}])")),
               "methods[0]: ");
}

// Found with tests/fuzz/sweeps_fuzz.cpp: a count or steps beyond long was cast
// to long before the range check (undefined behaviour; UBSan aborts).
TEST(SweepSpec, HugeCountsAndStepsAreOutOfRange) {
  json doc = small_spec();
  doc["steps"] = 1e300;
  expect_error(doc, "steps: must be an integer in [1, ");
  doc["steps"] = -1e300;
  expect_error(doc, "steps: must be an integer in [1, ");
  doc = small_spec();
  doc["scenarios"] = json::parse(R"([{"generator": "planar_clutter", "count": 1e300}])");
  expect_error(doc, "scenarios[0].count: must be an integer in [1, 1000000]");
}

TEST(SweepSpec, ScenarioFileErrorsArePrefixedWithTheEntry) {
  testing::TempDir dir;
  json scenario = json::parse(std::ifstream(testing::scenarios_dir() / "01_planar7_obstacles.json"));
  scenario["robot"]["links"][1]["length"] = -1;
  dir.write("bad.json", scenario.dump());
  json doc = small_spec();
  doc["scenarios"] = {"bad.json"};
  try {
    parse_sweep_spec(doc, {dir.path, testing::scenarios_dir()});
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.path(), "scenarios[0].robot.links[1].length") << e.what();
  }
}

TEST(SuccessCriteria, JudgesASummary) {
  SuccessCriteria c = parse_success_criteria(json::parse(R"({"max_tracking_error": 0.01, "min_distance": 0})"), "success");
  Summary s;
  s.max_tracking_error = 0.005;
  s.min_distance = 0.1;
  EXPECT_TRUE(judge_success(c, s));
  s.collided = true;
  EXPECT_FALSE(judge_success(c, s));
  s.collided = false;
  s.joint_limit_violated = true;
  EXPECT_FALSE(judge_success(c, s));
  s.joint_limit_violated = false;
  s.nonfinite_steps = 1;
  EXPECT_FALSE(judge_success(c, s));
  s.nonfinite_steps = 0;
  s.max_tracking_error = std::nan("");
  EXPECT_FALSE(judge_success(c, s));
}

TEST(SuccessCriteria, JointSpeedsAndASettleTime) {
  SuccessCriteria c = parse_success_criteria(
      json::parse(R"({"max_tracking_error": 0.01, "settle_time": 2, "joint_speeds": true})"), "success");
  EXPECT_EQ(c.settle_time, 2.0);
  Summary s;
  s.max_tracking_error = 0.5;  // the start off the path: the watch judges the error after 2 s
  EXPECT_TRUE(judge_success(c, s));
  s.max_qdot_ratio = 1.0 + 1e-9;  // riding the bound
  EXPECT_TRUE(judge_success(c, s));
  s.max_qdot_ratio = 1.01;
  EXPECT_FALSE(judge_success(c, s));
  s.max_qdot_ratio.reset();  // no velocity limits: nothing to exceed
  EXPECT_TRUE(judge_success(c, s));
  const auto error_of = [](const char* text) {
    try {
      parse_success_criteria(json::parse(text), "success");
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of(R"({"settle_time": 1})"),
            "success.settle_time: needs max_tracking_error: it says when that bound starts");
  EXPECT_EQ(error_of(R"({"max_tracking_error": 0.01, "settle_time": -1})"), "success.settle_time: must be >= 0 s");
  EXPECT_EQ(error_of(R"({"joint_speeds": 1})"), "success.joint_speeds: must be true or false, got a number");
}

}  // namespace
}  // namespace rrlab::sweep
