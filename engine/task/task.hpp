// The end-effector task: a trajectory in a task space, turned each step into
// the commanded task velocity ẋ = ẋ_ff + K·e (closed-loop inverse kinematics).
#pragma once

#include <Eigen/Geometry>
#include <optional>

#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/task/trajectory.hpp>

namespace rrlab {

struct TaskSpec {
  TaskSpace space = TaskSpace::xy;
  std::optional<double> gain;                // K in 1/s; default: default_task_gain(dt)
  TrajectorySpec trajectory;
  std::optional<Eigen::Matrix3d> orientation;  // pose tasks: fixed target; default: initial
};

// Default closed-loop gain: 20 1/s, capped at 0.5/dt so the discrete loop
// e_{k+1} = (1 − K·dt)·e_k converges without overshoot at any step size.
double default_task_gain(double dt);

struct TaskRef {
  explicit TaskRef(TaskSpace space);
  TaskSpace space;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();     // desired at t
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
  Eigen::VectorXd xdot_ff;  // feed-forward task velocity over [t, t + dt]
  Eigen::VectorXd error;    // desired − actual (orientation rows: rotation vector)
  Eigen::VectorXd xdot;     // commanded: xdot_ff + gain · error
  double position_error = 0;     // norm of the position rows of error
  double orientation_error = 0;  // rad (pose tasks)
};

class Task {
 public:
  Task(const TaskSpec& spec, const Eigen::Isometry3d& initial_ee, double duration, double dt);

  // Reference at time t for an end-effector at `ee`.
  void reference(double t, const Eigen::Isometry3d& ee, TaskRef& out) const;
  // Desired pose at time t, without feedback.
  Eigen::Vector3d target_position(double t) const;
  // Joystick: velocity command held until the next one; advance() integrates it.
  void set_joystick(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular);
  void advance();

  TaskSpace space() const { return spec_.space; }
  int rows() const { return task_rows(spec_.space); }
  double gain() const { return gain_; }
  void set_gain(double gain) { gain_ = gain; }
  bool is_joystick() const { return trajectory_.is_joystick(); }
  // Length of the trajectory in time (the scenario's duration): previews and plans stop there.
  double duration() const { return trajectory_.duration(); }
  const Eigen::Vector3d& joystick_linear() const { return joy_linear_; }

 private:
  TaskSpec spec_;
  Trajectory trajectory_;
  double dt_, gain_;
  Eigen::Matrix3d target_orientation_;
  Eigen::Vector3d joy_position_, joy_linear_ = Eigen::Vector3d::Zero(),
                                 joy_angular_ = Eigen::Vector3d::Zero();
};

// Rotation vector (axis · angle) of R_desired · R_actualᵀ.
Eigen::Vector3d orientation_error(const Eigen::Matrix3d& desired, const Eigen::Matrix3d& actual);
// The same rotation vector from the skew part of R = R_desired · R_actualᵀ,
// sin θ · axis, without the quaternion: θ/sin θ by its series for sin θ
// below 1e-4 (no atan2; an iteration's errors near convergence), by atan2
// up to 90°, and beyond 90° (where sin θ loses the angle) orientation_error
// itself. Both are accurate to a few ε absolute; they differ in rounding.
Eigen::Vector3d orientation_error_from_skew(const Eigen::Matrix3d& desired, const Eigen::Matrix3d& actual);

}  // namespace rrlab
