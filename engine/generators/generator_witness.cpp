#include <rrlab/generators/generator_witness.hpp>

#include <algorithm>
#include <cmath>

#include <rrlab/collision/allowed_collisions.hpp>
#include <rrlab/collision/self_collision.hpp>
#include <rrlab/generators/generator_blocking.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/task/trajectory.hpp>

namespace rrlab {

namespace {

constexpr int kArcSamples = 32;        // per segment, for the hand's arc length
constexpr double kHandStep = 1e-6;     // m: hand positions as written
constexpr double kQuinticPeak = 1.875;  // peak of d/dτ (10τ³ − 15τ⁴ + 6τ⁵)
constexpr long kMaxWitnessSteps = 200'000;

struct Segments {
  std::vector<Eigen::VectorXd> from, to;
  std::vector<long> end_step;  // cumulative, in steps
  TimeLaw law = TimeLaw::quintic;
};

// The smooth witness at step k (before sampling).
void smooth_at(const Segments& s, long k, Eigen::VectorXd& q) {
  size_t i = 0;
  while (i + 1 < s.end_step.size() && k > s.end_step[i]) ++i;
  const long begin = i == 0 ? 0 : s.end_step[i - 1];
  const double tau = std::clamp(double(k - begin) / double(s.end_step[i] - begin), 0.0, 1.0);
  q = s.from[i] + time_law_progress(s.law, tau) * (s.to[i] - s.from[i]);
}

double hand_arc_length(const Model& model, const Eigen::VectorXd& a, const Eigen::VectorXd& b, KinematicsData& kin) {
  double length = 0;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (int j = 0; j <= kArcSamples; ++j) {
    forward_kinematics(model, a + (double(j) / kArcSamples) * (b - a), kin);
    const Eigen::Vector3d p = kin.end_effector().translation();
    if (j > 0) length += (p - previous).norm();
    previous = p;
  }
  return length;
}

Eigen::Vector3d rounded_hand(const Model& model, const Eigen::VectorXd& q, KinematicsData& kin) {
  forward_kinematics(model, q, kin);
  const Eigen::Vector3d p = kin.end_effector().translation();
  return {rounded(p.x(), kHandStep), rounded(p.y(), kHandStep), rounded(p.z(), kHandStep)};
}

// Samples every m steps of the smooth witness, the played-back steps between
// them and how far the played-back hand comes from the task's polyline (and,
// with an orientation, from it).
void sample(const Model& model, const SmoothWitness& smooth_at, long steps, long m, const Eigen::Matrix3d* orientation,
            KinematicsData& kin, GeneratedWitness& w) {
  w.samples.clear();
  w.hand.clear();
  w.steps.clear();
  Eigen::VectorXd q;
  const long intervals = (steps + m - 1) / m;  // the last may hold the end configuration
  for (long j = 0; j <= intervals; ++j) {
    smooth_at(std::min(j * m, steps), q);
    for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = rounded(q[i], kSampleStep);
    w.samples.push_back(q);
    w.hand.push_back(rounded_hand(model, q, kin));
  }
  w.interpolation_error = 0;
  w.orientation_error = 0;
  for (long k = 0; k <= intervals * m; ++k) {
    const long j = std::min(k / m, intervals - 1);
    const double u = double(k - j * m) / double(m);
    w.steps.push_back(w.samples[j] + u * (w.samples[j + 1] - w.samples[j]));
    forward_kinematics(model, w.steps.back(), kin);
    const Eigen::Vector3d reference = w.hand[j] + u * (w.hand[j + 1] - w.hand[j]);
    w.interpolation_error = std::max(w.interpolation_error, (kin.end_effector().translation() - reference).norm());
    if (orientation)
      w.orientation_error = std::max(w.orientation_error, orientation_error(*orientation, kin.end_effector().linear()).norm());
  }
}

}  // namespace

double witness_speed(const PathOptions& options, double reach, Rng& rng) {
  const double speed = options.speed ? rounded(options.speed->draw(rng), 1e-3) : rounded(kDefaultSpeedPerReach * reach, 1e-3);
  return std::max(speed, 1e-3);
}

std::optional<GeneratedWitness> build_witness(const Model& model, const std::vector<Eigen::VectorXd>& configurations,
                                              const PathOptions& options, double reach, TaskSpace space, Rng& rng) {
  GeneratedWitness w;
  w.step_dt = options.dt;
  w.time_law = options.time_law;
  w.speed = witness_speed(options, reach, rng);
  Segments segments;
  segments.law = options.time_law == "linear" ? TimeLaw::linear : TimeLaw::quintic;
  const double peak = segments.law == TimeLaw::linear ? 1.0 : kQuinticPeak;
  KinematicsData kin(model);
  long steps = 0;
  for (size_t i = 1; i < configurations.size(); ++i) {
    const Eigen::VectorXd& a = configurations[i - 1];
    const Eigen::VectorXd& b = configurations[i];
    double seconds = hand_arc_length(model, a, b, kin) / w.speed;
    if (model.limits.has_velocity())
      for (Eigen::Index j = 0; j < a.size(); ++j)
        if (std::isfinite(model.limits.velocity[j]))
          seconds = std::max(seconds, peak * std::abs(b[j] - a[j]) / (kVelocityLimitShare * model.limits.velocity[j]));
    steps += std::max(1L, long(std::ceil(seconds / options.dt - 1e-9)));
    if (steps > kMaxWitnessSteps)
      throw ScenarioError("options.speed", "with this dt the path needs more than " +
                                               std::to_string(kMaxWitnessSteps) +
                                               " steps (every step of a witness is checked); raise speed or dt");
    segments.from.push_back(a);
    segments.to.push_back(b);
    segments.end_step.push_back(steps);
  }
  if (!finish_witness(model, [&](long k, Eigen::VectorXd& q) { smooth_at(segments, k, q); }, steps, options.dt, space,
                      nullptr, w))
    return std::nullopt;
  return w;
}

bool finish_witness(const Model& model, const SmoothWitness& smooth, long steps, double dt, TaskSpace space,
                    const Eigen::Matrix3d* orientation, GeneratedWitness& w) {
  KinematicsData kin(model);
  // the widest spacing (halving from kMaxSampleSpacing) whose playback stays
  // within the tolerances; one step per sample always does
  long m = std::max(1L, long(std::floor(kMaxSampleSpacing / dt + 1e-9)));
  for (;;) {
    const bool fits = (steps + m - 1) / m + 1 <= ScenarioLimits::max_path_points;
    if (fits) {
      sample(model, smooth, steps, m, orientation, kin, w);
      if (w.interpolation_error <= kInterpolationTolerance && w.orientation_error <= kOrientationTolerance) break;
    }
    if (m == 1) {
      if (!fits) return false;
      break;
    }
    m = std::max(1L, m / 2);
  }
  w.dt = rounded(double(m) * dt, 1e-9);
  // the run lasts a whole number of sample intervals (the witness holds its
  // last configuration for the remainder)
  w.duration = rounded(double(w.steps.size() - 1) * dt, 1e-9);
  for (size_t j = 1; j < w.hand.size(); ++j) w.length += (w.hand[j] - w.hand[j - 1]).norm();
  // what a run of it meets: the limits' margin and the joint rates at the steps
  for (size_t k = 0; k < w.steps.size(); ++k) {
    const Eigen::VectorXd& q = w.steps[k];
    if (model.limits.has_position())
      w.limit_margin = std::min({w.limit_margin, (q - model.limits.lower).minCoeff(),
                                 (model.limits.upper - q).minCoeff()});
    if (k > 0) w.peak_joint_speed = std::max(w.peak_joint_speed, (q - w.steps[k - 1]).cwiseAbs().maxCoeff() / dt);
  }
  Eigen::MatrixXd jac(task_rows(space), model.dof());
  w.min_manipulability = std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& q : w.samples) {
    forward_kinematics(model, q, kin);
    task_jacobian(model, kin, space, jac);
    w.min_manipulability = std::min(w.min_manipulability, std::sqrt(std::max(0.0, (jac * jac.transpose()).determinant())));
  }
  return true;
}

double witness_self_clearance(const Model& model, const std::vector<Eigen::VectorXd>& steps) {
  Model checked = model;
  assign_self_pairs(checked);
  if (checked.self_pairs.empty()) return std::numeric_limits<double>::infinity();
  const SelfCollisionWorld world(checked);
  KinematicsData kin(checked);
  SelfDistanceTable table;
  double least = std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& q : steps) {
    forward_kinematics(checked, q, kin);
    world.compute(kin, table);
    least = std::min(least, table.min_distance);
  }
  return least;
}

double self_margin(const Model& model) {
  double thinnest = std::numeric_limits<double>::infinity();
  for (const Link& link : model.links) thinnest = std::min(thinnest, link.radius);
  return std::min(kSelfClearance, 0.5 * thinnest);
}

bool keeps_self_clearance(const Model& model, GeneratedWitness& w) {
  w.self_clearance = witness_self_clearance(model, w.steps);
  return w.self_clearance > self_margin(model);
}

nlohmann::json witness_task(const GeneratedWitness& w, TaskSpace space) {
  nlohmann::json points = nlohmann::json::array(), durations = nlohmann::json::array();
  for (const Eigen::Vector3d& p : w.hand) {
    if (space == TaskSpace::xy)
      points.push_back({p.x(), p.y()});
    else
      points.push_back({p.x(), p.y(), p.z()});
  }
  for (size_t j = 1; j < w.hand.size(); ++j)
    durations.push_back(w.dt);
  nlohmann::json task = {
      {"space", to_string(space)},
      {"trajectory", {{"type", "polyline"}, {"points", points}, {"durations", durations}, {"time_law", "linear"}}}};
  if (space == TaskSpace::pose && w.orientation_rpy)
    task["orientation"] = {w.orientation_rpy->x(), w.orientation_rpy->y(), w.orientation_rpy->z()};
  return task;
}

nlohmann::json witness_json(const GeneratedWitness& w, const std::optional<ObstacleDifficulty>& obstacles) {
  nlohmann::json q = nlohmann::json::array();
  for (const Eigen::VectorXd& sample : w.samples) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index i = 0; i < sample.size(); ++i) row.push_back(sample[i]);
    q.push_back(std::move(row));
  }
  nlohmann::json difficulty = {{"path_length", rounded(w.length, 1e-6)},
                               {"duration", w.duration},
                               {"min_manipulability", rounded(w.min_manipulability, 1e-9)},
                               {"interpolation_error", rounded(w.interpolation_error, 1e-9)},
                               {"peak_joint_speed", rounded(w.peak_joint_speed, 1e-6)}};
  if (obstacles) {
    difficulty["clearance"] = rounded(obstacles->clearance, 1e-6);
    difficulty["tight_obstacles"] = obstacles->tight;
    difficulty["blocking_obstacles"] = obstacles->blocking;
  }
  if (std::isfinite(w.limit_margin)) difficulty["limit_margin"] = rounded(w.limit_margin, 1e-6);
  if (w.orientation_rpy) difficulty["orientation_error"] = rounded(w.orientation_error, 1e-9);
  if (std::isfinite(w.self_clearance)) difficulty["self_clearance"] = rounded(w.self_clearance, 1e-6);
  return {{"dt", w.dt}, {"q", q}, {"difficulty", difficulty}};
}

double witness_clearance(const ArmSweep& sweep, const nlohmann::json& obstacles) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const nlohmann::json& o : obstacles)
    clearance = std::min(clearance, sweep_clearance(sweep, parse_obstacle_json(o, "obstacle")));
  return clearance;
}

int obstacles_within(const ArmSweep& sweep, const nlohmann::json& obstacles, double distance) {
  int within = 0;
  for (const nlohmann::json& o : obstacles)
    if (sweep_clearance(sweep, parse_obstacle_json(o, "obstacle"), distance) <= distance) ++within;
  return within;
}

nlohmann::json witnessed_document(const GeneratorCase& c, const std::string& description, const WitnessedArm& drawn,
                                  const nlohmann::json& obstacles, TaskSpace space, double clearance) {
  nlohmann::json doc = case_document(c, description, drawn.witness.step_dt, drawn.witness.duration,
                                     robot_with_q0(drawn.arm, drawn.witness.samples[0]), obstacles,
                                     witness_task(drawn.witness, space));
  std::optional<ObstacleDifficulty> measured;
  if (!obstacles.empty())
    measured = ObstacleDifficulty{witness_clearance(drawn.sweep, obstacles),
                                  obstacles_within(drawn.sweep, obstacles, 2 * clearance),
                                  pinv_blocking_obstacles(doc)};
  doc["witness"] = witness_json(drawn.witness, measured);
  return doc;
}

std::string witness_summary(const GeneratedWitness& w, int waypoints) {
  return "the hand follows the trace of a witness (a joint trajectory through " + std::to_string(waypoints) +
         (waypoints == 1 ? " drawn configuration" : " drawn configurations") + ", " + w.time_law +
         " time law per segment), " + fixed_digits(w.length, 3) + " m timed for " + fixed_digits(w.speed, 3) +
         " m/s (" + fixed_digits(w.duration, 2) + " s)";
}

}  // namespace rrlab
