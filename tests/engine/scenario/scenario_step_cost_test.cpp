// The step cost model admission uses (a method's registry row, through
// scenario/scenario_step_cost.hpp): properties, not the fitted constants. Each
// costly method grows with the parameters that drive its cost and is blind to
// the others, defaults apply where a scenario sets none, and meshes count by
// their triangles. (How close the model is to real step times is measured by
// bench/method_cost_bench.cpp, not asserted here: tests never time.)
#include <rrlab/scenario/scenario_step_cost.hpp>

#include <gtest/gtest.h>

#include <cmath>

#include <rrlab/methods/registry.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

Scenario with(const std::string& file, const std::string& method, std::vector<std::pair<std::string, double>> params) {
  Scenario scenario = load_scenario_file(test::source_path("scenarios/" + file));
  scenario.method = {method, std::move(params)};
  return scenario;
}

const std::string kPlanar = "01_planar7_obstacles.json";

double factor(const std::string& method, std::vector<std::pair<std::string, double>> params = {},
              const std::string& file = kPlanar) {
  return method_step_factor(with(file, method, std::move(params)));
}

TEST(ScenarioStepCost, EveryMethodCostsAtLeastAPinvStepAtItsDefaults) {
  for (const std::string file : {kPlanar, std::string("03_dh7_pose.json")})
    for (const MethodInfo& info : method_registry()) {
      const double f = factor(info.name, {}, file);
      EXPECT_TRUE(std::isfinite(f)) << info.name;
      EXPECT_GE(f, 1) << info.name << " on " << file;
    }
  EXPECT_EQ(factor("pinv"), 1);  // the unit
}

TEST(ScenarioStepCost, DefaultsApplyWhereTheScenarioSetsNone) {
  for (const MethodInfo& info : method_registry()) {
    std::vector<std::pair<std::string, double>> defaults;
    for (const ParamSpec& spec : info.params) defaults.push_back({spec.name, spec.def});
    EXPECT_EQ(factor(info.name), factor(info.name, defaults)) << info.name;
  }
}

TEST(ScenarioStepCost, CostlyMethodsGrowWithWhatDrivesTheirCostOnly) {
  // multi_preview: GA evaluations a step (previews x population x generations)
  EXPECT_GT(factor("multi_preview", {{"population", 200}}), factor("multi_preview"));
  EXPECT_GT(factor("multi_preview", {{"generations", 4}}), factor("multi_preview"));
  EXPECT_GT(factor("multi_preview", {{"previews", 5}}), factor("multi_preview", {{"previews", 1}}));
  EXPECT_EQ(factor("multi_preview", {{"previews", 0}}), factor("multi_preview", {{"previews", 1}}));  // planned: as 1
  // direct_search: 3^k options over k perturbed joints, at most the free ones
  EXPECT_GT(factor("direct_search", {{"perturb_mask", 127}}), factor("direct_search", {{"perturb_mask", 3}}));
  EXPECT_GT(factor("direct_search", {{"newton_iterations", 32}}), factor("direct_search", {{"newton_iterations", 0}}));
  EXPECT_LT(factor("direct_search", {}, "03_dh7_pose.json"), factor("direct_search"));  // pose: one free joint
  EXPECT_EQ(factor("direct_search", {{"perturb_mask", 127}}, "03_dh7_pose.json"),
            factor("direct_search", {{"perturb_mask", 1}}, "03_dh7_pose.json"));  // capped at the free joints
  EXPECT_GT(factor("ccp_voronoi", {{"newton_iterations", 80}}), factor("ccp_voronoi"));
  // a parameter that drives no cost changes none
  EXPECT_EQ(factor("dls", {{"lambda", 0.2}}), factor("dls", {{"lambda", 0.01}}));
  EXPECT_EQ(factor("multi_preview", {{"mutation", 0.5}}), factor("multi_preview"));
}

TEST(ScenarioStepCost, MeshesCountByTheirTriangles) {
  const Scenario hoop = load_scenario_file(test::source_path("scenarios/43_urdf_iiwa14_mesh_obstacle.json"));
  const double primitives = double(hoop.scene.obstacles.size());
  EXPECT_NEAR(obstacle_equivalents(hoop.scene), primitives + 576.0 / 64, 1e-9);  // the 576-triangle torus
  const Scenario capsules = load_scenario_file(test::source_path("scenarios/40_urdf_iiwa14_pose.json"));
  EXPECT_EQ(link_mesh_factor(capsules.model), 1);
  EXPECT_EQ(obstacle_equivalents(capsules.scene), double(capsules.scene.obstacles.size()));
}

}  // namespace
}  // namespace rrlab
