#include <rrlab/task/trajectory.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace rrlab {

const char* to_string(TrajectoryType type) {
  switch (type) {
    case TrajectoryType::polyline: return "polyline";
    case TrajectoryType::circle: return "circle";
    case TrajectoryType::ellipse: return "ellipse";
    case TrajectoryType::joystick: return "joystick";
  }
  return "?";
}

const char* to_string(TimeLaw law) { return law == TimeLaw::linear ? "linear" : "quintic"; }

double time_law_progress(TimeLaw law, double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  if (law == TimeLaw::linear) return tau;
  // rest-to-rest quintic: zero velocity and acceleration at both ends
  return tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
}

Trajectory::Trajectory(const TrajectorySpec& spec, const Eigen::Vector3d& start, double duration)
    : spec_(spec), duration_(duration) {
  if (spec_.type == TrajectoryType::polyline) {
    cumulative_length_.push_back(0.0);
    for (size_t i = 1; i < spec_.points.size(); ++i)
      cumulative_length_.push_back(cumulative_length_.back() + (spec_.points[i] - spec_.points[i - 1]).norm());
    const double total = cumulative_length_.back();
    const size_t segments = spec_.points.size() - 1;
    double t = 0;
    for (size_t i = 0; i < segments; ++i) {
      if (!spec_.durations.empty())
        t += spec_.durations[i];
      else if (total > 0)
        t = duration * cumulative_length_[i + 1] / total;
      else
        t = duration * double(i + 1) / double(segments);
      segment_end_times_.push_back(t);
    }
    return;
  }
  if (spec_.type == TrajectoryType::joystick) return;
  // circle / ellipse: plane basis (u, v) with u the projection of +x (or +y
  // when the normal is along x), v = n × u; angles are measured from u.
  const Eigen::Vector3d n = spec_.normal.normalized();
  Eigen::Vector3d ref = Eigen::Vector3d::UnitX();
  if (std::abs(n.dot(ref)) > 0.9) ref = Eigen::Vector3d::UnitY();
  plane_u_ = (ref - n * n.dot(ref)).normalized();
  plane_v_ = n.cross(plane_u_);
  if (spec_.start_angle) {
    start_angle_ = *spec_.start_angle;
  } else {
    const Eigen::Vector3d r = start - spec_.center;
    double a = 1, b = 1;
    if (spec_.type == TrajectoryType::ellipse) a = spec_.semi_axes[0], b = spec_.semi_axes[1];
    start_angle_ = std::atan2(r.dot(plane_v_) / b, r.dot(plane_u_) / a);
  }
}

Eigen::Vector3d Trajectory::position(double t) const {
  switch (spec_.type) {
    case TrajectoryType::polyline: return polyline_at(t);
    case TrajectoryType::circle:
    case TrajectoryType::ellipse: return conic_at(t);
    case TrajectoryType::joystick: break;
  }
  return Eigen::Vector3d::Zero();  // joystick targets live in Task
}

Eigen::Vector3d Trajectory::polyline_at(double t) const {
  const auto& p = spec_.points;
  if (p.size() == 1) return p[0];
  if (spec_.time_law == TimeLaw::linear && spec_.durations.empty()) {
    // constant speed over the whole path
    const double total = cumulative_length_.back();
    const double s = total * std::clamp(duration_ > 0 ? t / duration_ : 1.0, 0.0, 1.0);
    size_t i = 1;
    while (i + 1 < p.size() && cumulative_length_[i] < s) ++i;
    const double len = cumulative_length_[i] - cumulative_length_[i - 1];
    const double u = len > 0 ? (s - cumulative_length_[i - 1]) / len : 1.0;
    return p[i - 1] + u * (p[i] - p[i - 1]);
  }
  // per-segment time law (quintic: rest-to-rest on each segment)
  size_t seg = 0;
  while (seg + 1 < segment_end_times_.size() && t > segment_end_times_[seg]) ++seg;
  const double t0 = seg == 0 ? 0.0 : segment_end_times_[seg - 1];
  const double span = segment_end_times_[seg] - t0;
  const double s = time_law_progress(spec_.time_law, span > 0 ? (t - t0) / span : 1.0);
  return p[seg] + s * (p[seg + 1] - p[seg]);
}

Eigen::Vector3d Trajectory::conic_at(double t) const {
  const double s = time_law_progress(spec_.time_law, duration_ > 0 ? t / duration_ : 1.0);
  const double sweep = 2.0 * M_PI * spec_.turns * (spec_.clockwise ? -1.0 : 1.0);
  const double phi = start_angle_ + sweep * s;
  double a = spec_.radius, b = spec_.radius;
  if (spec_.type == TrajectoryType::ellipse) a = spec_.semi_axes[0], b = spec_.semi_axes[1];
  return spec_.center + a * std::cos(phi) * plane_u_ + b * std::sin(phi) * plane_v_;
}

}  // namespace rrlab
