#include <rrlab/sim/run_inputs.hpp>

#include <cmath>
#include <iterator>

#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/scenario/physical_bounds.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {

namespace {

using nlohmann::json;

Eigen::Vector3d vector3(JsonObject& obj, const std::string& key, const Quantity& quantity) {
  const std::vector<double> v = obj.numbers(key, 2, 3);
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < v.size(); ++i)
    out[Eigen::Index(i)] = check_quantity(v[i], quantity, index_path(obj.child(key), i));
  return out;
}

int obstacle_index(const Simulator& sim, JsonObject& obj) {
  const std::string id = obj.string("id");
  const int index = sim.scene().find(id);
  if (index < 0) throw ScenarioError(obj.child("id"), "no obstacle \"" + id + "\" in this run");
  return index;
}

void apply_params(Simulator& sim, const json& payload) {
  if (!payload.is_object() || payload.empty())
    throw ScenarioError("", "must be an object {\"NAME\": value, ...} with at least one parameter");
  for (const auto& [name, value] : resolve_method_params(sim.method_name(), payload, ""))
    sim.set_param(name, value);
}

// Edits one obstacle; "position" places its reference point (centre, point,
// polygon frame origin) at the current time, so a moving one keeps moving from there.
void apply_obstacle(Simulator& sim, const json& payload) {
  JsonObject obj(payload, "");
  obj.check_keys({"id", "position", "velocity", "size", "radius", "points", "normal", "z"});
  const int index = obstacle_index(sim, obj);
  Obstacle edited = sim.scene().obstacles[size_t(index)];
  bool reshape = false;
  // Shape fields go through the scenario parser so that they are checked alike.
  if (obj.has("size") || obj.has("radius") || obj.has("points") || obj.has("normal") || obj.has("z")) {
    json shape = obstacle_to_json(edited);
    for (const char* key : {"size", "radius", "points", "normal", "z"})
      if (obj.has(key)) {
        if (!shape.contains(key))
          throw ScenarioError(obj.child(key), std::string("a ") + to_string(edited.shape) +
                                                  " obstacle has no " + key);
        shape[key] = obj.raw(key);
      }
    shape.erase("position");  // a polygon's translation is kept below, not parsed
    Obstacle parsed = parse_obstacle_json(shape, "");
    parsed.rotation = edited.rotation;
    parsed.position0 = edited.position0;
    parsed.position = edited.position;
    parsed.velocity = edited.velocity;
    edited = std::move(parsed);
    reshape = true;
  }
  if (obj.has("velocity")) edited.velocity = vector3(obj, "velocity", PhysicalBounds::linear_speed);
  if (obj.has("position")) edited.position = vector3(obj, "position", PhysicalBounds::length);
  if (obj.has("position") && payload.at("position").size() == 2)
    edited.position.z() = sim.scene().obstacles[size_t(index)].position.z();
  // position(t) = position0 + velocity · t must hold at the current time
  edited.position0 = edited.position - edited.velocity * sim.state().t;
  sim.scene().obstacles[size_t(index)] = std::move(edited);
  sim.scene_changed(reshape);
}

void apply_obstacle_add(Simulator& sim, const json& payload) {
  if (!payload.is_object() || !payload.contains("id"))
    throw ScenarioError("id", "an added obstacle needs an id");
  if (sim.scene().obstacles.size() >= size_t(ScenarioLimits::max_obstacles))
    throw InputStateError("the run already has " + std::to_string(ScenarioLimits::max_obstacles) +
                          " obstacles, the most allowed");
  Obstacle added = parse_obstacle_json(payload, "");  // a mesh's file: in the catalogue directory
  if (sim.scene().find(added.id) >= 0)
    throw ScenarioError("id", "an obstacle \"" + added.id + "\" exists already");
  check_obstacle_fits(added, sim.model(), sim.scene(), "");
  added.position = added.position0;
  added.position0 = added.position - added.velocity * sim.state().t;
  sim.scene().obstacles.push_back(std::move(added));
  sim.scene_changed(true);
}

void apply_obstacle_remove(Simulator& sim, const json& payload) {
  JsonObject obj(payload, "");
  obj.check_keys({"id"});
  const int index = obstacle_index(sim, obj);
  sim.scene().obstacles.erase(sim.scene().obstacles.begin() + index);
  sim.scene_changed(true);
}

void apply_joystick(Simulator& sim, const json& payload) {
  if (!sim.task().is_joystick())
    throw InputStateError("this run's task is a " + std::string(to_string(sim.scenario().task.trajectory.type)) +
                          " trajectory, not a joystick");
  JsonObject obj(payload, "");
  obj.check_keys({"linear", "angular"});
  const Eigen::Vector3d linear = vector3(obj, "linear", PhysicalBounds::joystick_speed);
  const Eigen::Vector3d angular = obj.has("angular") ? vector3(obj, "angular", PhysicalBounds::joystick_rate)
                                                     : Eigen::Vector3d::Zero();
  sim.task().set_joystick(linear, angular);
}

void apply_method(Simulator& sim, const json& payload) {
  JsonObject obj(payload, "");
  obj.check_keys({"name", "params"});
  const std::string name = obj.string("name");
  require_method(name, "name");
  std::vector<std::pair<std::string, double>> resolved;
  if (obj.has("params")) resolved = resolve_method_params(name, payload.at("params"), "params");
  sim.switch_method(name);
  for (const auto& [param, value] : resolved) sim.set_param(param, value);
}

}  // namespace

namespace {
constexpr const char* kInputKindNames[] = {"params", "obstacle", "obstacle_add", "obstacle_remove",
                                           "joystick", "method", "reset"};
}  // namespace

const char* to_string(InputKind kind) { return kInputKindNames[size_t(kind)]; }

std::optional<InputKind> parse_input_kind(std::string_view text) {
  for (size_t i = 0; i < std::size(kInputKindNames); ++i)
    if (text == kInputKindNames[i]) return InputKind(i);
  return std::nullopt;
}

ScenarioError unknown_input_kind(const std::string& kind) {
  std::string known;
  for (const char* name : kInputKindNames) known += (known.empty() ? "" : ", ") + std::string(name);
  return ScenarioError("kind", "unknown input \"" + kind + "\" (known: " + known + ")");
}

void apply_input(Simulator& sim, InputKind kind, const json& payload) {
  switch (kind) {
    case InputKind::params: return apply_params(sim, payload);
    case InputKind::obstacle: return apply_obstacle(sim, payload);
    case InputKind::obstacle_add: return apply_obstacle_add(sim, payload);
    case InputKind::obstacle_remove: return apply_obstacle_remove(sim, payload);
    case InputKind::joystick: return apply_joystick(sim, payload);
    case InputKind::method: return apply_method(sim, payload);
    case InputKind::reset:
      if (!payload.is_null() && !(payload.is_object() && payload.empty()))
        throw ScenarioError("", "reset takes no payload");
      return sim.reset();
  }
}

void apply_input(Simulator& sim, const std::string& kind, const json& payload) {
  const std::optional<InputKind> known = parse_input_kind(kind);
  if (!known) throw unknown_input_kind(kind);
  apply_input(sim, *known, payload);
}

json obstacle_to_json(const Obstacle& o) {
  const auto vec = [](const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); };
  json j = {{"id", o.id}, {"shape", to_string(o.shape)}};
  switch (o.shape) {
    case ShapeKind::polygon: {
      json points = json::array();
      for (const Eigen::Vector2d& p : o.points) points.push_back({p.x(), p.y()});
      j["points"] = points;
      j["z"] = {o.z_min, o.z_max};
      j["position"] = vec(o.position);  // translation of the polygon's frame
      break;
    }
    case ShapeKind::box: {
      j["center"] = vec(o.position);
      j["size"] = vec(o.size);
      const Eigen::Vector3d rpy = o.rotation.eulerAngles(2, 1, 0).reverse();  // roll, pitch, yaw
      j["rpy"] = vec(rpy);
      break;
    }
    case ShapeKind::sphere:
      j["center"] = vec(o.position);
      j["radius"] = o.radius;
      break;
    case ShapeKind::point:
      j["position"] = vec(o.position);
      break;
    case ShapeKind::wall:
      j["point"] = vec(o.position);
      j["normal"] = vec(o.normal);
      break;
    case ShapeKind::mesh: {
      j["file"] = o.file;
      j["scale"] = vec(o.scale);
      j["center"] = vec(o.position);
      const Eigen::Vector3d rpy = o.rotation.eulerAngles(2, 1, 0).reverse();  // roll, pitch, yaw
      j["rpy"] = vec(rpy);
      break;
    }
  }
  j["velocity"] = vec(o.velocity);
  return j;
}

}  // namespace rrlab
