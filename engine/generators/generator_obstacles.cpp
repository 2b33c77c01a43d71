#include <rrlab/generators/generator_obstacles.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include <rrlab/generators/generator_case.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

nlohmann::json coordinates(const Eigen::Vector3d& p, bool spatial) {
  if (spatial) return {rounded(p.x()), rounded(p.y()), rounded(p.z())};
  return {rounded(p.x()), rounded(p.y())};
}

// Vertices at sorted distinct angles around the center: a simple polygon
// (star-shaped about its center), convex or not.
nlohmann::json star_polygon(const Eigen::Vector3d& center, double size, Rng& rng) {
  const int vertices = 3 + int(rng.below(5));
  std::vector<double> angles;
  const double start = rng.uniform(0, 2 * M_PI);
  for (int i = 0; i < vertices; ++i)
    angles.push_back(start + 2 * M_PI * (i + rng.uniform(0.1, 0.9)) / vertices);
  nlohmann::json points = nlohmann::json::array();
  for (double a : angles) {
    const double r = size * rng.uniform(0.5, 1.0);
    points.push_back({rounded(center.x() + r * std::cos(a)), rounded(center.y() + r * std::sin(a))});
  }
  return points;
}

}  // namespace

ClutterOptions read_clutter_options(const GeneratorOptions& options, IntRange default_count,
                                    const std::vector<std::string>& allowed_shapes, IntRange blocking) {
  ClutterOptions o;
  o.blocking = blocking;
  const IntRange raised{std::max(default_count.min, blocking.max), std::max(default_count.max, blocking.max)};
  o.count = options.int_range("obstacles", raised, {0, 64});
  o.size = options.range("obstacle_size", o.size, {0.001, 1.0});
  o.shapes = options.subset("shapes", allowed_shapes, allowed_shapes);
  o.clearance = options.number("clearance", o.clearance, {0.0, 1.0});
  if (o.count.min < blocking.max)
    throw ScenarioError("options.obstacles", "must be at least " + std::to_string(blocking.max) +
                                                 " with blocking " + std::to_string(blocking.max) +
                                                 " (the blocking obstacles are among them; set block_pinv false for none)");
  return o;
}

nlohmann::json draw_obstacle(const std::string& shape, const Eigen::Vector3d& center, double size, bool spatial,
                             int number, Rng& rng) {
  nlohmann::json o = {{"id", shape + std::to_string(number)}, {"shape", shape}};
  if (shape == "sphere") {
    o["center"] = coordinates(center, spatial);
    o["radius"] = std::max(rounded(size), 1e-3);
  } else if (shape == "box") {
    o["center"] = coordinates(center, spatial);
    const int dims = spatial ? 3 : 2;
    nlohmann::json edges = nlohmann::json::array();
    for (int i = 0; i < dims; ++i) edges.push_back(std::max(rounded(2 * size * rng.uniform(0.5, 1.0)), 1e-3));
    o["size"] = edges;
    if (spatial)
      o["rpy"] = {rounded(rng.uniform(-M_PI, M_PI)), rounded(rng.uniform(-M_PI / 2, M_PI / 2)),
                  rounded(rng.uniform(-M_PI, M_PI))};
    else
      o["rpy"] = {0, 0, rounded(rng.uniform(-M_PI, M_PI))};
  } else if (shape == "polygon") {
    o["points"] = star_polygon(center, size, rng);
  } else {
    o["position"] = coordinates(center, spatial);
  }
  return o;
}

double shape_reach(const std::string& shape, bool spatial) {
  if (shape == "box") return std::sqrt(spatial ? 3.0 : 2.0);
  if (shape == "point") return 0;
  return 1;
}

double shape_inner(const std::string& shape) {
  if (shape == "sphere") return 1;
  if (shape == "box") return 0.5;
  return 0;
}

bool keeps_out(const nlohmann::json& obstacle, const KeepOut& keep_out) {
  Obstacle o;
  try {
    o = parse_obstacle_json(obstacle, "obstacle");
  } catch (const ScenarioError&) {
    return false;  // a polygon degenerate after rounding: draw another
  }
  return sweep_clearance(*keep_out.sweep, o, keep_out.clearance) > keep_out.clearance;
}

std::optional<nlohmann::json> place_obstacles(int count, const KeepOut& keep_out, const ObstacleDraw& draw,
                                              Rng& rng, int draws, const ObstacleAdmit& admit) {
  nlohmann::json placed = nlohmann::json::array();
  for (int k = 0; k < count; ++k) {
    bool found = false;
    for (int attempt = 0; attempt < draws && !found; ++attempt) {
      std::optional<nlohmann::json> candidate = draw(k, rng);
      if (!candidate || !keeps_out(*candidate, keep_out) || (admit && !admit(k, *candidate))) continue;
      placed.push_back(std::move(*candidate));
      found = true;
    }
    if (!found) return std::nullopt;
  }
  return placed;
}

Eigen::Vector3d point_in_ball(const Eigen::Vector3d& center, double radius, bool spatial, Rng& rng) {
  for (;;) {
    // one draw per statement: as constructor arguments their order was up to the
    // compiler (gcc drew z, y, x; clang x, y, z: other scenarios). gcc's order
    // is kept, so that the generated families stay what they were.
    const double z = spatial ? rng.uniform(-1, 1) : 0.0;
    const double y = rng.uniform(-1, 1);
    const double x = rng.uniform(-1, 1);
    const Eigen::Vector3d u(x, y, z);
    if (u.squaredNorm() <= 1) return center + radius * u;
  }
}

std::string obstacle_summary(const nlohmann::json& obstacles) {
  std::map<std::string, int> by_shape;
  for (const nlohmann::json& o : obstacles) ++by_shape[o["shape"].get<std::string>()];
  std::string parts;
  for (const auto& [shape, n] : by_shape) parts += (parts.empty() ? "" : ", ") + std::to_string(n) + " " + shape;
  return std::to_string(obstacles.size()) + (obstacles.size() == 1 ? " obstacle" : " obstacles") +
         (parts.empty() ? "" : " (" + parts + ")");
}

}  // namespace rrlab
