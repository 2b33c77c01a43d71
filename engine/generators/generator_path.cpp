#include <rrlab/generators/generator_path.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <rrlab/generators/generator_case.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

// Waypoints keep inside this band of the reach (a stretched arm is singular),
// apart from each other, and segments this far outside the hole; in reaches.
constexpr double kNearest = 0.15, kFarthest = 0.9, kSeparation = 0.15, kHoleMargin = 0.02;
constexpr int kWaypointDraws = 100;
constexpr double kWaypointJointStep = 0.6;  // rad: each joint of a waypoint within this of the previous one
// Positions derived from kinematics are written to this step (m).
constexpr double kPointStep = 1e-6;

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

PathOptions read_path_options(const GeneratorOptions& options, IntRange default_waypoints) {
  PathOptions o;
  o.waypoints = options.int_range("waypoints", default_waypoints, {1, 50});
  if (options.has("speed")) o.speed = options.range("speed", {0, 0}, {0.001, 100.0});
  o.dt = options.number("dt", o.dt, {0.0001, 0.1});
  o.time_law = options.choice("time_law", {"linear", "quintic"}, o.time_law);
  return o;
}

Eigen::Vector3d hand_position(const Model& model, const Eigen::VectorXd& q) {
  KinematicsData kin(model);
  forward_kinematics(model, q, kin);
  const Eigen::Vector3d p = kin.end_effector().translation();
  return {rounded(p.x(), kPointStep), rounded(p.y(), kPointStep), rounded(p.z(), kPointStep)};
}

std::optional<GeneratedPath> draw_path(const GeneratedArm& arm, int count, Rng& rng) {
  GeneratedPath path;
  const Eigen::Vector3d base = arm.model.base.translation();
  const double nearest = std::max(kNearest * arm.reach, arm.hole_radius + kHoleMargin * arm.reach);
  const auto acceptable = [&](const Eigen::Vector3d& p) {
    const double from_base = (p - base).norm();
    if (from_base < nearest || from_base > kFarthest * arm.reach) return false;
    if (path.points.empty()) return true;
    const Eigen::Vector3d& previous = path.points.back();
    if ((p - previous).norm() < kSeparation * arm.reach) return false;
    return arm.hole_radius == 0 ||
           segment_distance(base, previous, p) >= arm.hole_radius + kHoleMargin * arm.reach;
  };
  while (int(path.points.size()) <= count) {
    bool found = false;
    for (int draw = 0; draw < kWaypointDraws && !found; ++draw) {
      // waypoints near the previous configuration: the witness moves through
      // them on joint-space lines, which between far configurations sweep
      // the hand on long detours
      const Eigen::VectorXd q = path.configurations.empty()
                                    ? draw_configuration(arm, rng)
                                    : draw_configuration_near(arm, path.configurations.back(), kWaypointJointStep, rng);
      const Eigen::Vector3d p = hand_position(arm.model, q);
      if (!acceptable(p)) continue;
      path.configurations.push_back(q);
      path.points.push_back(p);
      found = true;
    }
    if (!found) return std::nullopt;
  }
  for (size_t i = 1; i < path.points.size(); ++i) path.length += (path.points[i] - path.points[i - 1]).norm();
  return path;
}

Eigen::Vector3d point_along(const GeneratedPath& path, double u) {
  double remaining = std::clamp(u, 0.0, 1.0) * path.length;
  for (size_t i = 1; i < path.points.size(); ++i) {
    const double segment = (path.points[i] - path.points[i - 1]).norm();
    if (remaining <= segment && segment > 0)
      return path.points[i - 1] + (remaining / segment) * (path.points[i] - path.points[i - 1]);
    remaining -= segment;
  }
  return path.points.back();
}

}  // namespace rrlab
