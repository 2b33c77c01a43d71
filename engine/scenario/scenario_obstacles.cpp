// The obstacles of a scenario ("obstacles": polygons, boxes, spheres, points,
// walls, meshes), read like the rest of the file (scenario.cpp): every number
// checked in the file's units, errors naming the JSON path.
#include <cmath>
#include <set>

#include <rrlab/collision/polygon.hpp>
#include <rrlab/scenario/mesh_obstacle.hpp>
#include <rrlab/scenario/scenario_parsing.hpp>

namespace rrlab {

namespace scenario_parsing {

using nlohmann::json;

Obstacle parse_obstacle(const json& value, const std::string& path, size_t index, const Units& units,
                        const std::string& dir) {
  JsonObject obj(value, path);
  Obstacle o;
  const std::string shape = obj.choice("shape", {"polygon", "box", "sphere", "point", "wall", "mesh"});
  if (shape == "polygon") {
    obj.check_keys({"id", "shape", "points", "z", "velocity"});
    o.shape = ShapeKind::polygon;
    const json& points = obj.array("points", ScenarioLimits::max_polygon_points);
    for (size_t i = 0; i < points.size(); ++i) {
      const std::string point_path = index_path(obj.child("points"), i);
      const std::vector<double> p = json_numbers(points[i], point_path, 2, 2);
      check_all(p, point_path, PhysicalBounds::length, units);
      o.points.emplace_back(p[0], p[1]);
    }
    const std::string problem = polygon_problem(o.points);
    if (!problem.empty()) throw ScenarioError(obj.child("points"), problem);
    if (obj.has("z")) {
      const std::vector<double> z = bounded_numbers(obj, "z", 2, 2, PhysicalBounds::length, units);
      if (!(z[0] < z[1])) throw ScenarioError(obj.child("z"), "must be [z_min, z_max] with z_min < z_max");
      o.z_min = z[0];
      o.z_max = z[1];
    }
  } else if (shape == "box") {
    obj.check_keys({"id", "shape", "center", "size", "rpy", "velocity"});
    o.shape = ShapeKind::box;
    o.position0 = to_vec3(bounded_numbers(obj, "center", 2, 3, PhysicalBounds::length, units));
    const std::vector<double> size = bounded_numbers(obj, "size", 2, 3, PhysicalBounds::length, units);
    o.size = {size[0], size[1], size.size() > 2 ? size[2] : 2.0};  // planar boxes: 2 m tall
    for (int i = 0; i < 3; ++i)
      if (!(o.size[i] > 0)) throw ScenarioError(index_path(obj.child("size"), i), "must be > 0");
    if (obj.has("rpy"))
      o.rotation = rpy_matrix(bounded_numbers(obj, "rpy", 3, 3, PhysicalBounds::angle, units), units.angle);
  } else if (shape == "sphere") {
    obj.check_keys({"id", "shape", "center", "radius", "velocity"});
    o.shape = ShapeKind::sphere;
    o.position0 = to_vec3(bounded_numbers(obj, "center", 2, 3, PhysicalBounds::length, units));
    o.radius = positive(obj, "radius", PhysicalBounds::length, units);
  } else if (shape == "mesh") {
    obj.check_keys({"id", "shape", "file", "scale", "center", "rpy", "velocity"});
    o.shape = ShapeKind::mesh;
    o.position0 = to_vec3(bounded_numbers(obj, "center", 3, 3, PhysicalBounds::length, units));
    if (obj.has("rpy"))
      o.rotation = rpy_matrix(bounded_numbers(obj, "rpy", 3, 3, PhysicalBounds::angle, units), units.angle);
    if (obj.has("scale")) {
      const json& scale = obj.raw("scale");
      const std::string scale_path = obj.child("scale");
      const std::vector<double> s = scale.is_number() ? std::vector<double>(3, json_number(scale, scale_path))
                                                      : json_numbers(scale, scale_path, 3, 3);
      for (int i = 0; i < 3; ++i) {
        const std::string at = scale.is_number() ? scale_path : index_path(scale_path, size_t(i));
        if (!(s[size_t(i)] > 0) || !std::isfinite(s[size_t(i)]) || s[size_t(i)] > ScenarioLimits::max_mesh_scale)
          throw ScenarioError(at, "must be in (0, " + format_number(ScenarioLimits::max_mesh_scale) + "], got " +
                                      format_number(s[size_t(i)]));
        o.scale[i] = s[size_t(i)];
      }
    }
    o.file = obj.string("file");
    o.mesh = load_obstacle_mesh(o.file, o.scale, dir, obj.child("file"));
  } else if (shape == "point") {
    obj.check_keys({"id", "shape", "position", "velocity"});
    o.shape = ShapeKind::point;
    o.position0 = to_vec3(bounded_numbers(obj, "position", 2, 3, PhysicalBounds::length, units));
  } else {
    obj.check_keys({"id", "shape", "point", "normal", "velocity"});
    o.shape = ShapeKind::wall;
    o.position0 = to_vec3(bounded_numbers(obj, "point", 2, 3, PhysicalBounds::length, units));
    const Eigen::Vector3d normal = to_vec3(bounded_numbers(obj, "normal", 2, 3, PhysicalBounds::length, units));
    if (normal.norm() < 1e-12) throw ScenarioError(obj.child("normal"), "must not be zero");
    o.normal = normal.normalized();
  }
  o.id = obj.string("id", "obstacle" + std::to_string(index + 1));
  if (o.id.empty() || o.id.size() > 64) throw ScenarioError(obj.child("id"), "must have 1 to 64 characters");
  if (obj.has("velocity"))
    o.velocity = to_vec3(bounded_numbers(obj, "velocity", 2, 3, PhysicalBounds::linear_speed, units));
  o.position = o.position0;
  return o;
}

void parse_obstacles(const json& value, const std::string& path, const Units& units, const std::string& dir,
                     Scenario& sc) {
  if (!value.is_array()) throw ScenarioError(path, "must be an array, got " + json_type_name(value));
  if (value.size() > size_t(ScenarioLimits::max_obstacles))
    throw ScenarioError(path, "has " + std::to_string(value.size()) + " obstacles, at most " +
                                  std::to_string(ScenarioLimits::max_obstacles) + " allowed");
  std::set<std::string> ids;
  for (size_t i = 0; i < value.size(); ++i) {
    Obstacle o = parse_obstacle(value[i], index_path(path, i), i, units, dir);
    if (!ids.insert(o.id).second)
      throw ScenarioError(index_path(path, i) + ".id", "duplicate obstacle id \"" + o.id + "\"");
    check_obstacle_fits(o, sc.model, sc.scene, index_path(path, i));
    sc.scene.obstacles.push_back(std::move(o));
  }
}

}  // namespace scenario_parsing

Obstacle parse_obstacle_json(const nlohmann::json& value, const std::string& path, const std::string& dir) {
  return scenario_parsing::parse_obstacle(value, path, 0, scenario_parsing::Units{}, dir);
}

void check_obstacle_fits(const Obstacle& o, const Model& model, const Scene& scene, const std::string& path) {
  if (o.shape != ShapeKind::mesh) return;
  const auto at = [&](const char* key) { return path.empty() ? std::string(key) : path + "." + key; };
  // Planar arms move in the x-y plane against obstacles seen as their x-y
  // footprint; a mesh has no such footprint here (it would need a prism or a
  // slice), so it is refused rather than approximated.
  if (model.kind == ModelKind::planar)
    throw ScenarioError(at("shape"), "mesh obstacles need a spatial robot (spatial_xz, dh or urdf), not a planar one");
  long triangles = long(o.mesh->triangles.size());
  for (const Obstacle& other : scene.obstacles)
    if (other.mesh) triangles += long(other.mesh->triangles.size());
  if (triangles > ScenarioLimits::max_mesh_obstacle_triangles)
    throw ScenarioError(at("file"), "the mesh obstacles would have " + std::to_string(triangles) +
                                            " triangles together, at most " +
                                            std::to_string(ScenarioLimits::max_mesh_obstacle_triangles) + " allowed");
}

}  // namespace rrlab
