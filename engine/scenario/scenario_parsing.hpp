// The scenario parser's own parts, shared by its files: scenario.cpp (the
// document, the robot, the task, the witness, the method) and
// scenario_obstacles.cpp (the obstacles). Every number is read in the file's
// units and checked against PhysicalBounds; errors name the JSON path.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/scenario/physical_bounds.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab::scenario_parsing {

struct Units {
  double angle = 1.0;  // radians per file unit
};

inline Eigen::Vector3d to_vec3(const std::vector<double>& v) {
  return {v[0], v[1], v.size() > 2 ? v[2] : 0.0};
}

// Every number read is checked against PhysicalBounds in the file's units.
inline void check_all(const std::vector<double>& values, const std::string& path, const Quantity& q,
                      const Units& units) {
  for (size_t i = 0; i < values.size(); ++i) check_quantity(values[i], q, index_path(path, i), units.angle);
}

inline double bounded(JsonObject& obj, const std::string& key, const Quantity& q, const Units& units, double def) {
  return check_quantity(obj.number(key, def), q, obj.child(key), units.angle);
}

inline std::vector<double> bounded_numbers(JsonObject& obj, const std::string& key, size_t min_size, size_t max_size,
                                           const Quantity& q, const Units& units) {
  std::vector<double> values = obj.numbers(key, min_size, max_size);
  check_all(values, obj.child(key), q, units);
  return values;
}

inline double positive(JsonObject& obj, const std::string& key, const Quantity& q, const Units& units,
                       std::optional<double> def = std::nullopt) {
  const double v = def ? obj.number(key, *def) : obj.number(key);
  if (!(v > 0)) throw ScenarioError(obj.child(key), "must be > 0, got " + format_number(v));
  return check_quantity(v, q, obj.child(key), units.angle);
}

inline double non_negative(JsonObject& obj, const std::string& key, const Quantity& q, const Units& units,
                           double def) {
  const double v = obj.number(key, def);
  if (v < 0) throw ScenarioError(obj.child(key), "must be >= 0, got " + format_number(v));
  return check_quantity(v, q, obj.child(key), units.angle);
}

// scenario_obstacles.cpp: one obstacle (`index`: its place in the list, for
// its default id), and the "obstacles" list into sc.scene (ids unique, each
// fitting the robot: check_obstacle_fits).
Obstacle parse_obstacle(const nlohmann::json& value, const std::string& path, size_t index, const Units& units,
                        const std::string& dir);
void parse_obstacles(const nlohmann::json& value, const std::string& path, const Units& units,
                     const std::string& dir, Scenario& sc);

}  // namespace rrlab::scenario_parsing
