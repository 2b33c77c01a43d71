#include <rrlab/task/task.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rrlab {
namespace {

TEST(Task, ReferenceIsFeedForwardPlusGainTimesError) {
  TaskSpec spec;
  spec.space = TaskSpace::xy;
  spec.gain = 10.0;
  spec.trajectory.type = TrajectoryType::polyline;
  spec.trajectory.points = {{0, 0, 0}, {1, 0, 0}};
  Eigen::Isometry3d ee = Eigen::Isometry3d::Identity();
  const Task task(spec, ee, 1.0, 0.01);
  ee.translation() = Eigen::Vector3d(0.5, 0.1, 0);
  TaskRef ref(TaskSpace::xy);
  task.reference(0.5, ee, ref);
  EXPECT_NEAR(ref.error[0], 0.0, 1e-12);
  EXPECT_NEAR(ref.error[1], -0.1, 1e-12);
  EXPECT_NEAR(ref.xdot_ff[0], 1.0, 1e-9);
  EXPECT_NEAR(ref.xdot[1], -1.0, 1e-12);
  EXPECT_NEAR(ref.position_error, 0.1, 1e-12);
}

TEST(Task, DefaultGainIsStableForLargeSteps) {
  EXPECT_DOUBLE_EQ(default_task_gain(0.001), 20.0);
  EXPECT_DOUBLE_EQ(default_task_gain(0.1), 5.0);
}

TEST(Task, PoseErrorIncludesOrientation) {
  TaskSpec spec;
  spec.space = TaskSpace::pose;
  spec.trajectory.type = TrajectoryType::joystick;
  spec.orientation = Eigen::Matrix3d(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()));
  const Eigen::Isometry3d ee = Eigen::Isometry3d::Identity();
  const Task task(spec, ee, 1.0, 0.01);
  TaskRef ref(TaskSpace::pose);
  task.reference(0, ee, ref);
  EXPECT_NEAR(ref.error[5], 0.2, 1e-12);
  EXPECT_NEAR(ref.orientation_error, 0.2, 1e-12);
}

TEST(Task, JoystickIntegratesVelocityCommands) {
  TaskSpec spec;
  spec.space = TaskSpace::xy;
  spec.trajectory.type = TrajectoryType::joystick;
  Eigen::Isometry3d ee = Eigen::Isometry3d::Identity();
  ee.translation() = Eigen::Vector3d(1, 2, 0);
  Task task(spec, ee, 1.0, 0.1);
  task.set_joystick({0.5, 0, 0}, Eigen::Vector3d::Zero());
  for (int i = 0; i < 10; ++i) task.advance();
  EXPECT_LT((task.target_position(1.0) - Eigen::Vector3d(1.5, 2, 0)).norm(), 1e-12);
  TaskRef ref(TaskSpace::xy);
  task.reference(1.0, ee, ref);
  EXPECT_NEAR(ref.xdot_ff[0], 0.5, 1e-12);
}

TEST(Task, OrientationErrorFromSkewMatchesTheQuaternionRoute) {
  // seeded rotations R_desired, and R_actual = R_desired turned back by an
  // angle from 1e-12 rad to π about a random axis: the series (< 1e-4), the
  // atan2 (< 90°) and the quaternion route (beyond) give the same rotation
  // vector to a few ε of its angle's scale
  std::mt19937 rng(11);
  std::normal_distribution<double> gauss;
  const auto random_axis = [&] { return Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized(); };
  int cases = 0;
  for (double angle : {0.0, 1e-12, 1e-9, 3e-7, 1e-5, 9.9e-5, 1.01e-4, 1e-3, 0.1, 1.0, 1.5, 1.5707, 1.5709, 2.5, 3.14159}) {
    for (int k = 0; k < 40; ++k, ++cases) {
      const Eigen::Matrix3d desired = Eigen::AngleAxisd(3.0 * gauss(rng), random_axis()).toRotationMatrix();
      const Eigen::Vector3d axis = random_axis();
      const Eigen::Matrix3d actual = Eigen::AngleAxisd(-angle, axis).toRotationMatrix() * desired;
      const Eigen::Vector3d reference = orientation_error(desired, actual);
      const Eigen::Vector3d skew = orientation_error_from_skew(desired, actual);
      EXPECT_LT((skew - reference).norm(), 8e-16 * std::max(1.0, angle)) << "angle " << angle;
      EXPECT_LT((skew - angle * axis).norm(), 4e-15) << "angle " << angle;
    }
  }
  EXPECT_EQ(cases, 600);
  EXPECT_EQ(orientation_error_from_skew(Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()),
            Eigen::Vector3d::Zero());
  const Eigen::Matrix3d broken = Eigen::Matrix3d::Constant(std::nan(""));
  EXPECT_FALSE(orientation_error_from_skew(Eigen::Matrix3d::Identity(), broken).allFinite());
}

}  // namespace
}  // namespace rrlab
