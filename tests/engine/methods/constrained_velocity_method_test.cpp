// What qp_ik, hqp and diffik share (constrained_velocity_method.cpp over
// velocity_constraints.cpp): where the constraints can be met, no collision
// with an obstacle or of the arm with itself and no joint past its limit, at
// every step and after the last integration; the dampers drawn while active;
// parameters checked; runs that repeat after a reset. And issue 40's
// acceptance check on generated cases of a seed no default was chosen on.
#include <gtest/gtest.h>

#include <rrlab/generators/generators.hpp>
#include <rrlab/methods/registry.hpp>

#include "engine/methods/velocity_method_scenarios.hpp"

namespace rrlab {
namespace {

using nlohmann::json;

class VelocityMethods : public ::testing::TestWithParam<std::string> {};

TEST_P(VelocityMethods, KeepTheSafetyDistanceFromAPostPinvHits) {
  ASSERT_TRUE(test::checked_run(test::post_in_the_way(), "pinv").summary.obstacle_collided);
  const test::CheckedRun r = test::checked_run(test::post_in_the_way(), GetParam());
  EXPECT_TRUE(r.safe()) << GetParam();
  EXPECT_GT(r.min_distance, 0.01 - 1e-3) << GetParam();  // d_s = 0.01 m, to the linearisation's error
  EXPECT_LT(r.summary.max_tracking_error, 1e-3) << GetParam();  // the arm goes round the post: 5e-5 to 8e-5 m
  // the damper on link 3 is active and drawn while the arm passes
  int drawn = 0;
  for (size_t i = 0; i < r.frames.size(); ++i)
    if (r.diag(i, "active_dampers") > 0) drawn += !r.frames[i].overlays.segments.empty();
  EXPECT_GT(drawn, 10) << GetParam();
}

TEST_P(VelocityMethods, KeepTheLinksApartWhenTheHandIsAskedOntoTheBase) {
  ASSERT_TRUE(test::checked_run(test::folding_onto_itself(), "pinv").summary.self_collided);
  const test::CheckedRun r = test::checked_run(test::folding_onto_itself(), GetParam());
  EXPECT_TRUE(r.safe()) << GetParam();
  EXPECT_GT(r.min_self_distance, 0.01 - 1e-3) << GetParam();
  // without the self pairs' dampers the arm folds into itself as pinv does
  EXPECT_TRUE(test::checked_run(test::folding_onto_itself(), GetParam(), {{"self_pairs", "off"}}).summary.self_collided)
      << GetParam();
}

TEST_P(VelocityMethods, NeverCrossAJointLimitEvenWhenTheTargetLiesBeyond) {
  ASSERT_TRUE(test::checked_run(test::target_past_the_limits(), "pinv").summary.joint_limit_violated);
  for (double gain : {0.1, 0.5, 1.0}) {
    const test::CheckedRun r = test::checked_run(test::target_past_the_limits(), GetParam(), {{"position_gain", gain}});
    EXPECT_EQ(r.limit_crossed_states, 0) << GetParam() << " γ = " << gain;
    EXPECT_FALSE(r.summary.joint_limit_violated);
    EXPECT_EQ(r.summary.nonfinite_steps, 0);
  }
}

// Infeasible dampers: each row gives way by its least violation (level 1),
// reported, and the box (here the velocity limits) still holds.
TEST_P(VelocityMethods, GiveWayByTheLeastViolationWhenADamperCannotHold) {
  const test::CheckedRun r = test::checked_run(test::ball_faster_than_the_arm(), GetParam());
  const size_t last = r.frames.size() - 1;
  EXPECT_GT(r.diag(last, "relaxed_steps"), 5) << GetParam();  // 21 to 24 steps
  double largest_slack = 0;
  for (size_t i = 0; i < r.frames.size(); ++i) largest_slack = std::max(largest_slack, r.diag(i, "damper_slack"));
  EXPECT_GT(largest_slack, 0.1) << GetParam();
  EXPECT_EQ(r.summary.nonfinite_steps, 0);
  ASSERT_TRUE(r.summary.max_qdot_ratio);
  EXPECT_LE(*r.summary.max_qdot_ratio, 1.0) << GetParam();
}

TEST_P(VelocityMethods, RepeatAfterAReset) {
  json doc = test::post_in_the_way();
  doc["method"] = {{"name", GetParam()}};
  Simulator sim(parse_scenario(doc));
  test::expect_repeats_after_reset(sim);
}

TEST_P(VelocityMethods, RefuseADetectionDistanceInsideTheSafetyDistance) {
  const MethodInfo* info = find_method(GetParam());
  ASSERT_NE(info, nullptr);
  for (const ParamSpec& spec : info->params) EXPECT_EQ(param_problem(spec, spec.def), "") << spec.name;
  const Model model = make_planar({{0.5, 0.02}, {0.5, 0.02}, {0.5, 0.02}}, Eigen::Vector2d::Zero());
  auto method = info->make({model, TaskSpace::xy, 1});
  try {
    method->set_param("safety_distance", 0.5);
    FAIL() << "accepted d_s above d_i";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.param(), "safety_distance");
    EXPECT_NE(std::string(e.what()).find("must exceed"), std::string::npos) << e.what();
  }
  EXPECT_EQ(method->param("safety_distance"), 0.01);  // the previous value stays
  EXPECT_THROW(method->set_param("detection_distance", 0.005), ParamError);
  EXPECT_EQ(method->param("detection_distance"), 0.08);
  method->set_param("detection_distance", 0.2);
  method->set_param("safety_distance", 0.1);  // valid together
  EXPECT_THROW(method->set_param("damper_gain", -1.0), ParamError);
}

INSTANTIATE_TEST_SUITE_P(ModernBaselines, VelocityMethods, ::testing::Values("qp_ik", "hqp", "diffik"));

// Issue 40's check: on 20 planar_clutter and 20 planar_limits cases of seed
// 6161 (generator defaults; the defaults were chosen on seed 5150, the
// benchmark suites use seeds 1 and 4242), hqp never collides (obstacle or
// self) or crosses a limit, qp_ik and diffik at most once in the 40 runs, and
// each tracks within 1 cm on at least 20 of the 40. Measured: no collision and
// no limit crossed by any of the three; tracked within 1 cm qp_ik 40, hqp 39,
// diffik 39 of 40.
TEST(ModernBaselinesAtScale, Issue40AcceptanceOnAnUnseenSeed) {
  std::vector<json> cases;
  for (const char* family : {"planar_clutter", "planar_limits"})
    for (int index = 0; index < 20; ++index) cases.push_back(generate_scenario(family, json::object(), 6161, index));
  for (const char* method : {"qp_ik", "hqp", "diffik"}) {
    int unsafe = 0, tracked = 0;
    for (const json& doc : cases) {
      const test::CheckedRun r = test::checked_run(doc, method);
      if (!r.safe()) {
        ++unsafe;
        std::cout << "[ issue 40 ] " << method << " " << doc["name"].get<std::string>() << ": collided states "
                  << r.collided_states << ", self " << r.self_collided_states << ", past a limit "
                  << r.limit_crossed_states << "\n";
      }
      tracked += r.summary.max_tracking_error <= 0.01;
    }
    std::cout << "[ issue 40 ] " << method << ": unsafe " << unsafe << " of 40, tracked within 1 cm " << tracked
              << " of 40\n";
    EXPECT_LE(unsafe, std::string(method) == "hqp" ? 0 : 1) << method;
    EXPECT_GE(tracked, 20) << method;
  }
}

}  // namespace
}  // namespace rrlab
