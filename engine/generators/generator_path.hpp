// The waypoints of generated scenarios: a start configuration and drawn
// configurations whose end-effector positions keep the family's spacing; the
// witness (generator_witness.hpp) moves through them.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_options.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

// Options "waypoints", "speed", "dt", "time_law"; see docs/generators.md.
struct PathOptions {
  IntRange waypoints{2, 4};
  std::optional<Range> speed;  // m/s; default: kDefaultSpeedPerReach * reach
  double dt = 0.01;
  std::string time_law = "quintic";
};
PathOptions read_path_options(const GeneratorOptions& options, IntRange default_waypoints = {2, 4});

constexpr double kDefaultSpeedPerReach = 0.2;  // 1/s

// Drawn by draw_path(); draw_witnessed_arm() (generator_witness.hpp) then
// replaces the points by the witness's hand trace and sets its timing.
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

// The point at arc-length fraction u in [0, 1] of the path.
Eigen::Vector3d point_along(const GeneratedPath& path, double u);

}  // namespace rrlab
