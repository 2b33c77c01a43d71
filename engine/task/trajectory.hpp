// End-effector trajectories: position as a function of time (and, for the
// joystick, of velocity commands).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace rrlab {

enum class TrajectoryType { polyline, circle, ellipse, joystick };
enum class TimeLaw { linear, quintic };
const char* to_string(TrajectoryType type);
const char* to_string(TimeLaw law);

struct TrajectorySpec {
  TrajectoryType type = TrajectoryType::polyline;
  TimeLaw time_law = TimeLaw::linear;
  std::vector<Eigen::Vector3d> points;       // polyline (the first is the start)
  std::vector<double> durations;             // polyline, per segment (empty: by length)
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;                       // circle
  Eigen::Vector2d semi_axes = Eigen::Vector2d::Zero();  // ellipse
  std::optional<double> start_angle;         // default: angle of the initial end-effector
  bool clockwise = false;
  double turns = 1.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

// Normalised progress s(τ) on [0, 1] for τ in [0, 1].
double time_law_progress(TimeLaw law, double tau);

class Trajectory {
 public:
  // `start` is the initial end-effector position, `duration` the run's length.
  Trajectory(const TrajectorySpec& spec, const Eigen::Vector3d& start, double duration);

  // Desired position at time t (held at the end after the last segment).
  Eigen::Vector3d position(double t) const;
  bool is_joystick() const { return spec_.type == TrajectoryType::joystick; }
  const TrajectorySpec& spec() const { return spec_; }
  double duration() const { return duration_; }

 private:
  Eigen::Vector3d polyline_at(double t) const;
  Eigen::Vector3d conic_at(double t) const;

  TrajectorySpec spec_;
  double duration_;
  std::vector<double> segment_end_times_;  // polyline: cumulative
  std::vector<double> cumulative_length_;  // polyline: arc length at each point
  Eigen::Vector3d plane_u_, plane_v_;      // circle / ellipse plane basis
  double start_angle_ = 0;
};

}  // namespace rrlab
