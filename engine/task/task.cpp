#include <rrlab/task/task.hpp>

#include <algorithm>
#include <cmath>

namespace rrlab {

double default_task_gain(double dt) { return std::min(20.0, 0.5 / dt); }

TaskRef::TaskRef(TaskSpace s)
    : space(s),
      xdot_ff(Eigen::VectorXd::Zero(task_rows(s))),
      error(Eigen::VectorXd::Zero(task_rows(s))),
      xdot(Eigen::VectorXd::Zero(task_rows(s))) {}

Eigen::Vector3d orientation_error(const Eigen::Matrix3d& desired, const Eigen::Matrix3d& actual) {
  const Eigen::AngleAxisd aa(Eigen::Matrix3d(desired * actual.transpose()));
  return aa.axis() * aa.angle();
}

Eigen::Vector3d orientation_error_from_skew(const Eigen::Matrix3d& desired, const Eigen::Matrix3d& actual) {
  const Eigen::Matrix3d r = desired * actual.transpose();
  const Eigen::Vector3d v(0.5 * (r(2, 1) - r(1, 2)), 0.5 * (r(0, 2) - r(2, 0)), 0.5 * (r(1, 0) - r(0, 1)));
  const double cos_angle = 0.5 * (r.trace() - 1.0), s2 = v.squaredNorm();
  if (!(cos_angle > 0)) return orientation_error(desired, actual);  // past 90° (or not finite)
  // θ/sin θ = 1 + s²/6 + 3s⁴/40 + O(s⁶) (θ = asin s): the next term is below ε for s < 1e-4
  if (s2 < 1e-8) return v * (1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0)));
  const double s = std::sqrt(s2);
  return v * (std::atan2(s, cos_angle) / s);
}

Task::Task(const TaskSpec& spec, const Eigen::Isometry3d& initial_ee, double duration, double dt)
    : spec_(spec),
      trajectory_(spec.trajectory, initial_ee.translation(), duration),
      dt_(dt),
      gain_(spec.gain.value_or(default_task_gain(dt))),
      target_orientation_(spec.orientation.value_or(initial_ee.linear())),
      joy_position_(initial_ee.translation()) {}

Eigen::Vector3d Task::target_position(double t) const {
  return is_joystick() ? joy_position_ : trajectory_.position(t);
}

void Task::reference(double t, const Eigen::Isometry3d& ee, TaskRef& out) const {
  Eigen::Vector3d now, ff;
  if (is_joystick()) {
    now = joy_position_;
    ff = joy_linear_;
  } else {
    now = trajectory_.position(t);
    // mean velocity over the coming step: removes the first-order lag of Euler integration
    ff = (trajectory_.position(t + dt_) - now) / dt_;
  }
  out.position = now;
  out.orientation = target_orientation_;
  const Eigen::Vector3d pos_err = now - ee.translation();
  switch (spec_.space) {
    case TaskSpace::xy:
      out.error = pos_err.head<2>();
      out.xdot_ff = ff.head<2>();
      break;
    case TaskSpace::xyz:
      out.error = pos_err;
      out.xdot_ff = ff;
      break;
    case TaskSpace::pose:
      out.error.head<3>() = pos_err;
      out.error.tail<3>() = orientation_error(target_orientation_, ee.linear());
      out.xdot_ff.head<3>() = ff;
      out.xdot_ff.tail<3>() = is_joystick() ? joy_angular_ : Eigen::Vector3d::Zero();
      break;
  }
  out.position_error = out.error.head(std::min<Eigen::Index>(3, out.error.size())).norm();
  out.orientation_error = spec_.space == TaskSpace::pose ? out.error.tail<3>().norm() : 0.0;
  out.xdot = out.xdot_ff + gain_ * out.error;
}

void Task::set_joystick(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  joy_linear_ = linear;
  joy_angular_ = angular;
}

void Task::advance() {
  if (!is_joystick()) return;
  joy_position_ += joy_linear_ * dt_;
  if (!joy_angular_.isZero(0.0)) {
    const double angle = joy_angular_.norm() * dt_;
    target_orientation_ = Eigen::AngleAxisd(angle, joy_angular_.normalized()) * target_orientation_;
  }
}

}  // namespace rrlab
