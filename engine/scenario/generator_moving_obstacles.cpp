// Family moving_obstacles: a planar arm, its hand on a polyline through
// reachable waypoints, and obstacles moving at constant velocity across it.
//
// | option         | meaning                                              | default                     | unit    |
// |----------------|------------------------------------------------------|-----------------------------|---------|
// | dof            | joints (links) of the arm, [min, max] or a number    | [3, 12]                     | —       |
// | link_length    | each link's length, drawn per link                   | [0.2, 0.6]                  | m       |
// | link_radius    | every link's capsule radius                          | 0.02                        | m       |
// | obstacles      | obstacle count                                       | [1, 4]                      | —       |
// | obstacle_size  | sphere radius / box half-edge / polygon radius       | [0.04, 0.12]                | × reach |
// | shapes         | shapes drawn from (uniformly)                        | sphere, box, polygon, point | —       |
// | obstacle_speed | each obstacle's speed, its direction uniform         | [0.1, 0.3] × reach per second | m/s     |
// | clearance      | least distance of an obstacle from the start arm at t = 0 | 0.05                   | m       |
// | waypoints      | waypoints after the start                            | [2, 4]                      | —       |
// | speed          | hand speed along the path (sets the duration)        | 0.2 × reach per second      | m/s     |
// | dt             | time step                                            | 0.01                        | s       |
// | time_law       | "linear" (constant speed) or "quintic" (per segment) | linear                      | —       |
//
// Each obstacle is aimed to pass through a random point of the hand's path at
// a random time in [0.2, 0.9] of the run (not when the hand is there), so it
// crosses the path while the arm works; at t = 0 it keeps the clearance from
// the start arm, and its track keeps clear of the base (which no method can
// move away).
#include <algorithm>
#include <cmath>

#include "scenario/generator_arms.hpp"
#include "scenario/generator_case.hpp"
#include "scenario/generator_obstacles.hpp"
#include "scenario/generator_path.hpp"
#include "scenario/scenario.hpp"

namespace rrlab {

namespace {

constexpr double kCrossFrom = 0.2, kCrossTo = 0.9;  // fractions of the duration
constexpr double kDefaultSpeedMin = 0.1, kDefaultSpeedMax = 0.3;  // reaches per second

double point_segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

nlohmann::json generate_moving_obstacles(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"dof", "link_length", "link_radius", "obstacles", "obstacle_size", "shapes",
                                  "obstacle_speed", "clearance", "waypoints", "speed", "dt", "time_law"});
  const PlanarArmOptions arm_options = read_planar_arm_options(options, false);
  const ClutterOptions clutter = read_clutter_options(options, {1, 4}, {"sphere", "box", "polygon", "point"});
  if (clutter.count.min < 1) throw ScenarioError("options.obstacles", "must be at least 1 in this family");
  const bool speed_given = options.has("obstacle_speed");
  const Range given_speed = options.range("obstacle_speed", {}, {0.001, 100.0});
  const PathOptions path_options = read_path_options(options);
  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    std::optional<ArmAndPath> drawn =
        draw_arm_and_path([&](Rng& r) { return draw_planar_arm(arm_options, r); }, path_options, rng);
    if (!drawn) continue;
    const GeneratedArm& arm = drawn->arm;
    GeneratedPath* path = &drawn->path;
    const KeepOut keep_out{arm_capsules(arm.model, path->configurations[0]), clutter.clearance, {}};
    const Range speed_range =
        speed_given ? given_speed : Range{kDefaultSpeedMin * arm.reach, kDefaultSpeedMax * arm.reach};
    const auto draw = [&](int k, Rng& r) -> std::optional<nlohmann::json> {
      const double size = clutter.size.draw(r) * arm.reach;
      const double speed = speed_range.draw(r), heading = r.uniform(-M_PI, M_PI);
      const Eigen::Vector3d velocity(rounded(speed * std::cos(heading)), rounded(speed * std::sin(heading)), 0);
      const Eigen::Vector3d crossing = point_along(*path, r.uniform());
      const Eigen::Vector3d start = crossing - velocity * (r.uniform(kCrossFrom, kCrossTo) * path->duration);
      const std::string& shape = clutter.shapes[r.below(clutter.shapes.size())];
      // its track, grown by a bound of its extent (sqrt(2) size), must miss the base
      const double track_to_base =
          point_segment_distance(Eigen::Vector3d::Zero(), start, start + velocity * path->duration);
      if (track_to_base <= std::sqrt(2.0) * size + arm.link_radius + clutter.clearance) return std::nullopt;
      nlohmann::json o = draw_obstacle(shape, start, size, false, k + 1, r);
      o["velocity"] = {velocity.x(), velocity.y()};
      return o;
    };
    const std::optional<nlohmann::json> obstacles = place_obstacles(clutter.count.draw(rng), keep_out, draw, rng);
    if (!obstacles) continue;
    const std::string description =
        case_title(c) + ": " + arm.summary + " and " + obstacle_summary(*obstacles) + " moving at " +
        fixed_digits(speed_range.min, 3) + "-" + fixed_digits(speed_range.max, 3) +
        " m/s, each aimed through a point of the hand's path at 0.2-0.9 of the run and, at t = 0, more than " +
        fixed_digits(clutter.clearance, 3) + " m from every link of the start configuration; " + path_summary(*path) +
        ".";
    return case_document(c, description, path_options.dt, path->duration,
                         robot_with_q0(arm, path->configurations[0]), *obstacles, path_task(*path, TaskSpace::xy));
  }
  no_case_found(c, "options.obstacles, options.obstacle_size or options.clearance");
}

}  // namespace rrlab
