// The hand's path in generated scenarios: a polyline from the start's
// end-effector through waypoints that are end-effector positions of drawn
// configurations (reachable by construction), timed by a speed along it.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/kinematics.hpp"
#include "scenario/generator_arms.hpp"
#include "scenario/generator_options.hpp"
#include "util/rng.hpp"

namespace rrlab {

// Options "waypoints", "speed", "dt", "time_law"; see docs/generators.md.
struct PathOptions {
  IntRange waypoints{2, 4};
  std::optional<Range> speed;  // m/s; default: kDefaultSpeedPerReach * reach
  double dt = 0.01;
  std::string time_law = "linear";
};
PathOptions read_path_options(const GeneratorOptions& options, IntRange default_waypoints = {2, 4});

constexpr double kDefaultSpeedPerReach = 0.2;  // 1/s

struct GeneratedPath {
  std::vector<Eigen::VectorXd> configurations;  // q0, then one per waypoint
  std::vector<Eigen::Vector3d> points;          // their end-effector positions
  double length = 0, speed = 0, duration = 0;   // m, m/s, s (a whole number of dt)
  std::string time_law;
};

// End-effector position of `arm` at q.
Eigen::Vector3d hand_position(const Model& model, const Eigen::VectorXd& q);

// A start configuration q0 and a path from its hand through `count` drawn
// waypoints: every point between 0.15 and 0.9 reach from the base, each
// waypoint 0.15 reach from the previous point, and each segment clear of the
// arm's unreachable hole. Nullopt when a point was not found within a bounded
// number of draws.
std::optional<GeneratedPath> draw_path(const GeneratedArm& arm, int count, Rng& rng);

// Sets speed (drawn, or the default for the arm's reach) and the duration.
void time_path(GeneratedPath& path, const PathOptions& options, double reach, Rng& rng);

// One attempt of a family: an arm from `draw_arm(rng)`, a path of its
// end-effector positions, timed by the options (in that order of draws).
// Nullopt when no path was found for that arm.
struct ArmAndPath {
  GeneratedArm arm;
  GeneratedPath path;
};
template <typename DrawArm>
std::optional<ArmAndPath> draw_arm_and_path(DrawArm&& draw_arm, const PathOptions& options, Rng& rng) {
  GeneratedArm arm = draw_arm(rng);
  std::optional<GeneratedPath> path = draw_path(arm, options.waypoints.draw(rng), rng);
  if (!path) return std::nullopt;
  time_path(*path, options, arm.reach, rng);
  return ArmAndPath{std::move(arm), std::move(*path)};
}

// The document's "task": a polyline in `space` ("xy" or "xyz").
nlohmann::json path_task(const GeneratedPath& path, TaskSpace space);

// The point at arc-length fraction u in [0, 1] of the path.
Eigen::Vector3d point_along(const GeneratedPath& path, double u);

// For descriptions: "the hand follows 3 waypoints, 4.12 m at 0.54 m/s (7.63 s, linear time law)".
std::string path_summary(const GeneratedPath& path);

}  // namespace rrlab
