// Obstacles of generated scenarios: random shapes in scenario syntax, placed
// by rejection so that each keeps its distance from the witness arm at every
// step, as the engine's collision code measures it.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/generators/generator_clearance.hpp>
#include <rrlab/generators/generator_options.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

// Options "obstacles", "obstacle_size", "shapes", "clearance"; see docs/generators.md.
struct ClutterOptions {
  IntRange count{2, 8};
  Range size{0.04, 0.12};  // characteristic size (sphere radius, box half-edge...) in reaches
  std::vector<std::string> shapes;
  double clearance = 0.05;  // m from every link capsule of the witness arm at every step
  // how many of them stand on the arm of the minimum-norm solution (pinv),
  // each where no other is, clear of the witness: avoiding is needed
  // (read_blocking, generator_blocking.hpp)
  IntRange blocking{0, 0};
};
// `blocking` as read by read_blocking(); the default count is raised to it,
// a count given below it is refused.
ClutterOptions read_clutter_options(const GeneratorOptions& options, IntRange default_count,
                                    const std::vector<std::string>& allowed_shapes, IntRange blocking = {0, 0});

// A `shape` ("sphere", "box", "polygon", "point") of characteristic size
// `size` (m) around `center`, in scenario syntax with id "<shape><number>".
// Planar: centers and sizes in x-y, boxes turned about z, polygons star-shaped
// with 3 to 7 vertices. Spatial: spheres and boxes turned about every axis.
nlohmann::json draw_obstacle(const std::string& shape, const Eigen::Vector3d& center, double size, bool spatial,
                             int number, Rng& rng);

// How far a drawn `shape`'s points reach from its centre, per unit of its
// size: 1 for spheres and polygons, the half-diagonal for boxes (√2 planar,
// √3 spatial), 0 for points.
double shape_reach(const std::string& shape, bool spatial);
// The radius of a ball about the centre that a drawn `shape` always holds,
// per unit of its size: 1 for spheres, 1/2 for boxes (each edge at least
// the size), 0 for polygons (star-shaped, possibly thin) and points.
double shape_inner(const std::string& shape);

// Where obstacles must not come: closer than `clearance` to the witness arm
// at any step.
struct KeepOut {
  const ArmSweep* sweep = nullptr;
  double clearance = 0;
};
bool keeps_out(const nlohmann::json& obstacle, const KeepOut& keep_out);

// Draws the k-th obstacle; nullopt rejects the draw (a family's own rule).
using ObstacleDraw = std::function<std::optional<nlohmann::json>(int k, Rng& rng)>;

// Admits the k-th obstacle once it keeps out (a family's rule that keeps state).
using ObstacleAdmit = std::function<bool(int k, const nlohmann::json& obstacle)>;

// `count` obstacles, the k-th the first of up to `draws` draws that keeps
// out (and is admitted); nullopt when one of them found no place.
std::optional<nlohmann::json> place_obstacles(int count, const KeepOut& keep_out, const ObstacleDraw& draw,
                                              Rng& rng, int draws = 100, const ObstacleAdmit& admit = nullptr);

// A point uniform in the disc (planar) or ball (spatial) of `radius` around `center`.
Eigen::Vector3d point_in_ball(const Eigen::Vector3d& center, double radius, bool spatial, Rng& rng);

// For descriptions: "5 obstacles (2 sphere, 1 box, 2 polygon)".
std::string obstacle_summary(const nlohmann::json& obstacles);

}  // namespace rrlab
