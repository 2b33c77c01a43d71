// The property that defines each baseline method, shown on small scenarios.
#include <gtest/gtest.h>

#include <map>

#include <rrlab/generators/generators.hpp>
#include <rrlab/methods/registry.hpp>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"

namespace rrlab {
namespace {

using nlohmann::json;
using test::planar_robot;
using test::planar_tip;
using test::run_scenario;

const std::vector<std::string> kBaselines = {"pinv", "dls", "gpm", "task_priority", "sr_task_priority",
                                             "closest_point"};

// Redundant planar 4-link arm, circle of radius 0.3 m, no obstacles.
json four_link_circle() {
  return {{"dt", 0.01},
          {"duration", 6.0},
          {"robot", planar_robot(4, 0.5, 0.02, {0.2, 0.6, 0.5, 0.4})},
          {"task", {{"space", "xy"},
                    {"trajectory", {{"type", "circle"}, {"center", {0.9, 0.9}}, {"radius", 0.3}}}}}};
}

// 7-DOF iiwa-like arm: circle in 3D with fixed orientation (6-row pose task).
json dh_pose_circle() {
  json links = json::array();
  for (const DhLinkSpec& l : test::iiwa_dh())
    links.push_back({{"a", l.a}, {"alpha", l.alpha}, {"d", l.d}, {"radius", l.radius}});
  return {{"dt", 0.005},
          {"duration", 4.0},
          {"robot", {{"kind", "dh"}, {"links", links}, {"q0", {0, 0.7, 0, -1.2, 0, 1.0, 0}}}},
          {"task", {{"space", "pose"},
                    {"trajectory", {{"type", "circle"}, {"center", {0.5, -0.12, 0.55}}, {"radius", 0.12},
                                    {"normal", {1, 0, 0}}}}}}};
}

class EveryBaseline : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryBaseline, TracksAPlanarCircleWithoutObstacles) {
  const auto r = run_scenario(four_link_circle(), GetParam());
  // the start is 0.1 m or so off the circle: the closed loop removes it first
  EXPECT_LT(r.max_error_after(100), 1e-4) << GetParam();
  EXPECT_LT(r.summary.final_tracking_error, 1e-4);
  EXPECT_EQ(r.summary.nonfinite_steps, 0);
}

TEST_P(EveryBaseline, TracksA6dPoseCircleOnASevenJointArm) {
  // fixed damping trades accuracy for robustness everywhere (λ = 0.05 leaves
  // ~3e-4 m here); adaptive damping only acts near singularities
  const json params = GetParam() == "dls" ? json{{"damping", "adaptive"}} : json::object();
  const auto r = run_scenario(dh_pose_circle(), GetParam(), params);
  double max_error = 0, max_orientation = 0;
  for (size_t i = 100; i < r.frames.size(); ++i) {
    max_error = std::max(max_error, r.frames[i].task_error);
    max_orientation = std::max(max_orientation, r.frames[i].orientation_error);
  }
  EXPECT_LT(max_error, 1e-4) << GetParam();
  EXPECT_LT(max_orientation, 1e-4) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Baselines, EveryBaseline, ::testing::ValuesIn(kBaselines));

TEST(Registry, ListsEveryBaselineWithValidDefaults) {
  for (const std::string& name : kBaselines) {
    const MethodInfo* info = find_method(name);
    ASSERT_NE(info, nullptr) << name;
    for (const ParamSpec& spec : info->params)
      EXPECT_EQ(param_problem(spec, spec.def), "") << name << "." << spec.name;
  }
  EXPECT_EQ(find_method("nope"), nullptr);
}

// Liégeois: the projected gradient is invisible at the end-effector.
TEST(Gpm, NullSpaceMotionMovesNoEndEffector) {
  json doc = four_link_circle();
  doc["robot"]["limits"] = {{"lower", {-3, -2, -2, -2}}, {"upper", {3, 2, 2, 2}}};
  doc["obstacles"] = {{{"shape", "sphere"}, {"center", {0.5, 0.6}}, {"radius", 0.1}}};
  for (const char* gradient : {"joint_range", "manipulability", "distance"}) {
    doc["method"] = {{"name", "gpm"}, {"params", {{"gradient", gradient}, {"gain", 5.0}}}};
    Simulator sim(parse_scenario(doc));
    const double largest_null = test::largest_null_space_motion(sim, 200, gradient);
    EXPECT_GT(largest_null, 1e-4) << gradient << ": the criterion should move the arm";
  }
}

// Damped least squares stays bounded where the pseudoinverse spikes: the target
// runs 0.1 m beyond the reach of a 3-link arm, which stretches to singularity.
TEST(Dls, StaysBoundedThroughASingularityWherePinvSpikes) {
  const std::vector<double> q0 = {0.3, 0.5, 0.5};
  const json doc = {{"dt", 0.01},
                    {"duration", 4.0},
                    {"robot", planar_robot(3, 1.0, 0.0, q0)},
                    {"task", {{"space", "xy"},
                              {"trajectory", {{"type", "polyline"},
                                              {"points", {planar_tip(1.0, q0), {3.1, 0.6}, {1.5, 0.3}}}}}}}};
  const auto pinv = run_scenario(doc, "pinv");
  const auto dls = run_scenario(doc, "dls", {{"lambda", 0.05}});
  double max_xdot = 0;  // bound of DLS: ‖q̇‖ ≤ ‖ẋ‖ / (2λ)
  for (const Frame& f : dls.frames) max_xdot = std::max(max_xdot, f.qdot.norm());
  EXPECT_GT(pinv.max_abs_qdot(), 100.0);
  EXPECT_LT(dls.max_abs_qdot(), 30.0);
  EXPECT_GT(pinv.max_abs_qdot(), 10 * dls.max_abs_qdot());
  EXPECT_EQ(dls.summary.nonfinite_steps, 0);
  EXPECT_LT(dls.summary.final_tracking_error, 1e-3);  // back on the path after the excursion
  std::cout << "[ singular ] pinv max |qdot| " << pinv.max_abs_qdot() << " rad/s, dls "
            << dls.max_abs_qdot() << " rad/s\n";
}

// Liégeois' joint-range gradient keeps the limits that minimum norm breaks
// while folding a 3-link arm towards its base.
TEST(Gpm, JointRangeGradientKeepsLimitsWherePinvViolatesThem) {
  const std::vector<double> q0 = {0, M_PI / 3, M_PI / 3};
  json doc = {{"dt", 0.01},
              {"duration", 4.0},
              {"robot", planar_robot(3, 1.0, 0.0, q0)},
              {"task", {{"space", "xy"},
                        {"trajectory", {{"type", "polyline"}, {"points", {planar_tip(1.0, q0), {0.9, 0.3}}}}}}}};
  const double lim = 110 * M_PI / 180;
  doc["robot"]["limits"] = {{"lower", {-M_PI, -lim, -lim}}, {"upper", {M_PI, lim, lim}}};
  const auto pinv = run_scenario(doc, "pinv");
  const auto gpm = run_scenario(doc, "gpm", {{"gradient", "joint_range"}, {"gain", 300.0}});
  EXPECT_TRUE(pinv.summary.joint_limit_violated);
  EXPECT_FALSE(gpm.summary.joint_limit_violated);
  EXPECT_GT(gpm.summary.min_joint_limit_margin, 0.05);
  EXPECT_LT(gpm.summary.final_tracking_error, 1e-4);
  std::cout << "[ limits ] min margin pinv " << pinv.summary.min_joint_limit_margin << " rad, gpm "
            << gpm.summary.min_joint_limit_margin << " rad\n";
}

// A point obstacle where minimum norm sweeps link 2 through it.
json obstacle_crossing() {
  const std::vector<double> q0 = {0.6, 0.3, 0.3, 0.3, 0.3};
  return {{"dt", 0.01},
          {"duration", 4.0},
          {"robot", planar_robot(5, 0.6, 0.05, q0)},
          {"obstacles", {{{"id", "pin"}, {"shape", "point"}, {"position", {0.976, -0.294}}}}},
          {"task", {{"space", "xy"},
                    {"trajectory", {{"type", "polyline"}, {"points", {planar_tip(0.6, q0), {2.2, -0.6}}}}}}}};
}

TEST(ObstacleAvoidance, TaskPriorityAndClosestPointKeepDistanceWherePinvCollides) {
  const json doc = obstacle_crossing();
  const auto pinv = run_scenario(doc, "pinv");
  EXPECT_TRUE(pinv.summary.collided);
  for (const char* method : {"task_priority", "closest_point"}) {
    const auto r = run_scenario(doc, method);
    EXPECT_FALSE(r.summary.collided) << method;
    EXPECT_GT(r.summary.min_distance, 0.1) << method;
    EXPECT_LT(r.summary.max_tracking_error, 1e-3) << method;
    std::cout << "[ obstacle ] " << method << " min distance " << r.summary.min_distance
              << " m (pinv " << pinv.summary.min_distance << " m)\n";
  }
}

// Defaults chosen on generated cases (seed 1001) hold on cases none was tuned
// on (seed 2001, 10 planar_limits cases, where pinv crosses a limit on every
// one by construction). Measured: gpm (joint_range, gain 200) holds the limits
// on 10 of 10, least margin 0.134 rad, tracking error at most 1.4 mm.
TEST(Defaults, GpmHoldsLimitsOnUntunedPlanarLimitsCases) {
  int pinv_crossed = 0, held = 0;
  for (int index = 0; index < 10; ++index) {
    const json doc = generate_scenario("planar_limits", json::object(), 2001, index);
    pinv_crossed += run_scenario(doc, "pinv").summary.joint_limit_violated;
    const auto gpm = run_scenario(doc, "gpm");
    std::cout << "[ defaults ] planar_limits 2001/" << index << " gpm min limit margin "
              << gpm.summary.min_joint_limit_margin << " rad, max tracking error " << gpm.summary.max_tracking_error
              << " m\n";
    held += !gpm.summary.joint_limit_violated && gpm.summary.max_tracking_error < 0.003;
  }
  EXPECT_EQ(pinv_crossed, 10);
  EXPECT_GE(held, 9);  // measured 10
}

// The obstacle-aware baselines with their defaults on untuned planar_clutter
// cases (seed 2001, 10 cases; two obstacles of each stand where pinv's
// arm passes, so pinv collides on every one). Before the secondary inverse was
// damped (secondary_lambda = 0) task_priority and closest_point lost the path
// by metres on most such cases (q̇ ~ 1e12 at J₂N₁ → 0). Measured, since two
// obstacles block pinv in every case: avoided with the path tracked within
// 1 cm on 10 (task_priority), 10 (closest_point) and 6 (sr_task_priority: two
// collisions, two errors past 1 cm; 61 % of the default suite's
// planar_clutter) of 10; with one blocking obstacle sr_task_priority had 8.
TEST(Defaults, ObstacleBaselinesAvoidWherePinvCollidesOnUntunedCases) {
  std::map<std::string, int> avoided;
  int pinv_collided = 0;
  for (int index = 0; index < 10; ++index) {
    const json doc = generate_scenario("planar_clutter", json::object(), 2001, index);
    pinv_collided += run_scenario(doc, "pinv").summary.collided;
    for (const char* method : {"task_priority", "closest_point", "sr_task_priority"}) {
      const auto r = run_scenario(doc, method);
      std::cout << "[ defaults ] planar_clutter 2001/" << index << " " << method << " min distance "
                << r.summary.min_distance << " m, max tracking error " << r.summary.max_tracking_error << " m\n";
      avoided[method] += !r.summary.collided && r.summary.max_tracking_error <= 0.01;
    }
  }
  EXPECT_EQ(pinv_collided, 10);
  EXPECT_GE(avoided["task_priority"], 9);
  EXPECT_GE(avoided["closest_point"], 9);
  EXPECT_GE(avoided["sr_task_priority"], 6);
}

TEST(SrTaskPriority, JointCentringLeavesTheTaskAlone) {
  json doc = four_link_circle();
  doc["robot"]["limits"] = {{"lower", {-3, -2, -2, -2}}, {"upper", {3, 2, 2, 2}}};
  const auto r = run_scenario(doc, "sr_task_priority", {{"secondary", "joint_centring"}, {"gain", 2.0}});
  EXPECT_LT(r.max_error_after(100), 2e-4);
}

TEST(Methods, ParametersChangeBetweenSteps) {
  Simulator sim(parse_scenario(four_link_circle()));
  sim.switch_method("dls");
  sim.set_param("lambda", 0.2);
  EXPECT_DOUBLE_EQ(sim.method().param("lambda"), 0.2);
  sim.step();
  EXPECT_DOUBLE_EQ(sim.frame().diagnostics[0], 0.2);  // the damping used by that step
  sim.set_param("lambda", 0.0);
  sim.step();
  EXPECT_DOUBLE_EQ(sim.frame().diagnostics[0], 0.0);
  EXPECT_THROW(sim.set_param("lambda", -1.0), ParamError);
  EXPECT_THROW(sim.set_param("bogus", 1.0), ParamError);
  EXPECT_THROW(sim.set_param("damping", 2.0), ParamError);
}

}  // namespace
}  // namespace rrlab
