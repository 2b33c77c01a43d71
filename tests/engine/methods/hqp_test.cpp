// hqp: strict priority. The task (level 2) keeps its optimal residual
// whatever the posture (level 3) asks, and the hard constraints (level 1)
// hold whatever the task asks.
#include <gtest/gtest.h>

#include "engine/methods/velocity_method_scenarios.hpp"

namespace rrlab {
namespace {

double largest(const test::CheckedRun& r, const std::string& diagnostic) {
  double m = 0;
  for (size_t i = 0; i < r.frames.size(); ++i) m = std::max(m, r.diag(i, diagnostic));
  return m;
}

// The level-2 residual after level 3 equals level 2's own at every step
// (priority_loss), however heavy the posture: the circle is tracked as
// without it, where qp_ik's weighted sum gives way (qp_ik_test.cpp).
TEST(Hqp, ThePostureNeverDegradesTheTask) {
  const test::CheckedRun plain = test::checked_run(test::circle_at_speed(0), "hqp");
  for (double weight : {1e-3, 1.0, 1e3}) {
    const test::CheckedRun r =
        test::checked_run(test::circle_at_speed(0), "hqp", {{"posture_weight", weight}, {"rest", "start"}});
    EXPECT_LT(largest(r, "priority_loss"), 1e-9) << weight;
    for (size_t i = 0; i < r.frames.size(); ++i) ASSERT_EQ(r.diag(i, "levels_solved"), 3) << i;
    double late = 0;
    for (size_t i = 100; i < r.frames.size(); ++i) late = std::max(late, r.frames[i].task_error);
    EXPECT_LT(late, 1e-4) << weight;
    EXPECT_NEAR(r.summary.max_tracking_error, plain.summary.max_tracking_error, 1e-4) << weight;
  }
}

// Where the task cannot be met (a target past the limits, a post in the
// way), level 2 is a least-squares residual (task_slack > 0) and level 3
// still does not grow it; level 1 holds throughout.
TEST(Hqp, AnInfeasibleTaskKeepsItsLeastSquaresResidual) {
  const test::CheckedRun limits = test::checked_run(test::target_past_the_limits(), "hqp", {{"posture_weight", 10.0}});
  EXPECT_GT(largest(limits, "task_slack"), 0.1);
  EXPECT_LT(largest(limits, "priority_loss"), 1e-9);
  EXPECT_TRUE(limits.safe());
  const test::CheckedRun post = test::checked_run(test::post_in_the_way(), "hqp", {{"posture_weight", 10.0}});
  EXPECT_LT(largest(post, "priority_loss"), 1e-9);
  EXPECT_TRUE(post.safe());
}

}  // namespace
}  // namespace rrlab
