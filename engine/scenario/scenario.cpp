// Scenario loader: scenario JSON (the file format of scenarios/) to engine types. Every
// check happens here, where user input enters; errors name the JSON path. The
// robot, the task, the witness and the method here; the obstacles in
// scenario_obstacles.cpp; the checked number readers in scenario_parsing.hpp.
#include <rrlab/scenario/scenario.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include <rrlab/collision/allowed_collisions.hpp>
#include <rrlab/methods/registry.hpp>
#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/scenario/physical_bounds.hpp>
#include <rrlab/scenario/scenario_parsing.hpp>
#include <rrlab/scenario/urdf_robot.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab {

Eigen::Matrix3d rpy_matrix(const std::vector<double>& rpy, double scale) {
  return (Eigen::AngleAxisd(rpy[2] * scale, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy[1] * scale, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy[0] * scale, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

namespace {
using nlohmann::json;
}  // namespace

namespace scenario_parsing {

// The quantity of a joint coordinate (or of its rate) by joint type.
struct JointQuantity {
  const Quantity& revolute;
  const Quantity& prismatic;
  const Quantity& of(JointType type) const { return type == JointType::revolute ? revolute : prismatic; }
};
constexpr JointQuantity kPosition{PhysicalBounds::angle, PhysicalBounds::length};
constexpr JointQuantity kVelocity{PhysicalBounds::angular_speed, PhysicalBounds::linear_speed};
constexpr JointQuantity kAcceleration{PhysicalBounds::acceleration, PhysicalBounds::acceleration};

// ---- robot ----

Model parse_links(JsonObject& robot, const std::string& kind, const Units& units) {
  const json& links = robot.array("links", ScenarioLimits::max_joints);
  const std::string links_path = robot.child("links");
  if (links.empty()) throw ScenarioError(links_path, "needs at least one link");
  const int joints_per_link = kind == "spatial_xz" ? 2 : 1;
  if (int(links.size()) * joints_per_link > ScenarioLimits::max_joints)
    throw ScenarioError(links_path, "gives " + std::to_string(links.size() * joints_per_link) +
                                        " joints, at most " +
                                        std::to_string(ScenarioLimits::max_joints) + " allowed");
  if (kind == "dh") {
    std::vector<DhLinkSpec> specs;
    for (size_t i = 0; i < links.size(); ++i) {
      JsonObject link(links[i], index_path(links_path, i));
      link.check_keys({"a", "alpha", "d", "theta", "joint", "radius"});
      DhLinkSpec s;
      s.a = bounded(link, "a", PhysicalBounds::length, units, 0.0);
      s.alpha = bounded(link, "alpha", PhysicalBounds::angle, units, 0.0) * units.angle;
      s.d = bounded(link, "d", PhysicalBounds::length, units, 0.0);
      s.theta = bounded(link, "theta", PhysicalBounds::angle, units, 0.0) * units.angle;
      s.joint = link.choice("joint", {"revolute", "prismatic"}, "revolute") == "prismatic"
                    ? JointType::prismatic
                    : JointType::revolute;
      s.radius = non_negative(link, "radius", PhysicalBounds::length, units, 0.0);
      specs.push_back(s);
    }
    Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
    if (robot.has("base"))
      base.translation() = to_vec3(bounded_numbers(robot, "base", 3, 3, PhysicalBounds::length, units));
    if (robot.has("base_rpy"))
      base.linear() = rpy_matrix(bounded_numbers(robot, "base_rpy", 3, 3, PhysicalBounds::angle, units), units.angle);
    return make_dh(specs, base);
  }
  std::vector<PlanarLinkSpec> specs;
  for (size_t i = 0; i < links.size(); ++i) {
    JsonObject link(links[i], index_path(links_path, i));
    link.check_keys({"length", "radius"});
    specs.push_back({positive(link, "length", PhysicalBounds::length, units),
                     non_negative(link, "radius", PhysicalBounds::length, units, 0.0)});
  }
  if (kind == "planar") {
    if (robot.has("base_rpy")) throw ScenarioError(robot.child("base_rpy"), "only dh robots take base_rpy");
    const std::vector<double> base = robot.has("base") ? bounded_numbers(robot, "base", 2, 2, PhysicalBounds::length, units)
                                                       : std::vector<double>{0, 0};
    return make_planar(specs, {base[0], base[1]});
  }
  if (robot.has("base_rpy")) throw ScenarioError(robot.child("base_rpy"), "only dh robots take base_rpy");
  const std::vector<double> base = robot.has("base") ? bounded_numbers(robot, "base", 3, 3, PhysicalBounds::length, units)
                                                       : std::vector<double>{0, 0, 0};
  return make_spatial_xz(specs, to_vec3(base));
}

// Limits entries may be null (unbounded); angles of revolute joints are converted.
// A key not given keeps the model's limits (unbounded, or a URDF's).
Eigen::VectorXd parse_limit_vector(JsonObject& limits, const std::string& key, const Model& model,
                                   const Eigen::VectorXd& current, const Units& units, double unbounded,
                                   bool must_be_positive, const JointQuantity& quantity) {
  Eigen::VectorXd out = current;
  if (!limits.has(key)) return out;
  const json& v = limits.raw(key);
  const std::string path = limits.child(key);
  if (!v.is_array()) throw ScenarioError(path, "must be an array of numbers, got " + json_type_name(v));
  if (int(v.size()) != model.dof())
    throw ScenarioError(path, "must have " + std::to_string(model.dof()) + " entries (one per joint), got " +
                                  std::to_string(v.size()));
  for (int i = 0; i < model.dof(); ++i) {
    if (v[i].is_null()) {
      out[i] = unbounded;
      continue;
    }
    const JointType type = model.joints[i].type;
    const double scale = type == JointType::revolute ? units.angle : 1.0;
    const double value = json_number(v[i], index_path(path, i));
    if (must_be_positive && !(value > 0)) throw ScenarioError(index_path(path, i), "must be > 0");
    out[i] = check_quantity(value, quantity.of(type), index_path(path, i), scale) * scale;
  }
  return out;
}

// robot.self_collision (default true) and robot.allowed_collisions: pairs of
// 1-based link numbers never checked, as an SRDF's disable list.
void parse_self_collision(JsonObject& robot, Model& model) {
  const bool enabled = robot.boolean("self_collision", true);
  std::vector<SelfPair> allowed;
  if (robot.has("allowed_collisions")) {
    const json& pairs = robot.array("allowed_collisions", size_t(model.link_count()) * size_t(model.link_count()));
    const std::string path = robot.child("allowed_collisions");
    for (size_t i = 0; i < pairs.size(); ++i) {
      const std::string at = index_path(path, i);
      const std::vector<double> links = json_numbers(pairs[i], at, 2, 2);
      for (size_t k = 0; k < 2; ++k)
        if (links[k] != std::floor(links[k]) || links[k] < 1 || links[k] > model.link_count())
          throw ScenarioError(index_path(at, k), "must be a link number from 1 to " + std::to_string(model.link_count()));
      if (links[0] == links[1]) throw ScenarioError(at, "names one link twice: a pair is two links");
      const int a = int(links[0]) - 1, b = int(links[1]) - 1;
      allowed.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  try {
    assign_self_pairs(model, enabled, allowed);
  } catch (const SelfCollisionError& e) {
    throw ScenarioError(robot.child("self_collision"), e.what());
  }
}

void parse_robot(JsonObject robot, const Units& units, const std::string& dir, Scenario& sc) {
  const std::string kind = robot.choice("kind", {"planar", "spatial_xz", "dh", "urdf"});
  if (kind == "urdf") {
    robot.check_keys({"kind", "file", "urdf", "base_link", "tip_link", "link_radius", "base", "base_rpy", "q0", "limits",
                      "self_collision", "allowed_collisions"});
    std::string text;
    sc.model = parse_urdf_robot(robot, units.angle, dir, text);
    // The scenario carries its URDF inline from here on, so a stored run
    // re-simulates without the file (unless the URDF uses mesh files).
    if (!text.empty() && sc.json.is_object() && sc.json["robot"].is_object() && sc.json["robot"].contains("file")) {
      sc.json["robot"].erase("file");
      sc.json["robot"]["urdf"] = text;
    }
  } else {
    robot.check_keys({"kind", "base", "base_rpy", "links", "q0", "limits", "self_collision", "allowed_collisions"});
    sc.model = parse_links(robot, kind, units);
  }
  const int n = sc.model.dof();

  sc.q0 = Eigen::VectorXd::Zero(n);
  if (robot.has("q0")) {
    const json& q0 = robot.raw("q0");
    const std::string path = robot.child("q0");
    if (q0.is_array() && int(q0.size()) != n)
      throw ScenarioError(path, "has " + std::to_string(q0.size()) + " values but the robot has " +
                                    std::to_string(n) + " joints");
    const std::vector<double> values = json_numbers(q0, path, n, n);
    for (int i = 0; i < n; ++i) {
      const JointType type = sc.model.joints[i].type;
      const double scale = type == JointType::revolute ? units.angle : 1.0;
      sc.q0[i] = check_quantity(values[i], kPosition.of(type), index_path(path, i), scale) * scale;
    }
  }

  if (robot.has("limits")) {
    JsonObject limits = robot.object("limits");
    limits.check_keys({"lower", "upper", "velocity", "acceleration"});
    constexpr double inf = std::numeric_limits<double>::infinity();
    JointLimits& l = sc.model.limits;
    l.lower = parse_limit_vector(limits, "lower", sc.model, l.lower, units, -inf, false, kPosition);
    l.upper = parse_limit_vector(limits, "upper", sc.model, l.upper, units, inf, false, kPosition);
    l.velocity = parse_limit_vector(limits, "velocity", sc.model, l.velocity, units, inf, true, kVelocity);
    l.acceleration = parse_limit_vector(limits, "acceleration", sc.model, l.acceleration, units, inf, true, kAcceleration);
    for (int i = 0; i < n; ++i)
      if (l.lower[i] >= l.upper[i])
        throw ScenarioError(index_path(limits.child("lower"), i), "must be below the upper limit");
  }
  parse_self_collision(robot, sc.model);
  // Also against a URDF's own limits when the scenario gives none.
  const JointLimits& l = sc.model.limits;
  for (int i = 0; i < n; ++i) {
    if (sc.q0[i] < l.lower[i] || sc.q0[i] > l.upper[i]) {
      std::ostringstream msg;
      msg << "value " << sc.q0[i] << " rad is outside the joint limits [" << l.lower[i] << ", "
          << l.upper[i] << "]";
      throw ScenarioError(index_path(robot.child("q0"), i), msg.str());
    }
  }
}

// ---- task ----

void parse_trajectory(JsonObject traj, const Units& units, TaskSpace space, TrajectorySpec& t) {
  const std::string type = traj.choice("type", {"polyline", "circle", "ellipse", "joystick"});
  const size_t dims = space == TaskSpace::xy ? 2 : 3;
  auto point = [&](const json& v, const std::string& path) {
    const std::vector<double> p = json_numbers(v, path, dims, dims);
    check_all(p, path, PhysicalBounds::length, units);
    return to_vec3(p);
  };
  auto time_law = [&] {
    return traj.choice("time_law", {"linear", "quintic"}, "linear") == "quintic" ? TimeLaw::quintic
                                                                                   : TimeLaw::linear;
  };
  if (type == "polyline") {
    traj.check_keys({"type", "points", "time_law", "durations"});
    t.type = TrajectoryType::polyline;
    t.time_law = time_law();
    const json& points = traj.array("points", ScenarioLimits::max_path_points);
    if (points.size() < 2) throw ScenarioError(traj.child("points"), "needs at least 2 points");
    for (size_t i = 0; i < points.size(); ++i) t.points.push_back(point(points[i], index_path(traj.child("points"), i)));
    if (traj.has("durations")) {
      t.durations = traj.numbers("durations", points.size() - 1, points.size() - 1);
      for (size_t i = 0; i < t.durations.size(); ++i)
        if (!(t.durations[i] > 0)) throw ScenarioError(index_path(traj.child("durations"), i), "must be > 0");
      check_all(t.durations, traj.child("durations"), PhysicalBounds::time, units);
    }
    return;
  }
  if (type == "joystick") {
    traj.check_keys({"type"});
    t.type = TrajectoryType::joystick;
    return;
  }
  const bool circle = type == "circle";
  if (circle)
    traj.check_keys({"type", "center", "radius", "start_angle", "direction", "turns", "time_law", "normal"});
  else
    traj.check_keys({"type", "center", "semi_axes", "start_angle", "direction", "turns", "time_law", "normal"});
  t.type = circle ? TrajectoryType::circle : TrajectoryType::ellipse;
  t.center = point(traj.raw("center"), traj.child("center"));
  if (circle) {
    t.radius = positive(traj, "radius", PhysicalBounds::length, units);
  } else {
    const std::vector<double> axes = bounded_numbers(traj, "semi_axes", 2, 2, PhysicalBounds::length, units);
    for (int i = 0; i < 2; ++i)
      if (!(axes[i] > 0)) throw ScenarioError(index_path(traj.child("semi_axes"), i), "must be > 0");
    t.semi_axes = {axes[0], axes[1]};
  }
  if (auto a = traj.optional_number("start_angle"))
    t.start_angle = check_quantity(*a, PhysicalBounds::angle, traj.child("start_angle"), units.angle) * units.angle;
  t.clockwise = traj.choice("direction", {"ccw", "cw"}, "ccw") == "cw";
  t.turns = positive(traj, "turns", PhysicalBounds::turns, units, 1.0);
  t.time_law = time_law();
  if (traj.has("normal")) {
    if (space == TaskSpace::xy) throw ScenarioError(traj.child("normal"), "only 3D task spaces take a normal");
    t.normal = to_vec3(bounded_numbers(traj, "normal", 3, 3, PhysicalBounds::length, units));
    if (t.normal.norm() < 1e-12) throw ScenarioError(traj.child("normal"), "must not be zero");
    t.normal.normalize();
  }
}

void parse_task(JsonObject task, const Units& units, Scenario& sc) {
  task.check_keys({"space", "gain", "trajectory", "orientation"});
  const std::string space = task.choice("space", {"xy", "xyz", "pose"}, "xy");
  sc.task.space = space == "xy" ? TaskSpace::xy : space == "xyz" ? TaskSpace::xyz : TaskSpace::pose;
  if (sc.model.kind == ModelKind::planar && sc.task.space != TaskSpace::xy)
    throw ScenarioError(task.child("space"), "a planar robot can only track an \"xy\" task");
  if (task_rows(sc.task.space) > sc.model.dof())
    throw ScenarioError(task.child("space"), "\"" + space + "\" needs at least " +
                                                 std::to_string(task_rows(sc.task.space)) + " joints, the robot has " +
                                                 std::to_string(sc.model.dof()));
  if (auto gain = task.optional_number("gain")) {
    if (!(*gain >= 0) || *gain * sc.dt > 1.0)
      throw ScenarioError(task.child("gain"), "must be in [0, 1/dt] so the discrete loop is stable");
    sc.task.gain = *gain;
  }
  if (task.has("orientation")) {
    if (sc.task.space != TaskSpace::pose)
      throw ScenarioError(task.child("orientation"), "only \"pose\" tasks take an orientation");
    sc.task.orientation =
        rpy_matrix(bounded_numbers(task, "orientation", 3, 3, PhysicalBounds::angle, units), units.angle);
  }
  parse_trajectory(task.object("trajectory"), units, sc.task.space, sc.task.trajectory);
}

// ---- witness ----

// "witness": {"dt", "q": [[...], ...], "difficulty": {...}}: samples from
// t = 0 every dt covering the run, starting at q0, in the file's angle unit.
// Whether it solves the task is what `--method witness` shows, not a parse rule.
void parse_witness(JsonObject w, const Units& units, Scenario& sc) {
  w.check_keys({"dt", "q", "difficulty"});
  auto witness = std::make_shared<WitnessTrajectory>();
  witness->dt = w.number("dt");
  if (!(witness->dt >= 1e-6) || witness->dt > sc.duration)
    throw ScenarioError(w.child("dt"), "must be in [1e-6 s, duration], got " + format_number(witness->dt));
  const int n = sc.model.dof();
  const json& rows = w.array("q", size_t(ScenarioLimits::max_witness_numbers / std::max(n, 1)));
  const double needed = std::ceil(sc.duration / witness->dt - 1e-9) + 1;
  if (double(rows.size()) < needed)
    throw ScenarioError(w.child("q"), "has " + std::to_string(rows.size()) + " samples; every " +
                                          format_number(witness->dt) + " s over the run's " +
                                          format_number(sc.duration) + " s needs " + format_number(needed));
  for (size_t k = 0; k < rows.size(); ++k) {
    const std::string path = index_path(w.child("q"), k);
    const std::vector<double> values = json_numbers(rows[k], path, size_t(n), size_t(n));
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) {
      const JointType type = sc.model.joints[i].type;
      const double scale = type == JointType::revolute ? units.angle : 1.0;
      q[i] = check_quantity(values[i], kPosition.of(type), index_path(path, i), scale) * scale;
    }
    witness->q.push_back(std::move(q));
  }
  if ((witness->q[0] - sc.q0).cwiseAbs().maxCoeff() > 1e-9)
    throw ScenarioError(index_path(w.child("q"), 0), "must be robot.q0, where the run starts");
  if (w.has("difficulty")) {
    const json& difficulty = w.raw("difficulty");
    if (!difficulty.is_object()) throw ScenarioError(w.child("difficulty"), "must be an object of numbers");
    for (auto it = difficulty.begin(); it != difficulty.end(); ++it)
      if (!it.value().is_number()) throw ScenarioError(w.child("difficulty") + "." + it.key(), "must be a number");
  }
  sc.witness = std::move(witness);
}

// ---- method ----

void parse_method(JsonObject method, Scenario& sc) {
  method.check_keys({"name", "params", "origin"});
  sc.method.name = method.string("name");
  // "origin": "python" marks a method written in Python (a run stored by the
  // Python package): only a Python process that registered it can run it
  if (method.has("origin")) {
    const std::string origin = method.string("origin");
    if (origin != "python") throw ScenarioError(method.child("origin"), "must be \"python\" (or absent: built in)");
    const MethodInfo* known = find_method(sc.method.name);
    if (known && !known->python)
      throw ScenarioError(method.child("origin"), "\"python\", but \"" + sc.method.name + "\" is a built-in method");
    if (!known)
      throw ScenarioError(method.child("name"), "\"" + sc.method.name +
                                                    "\" is a method written in Python: run it from Python with its "
                                                    "class registered (rrlab.register_method), not from this process");
  }
  require_method(sc.method.name, method.child("name"));
  if (method.has("params"))
    sc.method.params = resolve_method_params(sc.method.name, method.raw("params"), method.child("params"));
}

}  // namespace scenario_parsing

void require_method(const std::string& name, const std::string& path) {
  if (!find_method(name)) throw ScenarioError(path, "unknown method \"" + name + "\" (known: " + method_names() + ")");
}

std::vector<std::pair<std::string, double>> resolve_method_params(const std::string& method,
                                                                  const nlohmann::json& params,
                                                                  const std::string& path) {
  const JsonObject object(params, path);
  std::vector<std::pair<std::string, double>> resolved;
  for (auto it = params.begin(); it != params.end(); ++it)
    resolved.push_back(resolve_method_param(method, it.key(), it.value(), object.child(it.key())));
  return resolved;
}

long Scenario::steps() const { return std::lround(duration / dt); }

std::pair<std::string, double> resolve_method_param(const std::string& method_name,
                                                    const std::string& name,
                                                    const nlohmann::json& value,
                                                    const std::string& path) {
  const MethodInfo* info = find_method(method_name);
  if (!info) throw ScenarioError(path, "unknown method \"" + method_name + "\"");
  const int index = find_param(info->params, name);
  if (index < 0) {
    std::string known;
    for (const ParamSpec& s : info->params) known += (known.empty() ? "" : ", ") + s.name;
    throw ScenarioError(path, "unknown parameter of " + method_name + " (known: " +
                                  (known.empty() ? "none" : known) + ")");
  }
  const ParamSpec& spec = info->params[index];
  double v = 0;
  if (value.is_string() && !spec.choices.empty()) {
    const int c = choice_index(spec, value.get<std::string>());
    if (c < 0) throw ScenarioError(path, param_problem(spec, -1));
    v = c;
  } else {
    v = json_number(value, path);
  }
  const std::string problem = param_problem(spec, v);
  if (!problem.empty()) throw ScenarioError(path, problem);
  return {name, v};
}

namespace {

std::mutex catalogue_mutex;
std::string& catalogue_dir() {
  static std::string dir;
  return dir;
}

}  // namespace

void set_scenario_catalogue_dir(const std::string& dir) {
  std::lock_guard lock(catalogue_mutex);
  catalogue_dir() = dir;
}

std::string scenario_catalogue_dir() {
  std::lock_guard lock(catalogue_mutex);
  return catalogue_dir();
}

Scenario parse_scenario(const json& doc, const std::string& dir) {
  JsonObject root(doc, "");
  root.check_keys({"name", "description", "source", "dt", "duration", "angle_unit", "seed", "robot",
                   "obstacles", "task", "method", "witness", "perturbation"});
  Scenario sc;
  sc.json = doc;
  sc.name = root.string("name", "unnamed");
  sc.description = root.string("description", "");
  sc.source = root.string("source", "");
  sc.dt = root.number("dt", 0.01);
  if (!(sc.dt > 0) || sc.dt > 1.0) throw ScenarioError("dt", "must be in (0, 1] s");
  sc.duration = root.number("duration", 10.0);
  if (!(sc.duration > 0)) throw ScenarioError("duration", "must be > 0 s");
  // Compared in double: duration/dt may be far beyond any integer.
  if (sc.duration / sc.dt > double(ScenarioLimits::max_steps))
    throw ScenarioError("duration", "must give at most " + std::to_string(ScenarioLimits::max_steps) +
                                        " steps of dt = " + format_number(sc.dt) + " s (at most " +
                                        format_number(double(ScenarioLimits::max_steps) * sc.dt) + " s), got " +
                                        format_number(sc.duration) + " s");
  if (sc.steps() < 1) throw ScenarioError("duration", "must be at least one step (dt)");
  scenario_parsing::Units units;
  if (root.choice("angle_unit", {"rad", "deg"}, "rad") == "deg") units.angle = M_PI / 180.0;
  if (root.has("seed")) {
    const json& seed = root.raw("seed");
    if (!seed.is_number_integer() || seed.get<long long>() < 0)
      throw ScenarioError("seed", "must be a non-negative integer");
    sc.seed = seed.get<std::uint64_t>();
  }
  scenario_parsing::parse_robot(root.object("robot"), units, dir, sc);
  if (root.has("obstacles")) scenario_parsing::parse_obstacles(root.raw("obstacles"), "obstacles", units, dir, sc);
  scenario_parsing::parse_task(root.object("task"), units, sc);
  if (root.has("witness")) scenario_parsing::parse_witness(root.object("witness"), units, sc);
  if (root.has("perturbation")) root.object("perturbation");  // a record of how the case was drawn (perturbation.hpp)
  if (root.has("method")) {
    scenario_parsing::parse_method(root.object("method"), sc);
  } else {
    sc.method.name = "pinv";
  }
  return sc;
}

Scenario parse_scenario_text(const std::string& text) {
  json doc;
  try {
    doc = parse_json(text);
  } catch (const TooDeepError& e) {
    throw ScenarioError("", std::string("invalid JSON: ") + e.what());
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number beyond double
    throw ScenarioError("", std::string("invalid JSON: ") + e.what());
  }
  return parse_scenario(doc);
}

json read_json_file(const std::string& file, const std::string& what) {
  std::ifstream in(file);
  if (!in) throw ScenarioError("", "cannot read " + what + " '" + file + "'");
  std::stringstream buffer;
  buffer << in.rdbuf();
  try {
    return parse_json(buffer.str());
  } catch (const TooDeepError& e) {
    throw ScenarioError("", what + " '" + file + "' is not valid JSON: " + e.what());
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number beyond double
    throw ScenarioError("", what + " '" + file + "' is not valid JSON: " + e.what());
  }
}

Scenario load_scenario_file(const std::string& file) {
  const std::string dir = std::filesystem::path(file).parent_path().string();
  return parse_scenario(read_json_file(file, "scenario file"), dir.empty() ? "." : dir);
}

}  // namespace rrlab
