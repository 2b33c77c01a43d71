#include "task/task.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace rrlab
