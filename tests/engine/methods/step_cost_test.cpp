// The step cost model admission uses (methods/step_cost.hpp): each costly
// method grows with the parameters that drive its cost, defaults apply where
// a scenario sets none, and meshes count by their triangles. (How close the
// model is to real step times is measured by bench/method_cost_bench.cpp,
// not asserted here: tests never time.)
#include "methods/step_cost.hpp"

#include <gtest/gtest.h>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

Scenario with(const std::string& file, const std::string& method, std::vector<std::pair<std::string, double>> params) {
  Scenario scenario = load_scenario_file(test::source_path("scenarios/" + file));
  scenario.method = {method, std::move(params)};
  return scenario;
}

TEST(StepCost, MethodsGrowWithWhatDrivesTheirCost) {
  const std::string planar = "01_planar7_obstacles.json";
  EXPECT_EQ(method_step_factor(with(planar, "pinv", {})), 1);
  EXPECT_EQ(method_step_factor(with(planar, "dls", {{"lambda", 0.2}})), 1);
  // multi_preview: 12 x previews x population x generations, defaults 3 x 20 x 1
  EXPECT_EQ(method_step_factor(with(planar, "multi_preview", {})), 1 + 12 * 60);
  EXPECT_EQ(method_step_factor(with(planar, "multi_preview", {{"population", 200}})), 1 + 12 * 600);
  EXPECT_EQ(method_step_factor(with(planar, "multi_preview", {{"previews", 0}})), 1 + 12 * 20);  // planned: as 1
  // direct_search: 3^k options, k = perturbed joints (at most n - m and 6)
  EXPECT_EQ(method_step_factor(with(planar, "direct_search", {})), 1 + 81 * 1.5);                // mask 23: 4 joints
  EXPECT_EQ(method_step_factor(with(planar, "direct_search", {{"perturb_mask", 127}})), 1 + 243 * 1.5);  // 7 -> n - m = 5
  EXPECT_EQ(method_step_factor(with("03_dh7_pose.json", "direct_search", {})), 1 + 3 * 1.5);    // pose: n - m = 1
  EXPECT_GT(method_step_factor(with(planar, "ccp_voronoi", {{"newton_iterations", 80}})),
            method_step_factor(with(planar, "ccp_voronoi", {})));
}

TEST(StepCost, MeshesCountByTheirTriangles) {
  const Scenario hoop = load_scenario_file(test::source_path("scenarios/43_urdf_iiwa14_mesh_obstacle.json"));
  const double primitives = double(hoop.scene.obstacles.size());
  EXPECT_NEAR(obstacle_equivalents(hoop.scene), primitives + 576.0 / 64, 1e-9);  // the 576-triangle torus
  const Scenario capsules = load_scenario_file(test::source_path("scenarios/40_urdf_iiwa14_pose.json"));
  EXPECT_EQ(link_mesh_factor(capsules.model), 1);
  EXPECT_EQ(obstacle_equivalents(capsules.scene), double(capsules.scene.obstacles.size()));
}

}  // namespace
}  // namespace rrlab
