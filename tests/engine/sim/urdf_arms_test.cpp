// Every registered method on each shipped URDF arm: a short stretch of its
// pose task among obstacles, every step finite.
#include <gtest/gtest.h>

#include <cmath>

#include "methods/registry.hpp"
#include "scenario/scenario.hpp"
#include "sim/simulator.hpp"
#include "engine/test_models.hpp"

namespace rrlab {
namespace {

class UrdfArmRuns : public ::testing::TestWithParam<const char*> {};

TEST_P(UrdfArmRuns, EveryMethodStepsFinitely) {
  const Scenario scenario = load_scenario_file(test::source_path(std::string("scenarios/") + GetParam()));
  int ran = 0;
  for (const MethodInfo& info : method_registry()) {
    Scenario sc = scenario;
    sc.method.name = info.name;
    sc.method.params.clear();
    std::unique_ptr<Simulator> sim;
    try {
      sim = std::make_unique<Simulator>(sc);
    } catch (const std::exception& e) {
      ADD_FAILURE() << info.name << " refused the URDF arm: " << e.what();
      continue;
    }
    double worst_error = 0;
    for (int i = 0; i < 60; ++i) {  // 0.3 s of the task
      sim->step();
      const Frame& f = sim->frame();
      ASSERT_TRUE(f.q.allFinite()) << info.name << " step " << i;
      ASSERT_TRUE(f.qdot.allFinite()) << info.name << " step " << i;
      ASSERT_TRUE(std::isfinite(f.task_error)) << info.name << " step " << i;
      worst_error = std::max(worst_error, f.task_error);
    }
    // each method follows the circle's start (measured below 0.05 m for all)
    EXPECT_LT(worst_error, 0.05) << info.name;
    ++ran;
  }
  EXPECT_EQ(ran, int(method_registry().size()));
}

INSTANTIATE_TEST_SUITE_P(Arms, UrdfArmRuns,
                         ::testing::Values("40_urdf_iiwa14_pose.json", "41_urdf_panda_pose.json", "42_urdf_gen3_pose.json",
                                           "43_urdf_iiwa14_mesh_obstacle.json"));

}  // namespace
}  // namespace rrlab
