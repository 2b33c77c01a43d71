// diffik: the commanded task velocity is scaled by α ∈ [0, 1], never bent:
// J q̇ = α v at every step, checked here against the simulator's own J and v.
#include <gtest/gtest.h>

#include "engine/methods/velocity_method_scenarios.hpp"

namespace rrlab {
namespace {

struct DirectionStats {
  double largest_alpha = 0, smallest_alpha = 1, largest_bend = 0, largest_residual = 0;
  int kept = 0, steps = 0;
};

// Steps `doc` with `method`; after each step from `from` on compares the hand
// velocity J q̇ with the commanded v of the same step. The bend is 1 − cos(J q̇, v).
DirectionStats direction_stats(nlohmann::json doc, const std::string& method, long from = 0) {
  doc["method"] = {{"name", method}};
  Simulator sim(parse_scenario(doc));
  const std::vector<std::string>& names = sim.diagnostic_names();
  const auto alpha_at = std::find(names.begin(), names.end(), "alpha");
  const auto kept_at = std::find(names.begin(), names.end(), "direction_kept");
  DirectionStats s;
  while (!sim.done()) {
    sim.step();
    if (sim.frame().step < from) continue;
    const Eigen::VectorXd hand = sim.task_jacobian() * sim.frame().qdot;
    const Eigen::VectorXd& v = sim.reference().xdot;
    if (hand.norm() > 1e-9 && v.norm() > 1e-9) s.largest_bend = std::max(s.largest_bend, 1 - hand.dot(v) / (hand.norm() * v.norm()));
    ++s.steps;
    if (alpha_at == names.end()) continue;
    const double alpha = sim.frame().diagnostics[alpha_at - names.begin()];
    s.largest_alpha = std::max(s.largest_alpha, alpha);
    s.smallest_alpha = std::min(s.smallest_alpha, alpha);
    s.largest_residual = std::max(s.largest_residual, (hand - alpha * v).norm() / (1 + v.norm()));
    s.kept += sim.frame().diagnostics[kept_at - names.begin()] == 1;
  }
  return s;
}

// Once the start's offset from the circle is made up (the step cap scales the
// first steps' K·e down: α 0.37 at the first step)
TEST(DiffIk, TracksWithAlphaOneWhereNothingBinds) {
  const DirectionStats s = direction_stats(test::circle_at_speed(0), "diffik", 100);
  EXPECT_GT(s.smallest_alpha, 1 - 1e-9);
  EXPECT_LE(s.largest_alpha, 1.0);
  EXPECT_EQ(s.kept, s.steps);
  const test::CheckedRun r = test::checked_run(test::circle_at_speed(0), "diffik");
  double late = 0;
  for (size_t i = 100; i < r.frames.size(); ++i) late = std::max(late, r.frames[i].task_error);
  EXPECT_LT(late, 1e-4);
}

// Joints limited to 0.3 rad/s cannot follow the circle: α drops below 1 and
// the hand slows along v (J q̇ = α v to rounding), where qp_ik bends it.
TEST(DiffIk, SlowsAlongTheCommandedDirectionWhenTheLimitsBind) {
  const DirectionStats s = direction_stats(test::circle_at_speed(0.3), "diffik");
  EXPECT_LT(s.smallest_alpha, 0.9);
  EXPECT_GE(s.smallest_alpha, 0.0);
  EXPECT_LE(s.largest_alpha, 1.0);
  EXPECT_EQ(s.kept, s.steps);
  EXPECT_LT(s.largest_residual, 1e-9);
  EXPECT_LT(s.largest_bend, 1e-9);
  const DirectionStats weighted = direction_stats(test::circle_at_speed(0.3), "qp_ik");
  EXPECT_GT(weighted.largest_bend, 1e-3);
  // and it never passes a velocity limit doing so
  const test::CheckedRun r = test::checked_run(test::circle_at_speed(0.3), "diffik");
  ASSERT_TRUE(r.summary.max_qdot_ratio);
  EXPECT_LE(*r.summary.max_qdot_ratio, 1.0);
}

}  // namespace
}  // namespace rrlab
