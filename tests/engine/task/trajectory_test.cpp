#include <rrlab/task/trajectory.hpp>

#include <gtest/gtest.h>

namespace rrlab {
namespace {

TrajectorySpec polyline(TimeLaw law) {
  TrajectorySpec s;
  s.type = TrajectoryType::polyline;
  s.time_law = law;
  s.points = {{0, 0, 0}, {3, 0, 0}, {3, 1, 0}};  // lengths 3 and 1
  return s;
}

TEST(Polyline, LinearLawHasConstantSpeedOverThePath) {
  const Trajectory t(polyline(TimeLaw::linear), Eigen::Vector3d::Zero(), 4.0);
  EXPECT_LT((t.position(0) - Eigen::Vector3d(0, 0, 0)).norm(), 1e-12);
  EXPECT_LT((t.position(1) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((t.position(3.5) - Eigen::Vector3d(3, 0.5, 0)).norm(), 1e-12);
  EXPECT_LT((t.position(10) - Eigen::Vector3d(3, 1, 0)).norm(), 1e-12);  // held at the end
}

TEST(Polyline, QuinticLawIsRestToRestPerSegment) {
  const Trajectory t(polyline(TimeLaw::quintic), Eigen::Vector3d::Zero(), 4.0);  // 3 s + 1 s
  EXPECT_LT((t.position(1.5) - Eigen::Vector3d(1.5, 0, 0)).norm(), 1e-12);      // midpoint by symmetry
  EXPECT_LT((t.position(3.0) - Eigen::Vector3d(3, 0, 0)).norm(), 1e-12);
  const double h = 1e-5;  // zero velocity at the knot
  EXPECT_LT((t.position(3.0 + h) - t.position(3.0 - h)).norm() / (2 * h), 1e-4);
}

TEST(Polyline, ExplicitDurations) {
  TrajectorySpec s = polyline(TimeLaw::linear);
  s.durations = {1.0, 3.0};
  const Trajectory t(s, Eigen::Vector3d::Zero(), 4.0);
  EXPECT_LT((t.position(0.5) - Eigen::Vector3d(1.5, 0, 0)).norm(), 1e-12);
  EXPECT_LT((t.position(2.5) - Eigen::Vector3d(3, 0.5, 0)).norm(), 1e-12);
}

TEST(Circle, StartsAtTheInitialAngleAndTurnsCounterClockwise) {
  TrajectorySpec s;
  s.type = TrajectoryType::circle;
  s.center = {1.8, 0, 0};
  s.radius = 0.6;
  const Trajectory t(s, Eigen::Vector3d(1.8, -0.5, 0), 8.0);  // start angle −90°
  EXPECT_LT((t.position(0) - Eigen::Vector3d(1.8, -0.6, 0)).norm(), 1e-12);
  EXPECT_LT((t.position(2) - Eigen::Vector3d(2.4, 0, 0)).norm(), 1e-12);
  EXPECT_LT((t.position(8) - Eigen::Vector3d(1.8, -0.6, 0)).norm(), 1e-12);
}

TEST(Circle, ClockwiseWithGivenStartAngleAndNormal) {
  TrajectorySpec s;
  s.type = TrajectoryType::circle;
  s.center = {0, 0, 1};
  s.radius = 0.5;
  s.start_angle = 0.0;
  s.clockwise = true;
  s.normal = {1, 0, 0};  // plane y–z, angles from +y
  const Trajectory t(s, Eigen::Vector3d::Zero(), 4.0);
  EXPECT_LT((t.position(0) - Eigen::Vector3d(0, 0.5, 1)).norm(), 1e-12);
  EXPECT_LT((t.position(1) - Eigen::Vector3d(0, 0, 0.5)).norm(), 1e-12);  // −90° about +x
}

TEST(Ellipse, SemiAxes) {
  TrajectorySpec s;
  s.type = TrajectoryType::ellipse;
  s.center = {0, 0, 0};
  s.semi_axes = {2.0, 1.0};
  s.start_angle = 0.0;
  const Trajectory t(s, Eigen::Vector3d::Zero(), 4.0);
  EXPECT_LT((t.position(0) - Eigen::Vector3d(2, 0, 0)).norm(), 1e-12);
  EXPECT_LT((t.position(1) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
}

TEST(TimeLaw, QuinticEndpoints) {
  EXPECT_DOUBLE_EQ(time_law_progress(TimeLaw::quintic, 0), 0);
  EXPECT_DOUBLE_EQ(time_law_progress(TimeLaw::quintic, 1), 1);
  EXPECT_DOUBLE_EQ(time_law_progress(TimeLaw::quintic, 0.5), 0.5);
}

}  // namespace
}  // namespace rrlab
