// Family narrow_passage: a planar arm whose hand's path threads a gap between
// two walls (boxes standing across one segment of the path).
//
// | option         | meaning                                              | default                      | unit    |
// |----------------|------------------------------------------------------|------------------------------|---------|
// | dof            | joints (links) of the arm, [min, max] or a number    | [3, 12]                      | —       |
// | link_length    | each link's length, drawn per link                   | [0.2, 0.6]                   | m       |
// | link_radius    | every link's capsule radius                          | 0.02                         | m       |
// | gap_width      | free width between the walls (> 2 × link_radius)     | [4, 8] × link_radius         | m       |
// | wall_length    | each wall's length across the path                   | [0.2, 0.4]                   | × reach |
// | wall_thickness | each wall's thickness along the path                 | [0.03, 0.08]                 | × reach |
// | clearance      | least distance of a wall from the start arm          | 0.05                         | m       |
// | waypoints      | waypoints after the start                            | [1, 3]                       | —       |
// | speed          | hand speed along the path (sets the duration)        | 0.2 × reach per second       | m/s     |
// | dt             | time step                                            | 0.01                         | s       |
// | time_law       | "linear" (constant speed) or "quintic" (per segment) | linear                       | —       |
//
// The gap is centred on a point at 0.3-0.7 of a random segment, the walls
// square to it; the hand's whole path (a capsule of link_radius) stays off
// both walls, so only the arm behind the hand has to find its way through.
#include <cmath>

#include "scenario/generator_arms.hpp"
#include "scenario/generator_case.hpp"
#include "scenario/generator_obstacles.hpp"
#include "scenario/generator_path.hpp"
#include "scenario/scenario.hpp"

namespace rrlab {

namespace {

constexpr int kWallDraws = 20;
constexpr double kGapFrom = 0.3, kGapTo = 0.7;  // fraction of the segment

struct Passage {
  nlohmann::json walls;
  double gap = 0, length = 0, thickness = 0;
  int segment = 0;
};

// Two boxes of `length` x `thickness` whose inner faces are `gap` apart,
// centred on the point at fraction u of segment `segment`.
nlohmann::json walls_across(const GeneratedPath& path, int segment, double u, double gap, double length,
                            double thickness) {
  const Eigen::Vector3d a = path.points[segment], b = path.points[segment + 1];
  const Eigen::Vector3d along = (b - a).normalized(), across(-along.y(), along.x(), 0);
  const Eigen::Vector3d middle = a + u * (b - a);
  const double yaw = rounded(std::atan2(along.y(), along.x()));
  nlohmann::json walls = nlohmann::json::array();
  for (int side = 0; side < 2; ++side) {
    const Eigen::Vector3d center = middle + (side == 0 ? 1.0 : -1.0) * (0.5 * gap + 0.5 * length) * across;
    walls.push_back({{"id", side == 0 ? "wall_left" : "wall_right"},
                     {"shape", "box"},
                     {"center", {rounded(center.x()), rounded(center.y())}},
                     {"size", {thickness, length}},
                     {"rpy", {0, 0, yaw}}});
  }
  return walls;
}

}  // namespace

nlohmann::json generate_narrow_passage(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"dof", "link_length", "link_radius", "gap_width", "wall_length", "wall_thickness",
                                  "clearance", "waypoints", "speed", "dt", "time_law"});
  const PlanarArmOptions arm_options = read_planar_arm_options(options, false);
  const double r = arm_options.link_radius;
  const Range gap_width = options.range("gap_width", {4 * r, 8 * r}, {2 * r + 1e-4, 10.0});
  const Range wall_length = options.range("wall_length", {0.2, 0.4}, {0.01, 2.0});
  const Range wall_thickness = options.range("wall_thickness", {0.03, 0.08}, {0.001, 1.0});
  const double clearance = options.number("clearance", 0.05, {0.0, 1.0});
  const PathOptions path_options = read_path_options(options, {1, 3});
  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    std::optional<ArmAndPath> drawn =
        draw_arm_and_path([&](Rng& r) { return draw_planar_arm(arm_options, r); }, path_options, rng);
    if (!drawn) continue;
    const GeneratedArm& arm = drawn->arm;
    GeneratedPath* path = &drawn->path;
    const KeepOut keep_out{arm_capsules(arm.model, path->configurations[0]), clearance,
                           path_capsules(path->points, arm.link_radius)};
    std::optional<Passage> passage;
    for (int draw = 0; draw < kWallDraws && !passage; ++draw) {
      Passage p;
      p.segment = int(rng.below(path->points.size() - 1));
      const double u = rng.uniform(kGapFrom, kGapTo);
      p.gap = rounded(gap_width.draw(rng));
      p.length = rounded(wall_length.draw(rng) * arm.reach);
      p.thickness = rounded(wall_thickness.draw(rng) * arm.reach);
      p.walls = walls_across(*path, p.segment, u, p.gap, p.length, p.thickness);
      if (keeps_out(p.walls[0], keep_out) && keeps_out(p.walls[1], keep_out)) passage = p;
    }
    if (!passage) continue;
    const std::string description =
        case_title(c) + ": " + arm.summary + "; the hand's path crosses, on segment " +
        std::to_string(passage->segment + 1) + ", a gap " + fixed_digits(passage->gap, 4) +
        " m wide (the link is " + fixed_digits(2 * r, 4) + " m thick) between two walls " +
        fixed_digits(passage->length, 3) + " m long and " + fixed_digits(passage->thickness, 3) +
        " m thick, more than " + fixed_digits(clearance, 3) + " m from every link of the start configuration; " +
        path_summary(*path) + ".";
    return case_document(c, description, path_options.dt, path->duration,
                         robot_with_q0(arm, path->configurations[0]), passage->walls, path_task(*path, TaskSpace::xy));
  }
  no_case_found(c, "options.gap_width, options.wall_length or options.clearance");
}

}  // namespace rrlab
