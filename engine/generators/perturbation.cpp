#include <rrlab/generators/perturbation.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/self_collision.hpp>
#include <rrlab/generators/generator_clearance.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/scenario/physical_bounds.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/task/task.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {

namespace {

constexpr double kPerturbStep = 0.01;           // rad: arc length per self-motion step
constexpr int kPerturbNewton = 30;              // Newton iterations back onto the hand pose per step
constexpr double kPerturbHandTolerance = 1e-10; // m, rad: the hand "stays where it was"
constexpr double kPerturbDamping = 1e-9;
constexpr double kPerturbMaxShift = 10.0;       // m
constexpr double kPerturbMaxShiftReach = 1.0;   // of the reach
constexpr double kPerturbSpeedFrom = 0.05, kPerturbSpeedTo = 20.0;

// A number in [lo, hi] at `path`.
double perturb_number(JsonObject& object, const std::string& key, double lo, double hi) {
  const double v = object.number(key);
  if (!(v >= lo && v <= hi))
    throw ScenarioError(object.child(key), "must be in [" + format_number(lo) + ", " + format_number(hi) + "], got " +
                                               format_number(v));
  return v;
}

// A vector uniform in the unit disc (dims 2) or ball (3), by rejection; one draw per statement.
Eigen::Vector3d perturb_in_ball(Rng& rng, int dims) {
  for (;;) {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int k = 0; k < dims; ++k) {
      const double u = rng.uniform(-1.0, 1.0);
      v[k] = u;
    }
    if (v.squaredNorm() <= 1.0) return v;
  }
}

// Coordinates a vector is written with: a shift is rounded to 0.1 mm, sums to 1 µm.
double perturb_written(double value) { return rounded(value, 1e-6); }

void perturb_shift_point(nlohmann::json& point, const Eigen::Vector3d& d) {
  for (size_t k = 0; k < point.size() && k < 3; ++k) point[k] = perturb_written(point[k].get<double>() + d[int(k)]);
}

// Where an obstacle is in x-y: a polygon's mean point, a box's, sphere's or
// mesh's centre, a point's position, a wall's point.
Eigen::Vector2d perturb_place(const nlohmann::json& o) {
  const std::string shape = o.value("shape", "");
  const char* key = shape == "point" ? "position" : shape == "wall" ? "point" : "center";
  if (shape == "polygon") {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : o["points"]) mean += Eigen::Vector2d(p[0].get<double>(), p[1].get<double>());
    return mean / double(o["points"].size());
  }
  if (!o.contains(key)) return Eigen::Vector2d::Zero();
  return {o[key][0].get<double>(), o[key][1].get<double>()};
}

// Obstacle `o` turned by `turn` (rad; the file's angles are `scale` rad per
// unit) about the vertical through `pivot`, then moved by d: its place goes
// round the pivot and it turns by the same angle about its own vertical.
void perturb_obstacle(nlohmann::json& o, const Eigen::Vector3d& d, double turn, const Eigen::Vector2d& pivot,
                      double scale) {
  const std::string shape = o.value("shape", "");
  const double c = std::cos(turn), s = std::sin(turn);
  const Eigen::Vector2d place = perturb_place(o), r = place - pivot;
  const Eigen::Vector2d moved = pivot + Eigen::Vector2d(c * r.x() - s * r.y(), s * r.x() + c * r.y()) + d.head<2>();
  const Eigen::Vector3d D(moved.x() - place.x(), moved.y() - place.y(), d.z());
  if (shape == "polygon") {
    for (auto& p : o["points"]) {
      const Eigen::Vector2d q = Eigen::Vector2d(p[0].get<double>(), p[1].get<double>()) - place;
      p[0] = perturb_written(place.x() + c * q.x() - s * q.y() + D.x());
      p[1] = perturb_written(place.y() + s * q.x() + c * q.y() + D.y());
    }
    if (D.z() != 0) {
      nlohmann::json z = o.contains("z") ? o["z"] : nlohmann::json::array({-1.0, 1.0});
      for (auto& v : z) v = perturb_written(v.get<double>() + D.z());
      o["z"] = z;
    }
  } else if (shape == "box" || shape == "mesh") {
    // R = Rz(y) Ry(p) Rx(r): adding to y turns the obstacle about the world's z through its centre
    if (o.contains("center")) perturb_shift_point(o["center"], D);
    if (turn != 0) {
      nlohmann::json rpy = o.contains("rpy") ? o["rpy"] : nlohmann::json::array({0.0, 0.0, 0.0});
      rpy[2] = rounded(rpy[2].get<double>() + turn / scale, 1e-9);
      o["rpy"] = rpy;
    }
  } else if (shape == "sphere") {
    perturb_shift_point(o["center"], D);
  } else if (shape == "point") {
    perturb_shift_point(o["position"], D);
  } else if (shape == "wall") {
    perturb_shift_point(o["point"], D);
    auto& n = o["normal"];
    const double x = n[0].get<double>(), y = n[1].get<double>();
    n[0] = rounded(c * x - s * y, 1e-12);
    n[1] = rounded(s * x + c * y, 1e-12);
  }
}

void perturb_path(nlohmann::json& trajectory, const Eigen::Vector3d& d) {
  const std::string type = trajectory.value("type", "");
  if (type == "polyline") {
    for (auto& p : trajectory["points"]) perturb_shift_point(p, d);
  } else if (type == "circle" || type == "ellipse") {
    perturb_shift_point(trajectory["center"], d);
  }
}

void perturb_speed(nlohmann::json& doc, double s) {
  doc["duration"] = perturb_written(doc.value("duration", 10.0) / s);
  nlohmann::json& trajectory = doc["task"]["trajectory"];
  if (trajectory.contains("durations"))
    for (auto& d : trajectory["durations"]) d = perturb_written(d.get<double>() / s);
}

// The task rows of the hand at `kin` against the target pose.
void perturb_hand_error(TaskSpace space, const KinematicsData& kin, const Eigen::Isometry3d& target, Eigen::VectorXd& e) {
  const Eigen::Vector3d dp = target.translation() - kin.end_effector().translation();
  switch (space) {
    case TaskSpace::xy: e = dp.head<2>(); break;
    case TaskSpace::xyz: e = dp; break;
    case TaskSpace::pose:
      e.head<3>() = dp;
      e.tail<3>() = orientation_error(target.linear(), kin.end_effector().linear());
      break;
  }
}

// q moved `arc` rad along the self-motion manifold, starting in the null-space
// direction nearest `z` and following it; false when the hand could not be kept.
bool perturb_self_motion(const Scenario& sc, Eigen::VectorXd& q, Eigen::VectorXd z, double arc) {
  const Model& model = sc.model;
  const TaskSpace space = sc.task.space;
  const int n = model.dof(), m = task_rows(space);
  if (m >= n || arc <= 0) return true;
  KinematicsData kin(model);
  forward_kinematics(model, q, kin);
  const Eigen::Isometry3d target = kin.end_effector();
  Eigen::MatrixXd jac(m, n);
  RightInverse inverse(m, n);
  Eigen::VectorXd e(m), dq(n), along(n);
  const int steps = std::max(1, int(std::ceil(arc / kPerturbStep)));
  const double h = arc / steps;
  for (int k = 0; k < steps; ++k) {
    task_jacobian(model, kin, space, jac);
    inverse.factor_pinv(jac);
    inverse.null_project(z, along);  // (I − J⁺J) z: invisible at the hand to first order
    const double norm = along.norm();
    if (!(norm > 1e-9)) return false;  // no self-motion here (a singular arm)
    z = along / norm;
    q += h * z;
    bool held = false;
    for (int it = 0; it < kPerturbNewton && !held; ++it) {
      forward_kinematics(model, q, kin);
      perturb_hand_error(space, kin, target, e);
      if (e.norm() < kPerturbHandTolerance) {
        held = true;
        break;
      }
      task_jacobian(model, kin, space, jac);
      inverse.factor_dls(jac, kPerturbDamping);
      inverse.apply(e, dq);
      q += dq;
    }
    if (!held) return false;
  }
  return q.allFinite();
}

// Why a draw is drawn again, counted for the error when none passes.
enum class PerturbRedraw { lost_hand, joint_limit, self_collision, obstacle, count };
constexpr const char* kPerturbRedrawWhy[] = {"lost the hand along the self-motion", "left a joint limit",
                                             "touched itself", "touched an obstacle"};

// The least link-obstacle distance of the arm at `q` (+inf without obstacles).
double perturb_clearance(const Model& model, const Scene& scene, const Eigen::VectorXd& q) {
  if (scene.obstacles.empty()) return std::numeric_limits<double>::infinity();
  KinematicsData kin(model);
  forward_kinematics(model, q, kin);
  CollisionWorld world(model, scene);
  DistanceTable table;
  table.resize(model.link_count(), int(scene.obstacles.size()));
  world.compute(kin, table);
  return table.min_distance;
}

// The start a case's document will give: each joint written in the file's
// unit and read back as the parser reads it (the limits are read the same way).
Eigen::VectorXd perturb_start_as_read(const Model& model, const Eigen::VectorXd& q, double scale, nlohmann::json& q0) {
  Eigen::VectorXd read(q.size());
  q0 = nlohmann::json::array();
  for (int j = 0; j < model.dof(); ++j) {
    const bool revolute = model.joints[size_t(j)].type == JointType::revolute;
    const double written = revolute ? q[j] / scale : q[j];
    q0.push_back(written);
    read[j] = revolute ? written * scale : written;
  }
  return read;
}

// Whether the start `q` of the (unchanged) robot is inside its limits and clear of itself.
std::optional<PerturbRedraw> perturb_start_problem(const Model& model, const Eigen::VectorXd& q) {
  for (int j = 0; j < model.dof(); ++j)
    if (q[j] < model.limits.lower[j] || q[j] > model.limits.upper[j]) return PerturbRedraw::joint_limit;
  if (!(min_self_distance(model, q) > 0)) return PerturbRedraw::self_collision;
  return std::nullopt;
}

// The radius a shift moves by: its metres, or its fraction of the reach
// capped at its fraction of the free gap (to 1 µm).
double perturb_radius(const PerturbationShift& shift, const PerturbationScale& scale) {
  if (!shift.sized_to_scene()) return shift.metres;
  double radius = shift.reach * scale.reach;
  if (std::isfinite(scale.free_gap)) radius = std::min(radius, shift.gap * std::max(scale.free_gap, 0.0));
  return rounded(radius, 1e-6);
}

// "shift" or "shift_reach" (with its "shift_gap") of an options object.
PerturbationShift perturb_shift(JsonObject& object) {
  PerturbationShift shift;
  if (object.has("shift") && object.has("shift_reach"))
    throw ScenarioError(object.child("shift_reach"), "give shift (m) or shift_reach (a fraction of the reach), not both");
  if (object.has("shift_gap") && !object.has("shift_reach"))
    throw ScenarioError(object.child("shift_gap"), "caps shift_reach: give shift_reach with it");
  if (object.has("shift")) shift.metres = perturb_number(object, "shift", 0, kPerturbMaxShift);
  if (object.has("shift_reach")) shift.reach = perturb_number(object, "shift_reach", 0, kPerturbMaxShiftReach);
  if (object.has("shift_gap")) {
    shift.gap = object.number("shift_gap");
    if (!(shift.gap > 0 && shift.gap <= 1))
      throw ScenarioError(object.child("shift_gap"),
                          "must be in (0, 1] (a fraction of the free gap), got " + format_number(shift.gap));
  }
  return shift;
}

nlohmann::json perturb_vector_json(const Eigen::Vector3d& d, int dims) {
  nlohmann::json v = nlohmann::json::array();
  for (int k = 0; k < dims; ++k) v.push_back(d[k]);
  return v;
}

}  // namespace

bool PerturbationOptions::changes_anything() const {
  const auto moves = [](const PerturbationShift& shift) { return shift.metres > 0 || shift.reach > 0; };
  return moves(obstacle_shift) || obstacle_rotate_deg > 0 || speed_min != 1 || speed_max != 1 || q0_self_motion > 0 ||
         moves(path_shift);
}

PerturbationScale perturbation_scale(const Scenario& sc) {
  PerturbationScale scale;
  scale.reach = sc.model.reach();
  scale.free_gap = perturb_clearance(sc.model, sc.scene, sc.q0);
  const std::vector<Obstacle>& obstacles = sc.scene.obstacles;
  for (size_t a = 0; a < obstacles.size(); ++a)
    for (size_t b = a + 1; b < obstacles.size(); ++b) {
      const double apart = obstacles_distance(obstacles[a], obstacles[b]);
      if (apart > 0) scale.free_gap = std::min(scale.free_gap, apart);
    }
  return scale;
}

PerturbationOptions parse_perturbation_options(const nlohmann::json& entry, const std::string& path) {
  PerturbationOptions out;
  JsonObject root(entry, path);
  if (root.has("obstacles")) {
    JsonObject obstacles = root.object("obstacles");
    obstacles.check_keys({"shift", "shift_reach", "shift_gap", "rotate_deg", "together"});
    if (obstacles.has("together")) {
      const nlohmann::json& together = obstacles.raw("together");
      if (!together.is_boolean())
        throw ScenarioError(obstacles.child("together"), "must be true or false, got " + json_type_name(together));
      out.obstacles_together = together.get<bool>();
    }
    out.obstacle_shift = perturb_shift(obstacles);
    if (obstacles.has("rotate_deg")) out.obstacle_rotate_deg = perturb_number(obstacles, "rotate_deg", 0, 180);
  }
  if (root.has("speed")) {
    const nlohmann::json& speed = root.raw("speed");
    if (speed.is_number()) {
      out.speed_min = out.speed_max = perturb_number(root, "speed", kPerturbSpeedFrom, kPerturbSpeedTo);
    } else {
      const std::vector<double> range = root.numbers("speed", 2, 2);
      for (size_t k = 0; k < 2; ++k)
        if (!(range[k] >= kPerturbSpeedFrom && range[k] <= kPerturbSpeedTo))
          throw ScenarioError(index_path(root.child("speed"), k),
                              "must be in [" + format_number(kPerturbSpeedFrom) + ", " + format_number(kPerturbSpeedTo) +
                                  "] (a factor on the path's speed), got " + format_number(range[k]));
      if (range[0] > range[1]) throw ScenarioError(root.child("speed"), "must be [min, max] with min <= max");
      out.speed_min = range[0];
      out.speed_max = range[1];
    }
  }
  if (root.has("q0_self_motion")) out.q0_self_motion = perturb_number(root, "q0_self_motion", 0, 2 * M_PI);
  if (root.has("path")) {
    JsonObject p = root.object("path");
    p.check_keys({"shift", "shift_reach", "shift_gap"});
    out.path_shift = perturb_shift(p);
  }
  return out;
}

nlohmann::json perturb_scenario(const nlohmann::json& base, const std::string& dir, const std::string& name,
                                const PerturbationOptions& options, std::uint64_t seed, int index) {
  PerturbationScale scale;
  if (options.sized_to_scene()) scale = perturbation_scale(parse_scenario(base, dir));
  return perturb_scenario(base, dir, name, options, scale, seed, index);
}

nlohmann::json perturb_scenario(const nlohmann::json& base, const std::string& dir, const std::string& name,
                                const PerturbationOptions& options, const PerturbationScale& scale, std::uint64_t seed,
                                int index) {
  if (index < 0) throw ScenarioError("index", "must be >= 0");
  const Scenario sc = parse_scenario(base, dir);
  const bool deg = base.value("angle_unit", "rad") == "deg";
  const double scale_unit = deg ? M_PI / 180.0 : 1.0;
  const bool planar_robot = sc.model.kind == ModelKind::planar;
  const int obstacle_dims = planar_robot ? 2 : 3;
  const int path_dims = sc.task.space == TaskSpace::xy ? 2 : 3;
  const double obstacle_radius = perturb_radius(options.obstacle_shift, scale);
  const double path_radius = perturb_radius(options.path_shift, scale);
  const std::string family = "perturb:" + name;
  GeneratorCase c(family, nlohmann::json::object(), seed, index);
  Rng& rng = c.rng;
  int redrawn[int(PerturbRedraw::count)] = {};
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    nlohmann::json doc = base;
    nlohmann::json record = {{"of", name}, {"seed", seed}, {"index", index}, {"attempt", attempt}};
    // every quantity is drawn whether or not it applies, in one order: a
    // case's draws do not depend on the scenario's obstacle shapes
    nlohmann::json moved = nlohmann::json::array();
    if (doc.contains("obstacles") && !doc["obstacles"].empty()) {
      // together: one draw for the scene, turned about the mean of the obstacles' places
      Eigen::Vector2d centre = Eigen::Vector2d::Zero();
      for (const auto& o : doc["obstacles"]) centre += perturb_place(o) / double(doc["obstacles"].size());
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      double turn_deg = 0;
      for (size_t k = 0; k < doc["obstacles"].size(); ++k) {
        nlohmann::json& o = doc["obstacles"][k];
        if (k == 0 || !options.obstacles_together) {
          const Eigen::Vector3d unit = perturb_in_ball(rng, obstacle_dims);
          d = (obstacle_radius * unit).unaryExpr([](double v) { return rounded(v); });
          const double u = rng.uniform(-1.0, 1.0);
          turn_deg = rounded(options.obstacle_rotate_deg * u, 0.01);
        }
        const Eigen::Vector2d pivot = options.obstacles_together ? centre : perturb_place(o);
        perturb_obstacle(o, d, turn_deg * M_PI / 180.0, pivot, scale_unit);
        moved.push_back({{"id", o.value("id", "")}, {"shift", perturb_vector_json(d, obstacle_dims)}, {"rotate_deg", turn_deg}});
      }
    }
    record["obstacles"] = moved;
    const double w = rng.uniform();
    const double s = rounded(std::exp(std::log(options.speed_min) + w * (std::log(options.speed_max) - std::log(options.speed_min))), 1e-3);
    if (s != 1) perturb_speed(doc, s);
    record["speed"] = s;
    const Eigen::Vector3d path_unit = perturb_in_ball(rng, path_dims);
    const Eigen::Vector3d path_d = (path_radius * path_unit).unaryExpr([](double v) { return rounded(v); });
    if (path_d.norm() > 0) perturb_path(doc["task"]["trajectory"], path_d);
    record["path_shift"] = perturb_vector_json(path_d, path_dims);
    const double a = rng.uniform();
    const double arc = rounded(options.q0_self_motion * a, 1e-4);
    Eigen::VectorXd z(sc.model.dof());
    for (int j = 0; j < sc.model.dof(); ++j) {
      const double g = rng.normal();
      z[j] = g;
    }
    record["q0_self_motion"] = arc;
    if (options.sized_to_scene()) {  // what the fractions came to, so the case reads without the scenario
      const nlohmann::json free_gap = std::isfinite(scale.free_gap) ? nlohmann::json(rounded(scale.free_gap, 1e-6)) : nlohmann::json();
      record["sized_to_scene"] = {{"reach", rounded(scale.reach, 1e-6)},
                                  {"free_gap", free_gap},
                                  {"obstacle_shift", obstacle_radius},
                                  {"path_shift", path_radius}};
    }
    // the start, checked before the document is read: the parser refuses a start outside the limits
    Eigen::VectorXd start = sc.q0;
    if (arc > 0) {
      Eigen::VectorXd q = sc.q0;
      if (!perturb_self_motion(sc, q, z, arc)) {
        ++redrawn[int(PerturbRedraw::lost_hand)];
        continue;
      }
      nlohmann::json q0;
      start = perturb_start_as_read(sc.model, q, scale_unit, q0);
      doc["robot"]["q0"] = q0;
    }
    if (const auto problem = perturb_start_problem(sc.model, start)) {
      ++redrawn[int(*problem)];
      continue;
    }
    if (options.changes_anything()) doc.erase("witness");  // it solved the scenario before the nudge
    doc["name"] = sc.name + "-p" + std::to_string(index);
    doc["description"] = "Perturbation " + std::to_string(index) + " (seed " + std::to_string(seed) + ") of " + name +
                         " (obstacles moved up to " + fixed_digits(obstacle_radius, 3) + " m and turned up to " +
                         fixed_digits(options.obstacle_rotate_deg, 1) + " deg, path speed x" + fixed_digits(s, 3) +
                         ", start moved " + fixed_digits(arc, 4) + " rad along the self-motion manifold, path moved " +
                         fixed_digits(path_d.norm(), 4) + " m; \"perturbation\" has each draw). " +
                         base.value("description", "");
    doc["perturbation"] = record;
    const Scenario drawn = parse_scenario(doc, dir);
    if (perturb_clearance(drawn.model, drawn.scene, drawn.q0) > 0) return doc;
    ++redrawn[int(PerturbRedraw::obstacle)];
  }
  std::string why;
  for (int r = 0; r < int(PerturbRedraw::count); ++r)
    if (redrawn[r] > 0) why += std::string(why.empty() ? "" : ", ") + std::to_string(redrawn[r]) + " " + kPerturbRedrawWhy[r];
  const bool obstacles = redrawn[int(PerturbRedraw::obstacle)] > 0;
  const std::string shift_key = options.obstacle_shift.sized_to_scene() ? "obstacles.shift_reach" : "obstacles.shift";
  const std::string remedy = obstacles ? "reduce " + shift_key + ", obstacles.rotate_deg or q0_self_motion"
                             : options.q0_self_motion > 0
                                 ? "reduce q0_self_motion"
                                 : "the scenario's own start touches itself (robot.q0, robot.allowed_collisions)";
  throw ScenarioError("perturb", "no perturbation of " + name +
                                     " started inside the joint limits, clear of obstacles and of itself in " +
                                     std::to_string(kCaseAttempts) + " draws (" + why + "): " + remedy);
}

}  // namespace rrlab
