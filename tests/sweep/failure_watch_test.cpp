// A failed run's first failure mode and its time, watched frame by frame.
#include <rrlab/sweep/failure_watch.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <tuple>
#include <utility>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab::sweep {
namespace {

// A 3-link planar arm (reach 3 m) whose hand, at (2.866, 0.296), starts on a
// circle of `radius` whose centre lies `radius` to its -x side.
Scenario watched_arm(double radius, const nlohmann::json& obstacles = nlohmann::json::array()) {
  nlohmann::json doc = {
      {"dt", 0.01},
      {"duration", 3.0},
      {"robot", {{"kind", "planar"}, {"links", {{{"length", 1.0}}, {{"length", 1.0}}, {{"length", 1.0}}}},
                 {"q0", {0.3, -0.6, 0.6}}}},
      {"task", {{"trajectory", {{"type", "circle"}, {"center", {2.8663 - radius, 0.29552}}, {"radius", radius}}}}}};
  if (!obstacles.empty()) doc["obstacles"] = obstacles;
  return parse_scenario(doc);
}

SuccessCriteria usual() {
  SuccessCriteria c;
  c.max_tracking_error = 0.01;
  return c;
}

std::optional<FirstFailure> watch_run(const Scenario& sc, const SuccessCriteria& criteria) {
  Simulator sim(sc);
  FailureWatch watch(criteria);
  const Summary summary = run_to_end(sim, &watch);
  return watch.first(judge_success(criteria, summary));
}

TEST(FailureWatch, APassingRunHasNone) {
  const Scenario sc = watched_arm(0.3);
  EXPECT_FALSE(watch_run(sc, usual()));
}

TEST(FailureWatch, AnObstacleOnTheArmAtTheStartIsACollisionAtZero) {
  const Scenario sc = watched_arm(0.3, {{{"shape", "sphere"}, {"center", {0.5, 0.15}}, {"radius", 0.2}}});
  const std::optional<FirstFailure> f = watch_run(sc, usual());
  ASSERT_TRUE(f);
  EXPECT_EQ(f->mode, "collision");
  EXPECT_EQ(f->t, 0.0);
}

TEST(FailureWatch, APathBeyondReachIsLostWhereTheErrorPassesTheCriterion) {
  const Scenario sc = watched_arm(5.0);  // reaches 7 m from the base
  Simulator sim(sc);
  FailureWatch watch(usual());
  double first_over = -1;
  sim.set_total_steps(sim.total_steps());
  watch.begin(sim);
  while (!sim.done()) {
    sim.step();
    if (first_over < 0 && sim.frame().task_error > 0.01) first_over = sim.frame().t;
    watch.frame(sim.frame());
  }
  const Summary summary = sim.summary();
  watch.end(summary);
  const std::optional<FirstFailure> f = watch.first(judge_success(usual(), summary));
  ASSERT_TRUE(f);
  ASSERT_GE(first_over, 0);
  // lost, or stalled earlier at the edge of the workspace: never later than the error
  EXPECT_TRUE(f->mode == "tracking_lost" || f->mode == "stalled") << f->mode;
  EXPECT_LE(f->t, first_over);
}

// A hand that follows the reference for 2 s and then stops: a stall from 2 s,
// seen once it has lasted 1 s (without a tracking criterion nothing else fails).
TEST(FailureWatch, AHandThatStopsWhileThePathGoesOnStalls) {
  const Scenario sc = watched_arm(0.3);
  Simulator sim(sc);
  SuccessCriteria criteria;
  criteria.max_final_tracking_error = 0.01;
  FailureWatch watch(criteria);
  watch.begin(sim);
  Frame f = sim.frame();
  for (long k = 0; k < 300; ++k) {
    f.step = k;
    f.t = 0.01 * double(k);
    f.target = Eigen::Vector3d(0.1 * f.t, 0, 0);
    f.ee_position = Eigen::Vector3d(0.1 * std::min(f.t, 2.0), 0, 0);
    f.task_error = (f.target - f.ee_position).norm();
    f.min_distance = std::numeric_limits<double>::infinity();
    f.collided = false;
    f.joint_limit_margin = std::numeric_limits<double>::infinity();
    watch.frame(f);
  }
  Summary summary;
  summary.final_tracking_error = 0.1 * 0.99;
  watch.end(summary);
  const std::optional<FirstFailure> failure = watch.first(false);
  ASSERT_TRUE(failure);
  EXPECT_EQ(failure->mode, "stalled") << failure->t;
  EXPECT_NEAR(failure->t, 2.0, 0.02);
  EXPECT_FALSE(watch.first(true));  // a passing verdict names none
}

// Resting on the path while the reference rests (a rest-to-rest waypoint) is no stall.
TEST(FailureWatch, RestingWithTheReferenceIsNoStall) {
  const Scenario sc = watched_arm(0.3);
  Simulator sim(sc);
  SuccessCriteria criteria;
  FailureWatch watch(criteria);
  watch.begin(sim);
  Frame f = sim.frame();
  for (long k = 0; k < 300; ++k) {
    f.t = 0.01 * double(k);
    f.target = f.ee_position = Eigen::Vector3d(0.1 * std::min(f.t, 0.5), 0, 0);
    f.min_distance = std::numeric_limits<double>::infinity();
    f.joint_limit_margin = std::numeric_limits<double>::infinity();
    watch.frame(f);
  }
  watch.end(Summary{});
  EXPECT_EQ(watch.first(false)->mode, "other");  // a failed verdict nothing here explains
}

// A hand that starts 0.3 m off its path and reaches it within 1 s: lost
// without a settle time, held with one; a joint past its velocity limit is a
// joint_speed failure when the criteria hold speeds.
TEST(FailureWatch, ASettleTimeForgivesTheApproachAndJointSpeedsAreWatched) {
  nlohmann::json doc = {{"dt", 0.01},
                        {"duration", 3.0},
                        {"robot",
                         {{"kind", "planar"},
                          {"links", {{{"length", 1.0}}, {{"length", 1.0}}, {{"length", 1.0}}}},
                          {"q0", {0.3, -0.6, 0.6}},
                          {"limits", {{"velocity", {0.5, 0.5, 0.5}}}}}},
                        {"task", {{"trajectory", {{"type", "circle"}, {"center", {2.3663, 0.29552}}, {"radius", 0.3}}}}}};
  const Scenario sc = parse_scenario(doc);
  const auto run = [&](const SuccessCriteria& criteria, Frame (*edit)(Frame)) {
    Simulator sim(sc);
    FailureWatch watch(criteria);
    watch.begin(sim);
    Frame f = sim.frame();
    double qdot_ratio = 0;  // as the summary has it
    for (long k = 0; k < 300; ++k) {
      f.step = k;
      f.t = 0.01 * double(k);
      f.task_error = f.t < 1.0 ? 0.3 * (1.0 - f.t) : 0.001;
      f.min_distance = std::numeric_limits<double>::infinity();
      f.collided = false;
      f.joint_limit_margin = std::numeric_limits<double>::infinity();
      f.target = f.ee_position = Eigen::Vector3d(0.01 * f.t, 0, 0);
      f.qdot = Eigen::Vector3d(0.1, 0.2, 0.3);
      const Frame edited = edit(f);
      qdot_ratio = std::max(qdot_ratio, edited.qdot.cwiseAbs().maxCoeff() / 0.5);
      watch.frame(edited);
    }
    Summary summary;
    summary.max_tracking_error = 0.3;
    summary.max_qdot_ratio = qdot_ratio;
    watch.end(summary);
    const bool passed = judge_success(criteria, summary) && watch.tracking_held();
    return std::make_pair(passed, watch.first(passed));
  };
  const auto as_is = [](Frame f) { return f; };
  SuccessCriteria criteria;
  criteria.max_tracking_error = 0.01;
  auto [passed, failure] = run(criteria, as_is);
  EXPECT_FALSE(passed);
  ASSERT_TRUE(failure);
  EXPECT_EQ(failure->mode, "tracking_lost");
  EXPECT_EQ(failure->t, 0.0);
  criteria.settle_time = 1.5;
  std::tie(passed, failure) = run(criteria, as_is);
  EXPECT_TRUE(passed);
  EXPECT_FALSE(failure);
  // lost again at 2 s, after the settle time
  std::tie(passed, failure) = run(criteria, [](Frame f) {
    if (f.t >= 2.0) f.task_error = 0.05;
    return f;
  });
  EXPECT_FALSE(passed);
  ASSERT_TRUE(failure);
  EXPECT_EQ(failure->mode, "tracking_lost");
  EXPECT_NEAR(failure->t, 2.0, 1e-9);
  // a joint at 0.6 rad/s against 0.5 from 2.5 s
  criteria.joint_speeds = true;
  std::tie(passed, failure) = run(criteria, [](Frame f) {
    if (f.t >= 2.5) f.qdot[1] = 0.6;
    return f;
  });
  EXPECT_FALSE(passed);
  ASSERT_TRUE(failure);
  EXPECT_EQ(failure->mode, "joint_speed");
  EXPECT_NEAR(failure->t, 2.5, 1e-9);
}

}  // namespace
}  // namespace rrlab::sweep
