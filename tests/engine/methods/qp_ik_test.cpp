// qp_ik: the task is a weighted cost beside the posture and the
// Levenberg–Marquardt damping, so it tracks where nothing binds and gives way
// (instead of failing) where the weights or constraints say so.
#include <gtest/gtest.h>

#include "engine/methods/velocity_method_scenarios.hpp"

namespace rrlab {
namespace {

// The largest tracking error once the start's offset (0.5 m from the circle) is made up.
double error_after_the_start(const test::CheckedRun& r) {
  double late = 0;
  for (size_t i = 100; i < r.frames.size(); ++i) late = std::max(late, r.frames[i].task_error);
  return late;
}

TEST(QpIk, TracksACircleWhereNothingBinds) {
  const test::CheckedRun r = test::checked_run(test::circle_at_speed(0), "qp_ik");
  EXPECT_LT(error_after_the_start(r), 1e-3);  // the low-weight posture task costs a little accuracy
  EXPECT_EQ(r.summary.nonfinite_steps, 0);
  for (size_t i = 0; i < r.frames.size(); ++i) ASSERT_EQ(r.diag(i, "damper_rows"), 0) << i;
}

// λ = λ_0 + μ‖e‖², reported every step.
TEST(QpIk, DampsInProportionToTheSquaredTaskError) {
  const nlohmann::json params = {{"damping", 0.002}, {"lm_damping", 3.0}};
  const test::CheckedRun r = test::checked_run(test::target_past_the_limits(), "qp_ik", params);
  for (size_t i = 0; i + 1 < r.frames.size(); ++i) {
    const double e = r.frames[i].task_error;
    ASSERT_NEAR(r.diag(i, "lm_damping"), 0.002 + 3.0 * e * e, 1e-12) << i;
  }
  EXPECT_GT(r.summary.final_tracking_error, 0.1);  // the target lies beyond the limits
}

// The task is soft: a heavy posture task pulls the hand off the path, which
// hqp's strict hierarchy never lets it do (hqp_test.cpp).
TEST(QpIk, AHeavyPostureWeightTradesTaskAccuracy) {
  const test::CheckedRun light = test::checked_run(test::circle_at_speed(0), "qp_ik");
  const test::CheckedRun heavy =
      test::checked_run(test::circle_at_speed(0), "qp_ik", {{"posture_weight", 1.0}, {"rest", "start"}});
  EXPECT_GT(error_after_the_start(heavy), 5 * error_after_the_start(light));
  double residual = 0;
  for (size_t i = 0; i < heavy.frames.size(); ++i) residual = std::max(residual, heavy.diag(i, "task_residual"));
  EXPECT_GT(residual, 1e-3);
}

}  // namespace
}  // namespace rrlab
