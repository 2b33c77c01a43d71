// A scenario: robot, obstacles, task and method, loaded from the JSON
// contract (docs/scenario-format.md) with errors that name the JSON path.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <rrlab/collision/scene.hpp>
#include <rrlab/model/model.hpp>
#include <rrlab/task/task.hpp>
#include <rrlab/task/witness.hpp>

namespace rrlab {

// Size bounds that keep a scenario from exhausting memory or time.
struct ScenarioLimits {
  static constexpr int max_joints = 64;
  static constexpr int max_obstacles = 256;
  static constexpr int max_polygon_points = 1024;
  static constexpr int max_path_points = 10000;
  static constexpr long max_witness_numbers = 2'000'000;  // samples × joints
  static constexpr long max_steps = 10'000'000;
  static constexpr long max_urdf_bytes = 1 << 20;  // a URDF file or inline text
  // Mesh obstacles: per file, and over all of a scenario's mesh obstacles (the
  // dashboard receives their triangles with every snapshot).
  static constexpr long max_mesh_bytes = 8 << 20;
  static constexpr int max_mesh_triangles = 20000;
  static constexpr int max_mesh_obstacle_triangles = 20000;
  // A URDF robot: over all its <collision><mesh> references.
  static constexpr int max_robot_mesh_triangles = 20000;
  static constexpr double max_mesh_scale = 1000.0;
};

class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(std::string path, const std::string& message)
      : std::runtime_error(path.empty() ? message : path + ": " + message), path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

struct MethodSpec {
  std::string name;
  std::vector<std::pair<std::string, double>> params;  // validated against the method's specs
};

struct Scenario {
  std::string name, description, source;
  double dt = 0.01, duration = 1.0;
  std::uint64_t seed = 1;
  Model model;
  Eigen::VectorXd q0;
  Scene scene;
  TaskSpec task;
  MethodSpec method;
  // "witness": a joint trajectory known to solve the task (generated cases)
  std::shared_ptr<const WitnessTrajectory> witness;
  nlohmann::json json;  // the document as given

  long steps() const;
};

// Throws ScenarioError naming the offending path. `dir`: the directory a
// robot's URDF "file" is resolved in and confined to (the scenario file's
// directory); empty: the catalogue directory below.
Scenario parse_scenario(const nlohmann::json& doc, const std::string& dir = {});
Scenario parse_scenario_text(const std::string& text);
Scenario load_scenario_file(const std::string& file);
// The catalogue of scenario files (the server's --scenarios directory): where
// the URDF "file" of a scenario without a directory of its own (sent over
// REST, stored, re-simulated) is resolved. Empty until set: such a scenario
// must then carry its URDF inline ("urdf").
// The rotation a scenario's [r, p, y] describes (angles times `scale`, the
// radians per file unit): Rz(y) Ry(p) Rx(r).
Eigen::Matrix3d rpy_matrix(const std::vector<double>& rpy, double scale = 1.0);

void set_scenario_catalogue_dir(const std::string& dir);
std::string scenario_catalogue_dir();
// A JSON file (`what` names it in errors: "scenario file", "sweep spec"):
// ScenarioError("", ...) when it cannot be read or is not JSON.
nlohmann::json read_json_file(const std::string& file, const std::string& what);

// One obstacle in scenario syntax, angles in radians (live edits over REST).
// A mesh obstacle's file is resolved in `dir` (empty: the catalogue directory).
Obstacle parse_obstacle_json(const nlohmann::json& value, const std::string& path, const std::string& dir = {});
// Throws ScenarioError at `path` when obstacle `o` cannot join a scene of
// `model` that holds `scene` (mesh obstacles: not on planar robots, and the
// mesh triangles bounded in total).
void check_obstacle_fits(const Obstacle& o, const Model& model, const Scene& scene, const std::string& path);

// Throws ScenarioError at `path` unless `name` is a registered method.
void require_method(const std::string& name, const std::string& path);

// Every entry of a {"NAME": value, ...} object resolved for `method` as
// resolve_method_param does; errors name `path.NAME` (or `path` when the
// value is not an object).
std::vector<std::pair<std::string, double>> resolve_method_params(const std::string& method,
                                                                  const nlohmann::json& params,
                                                                  const std::string& path);

// Resolves a method parameter given as a number or an enumeration label;
// throws ScenarioError at `path`. Shared by scenarios, CLI and REST.
std::pair<std::string, double> resolve_method_param(const std::string& method,
                                                    const std::string& name,
                                                    const nlohmann::json& value,
                                                    const std::string& path);

}  // namespace rrlab
