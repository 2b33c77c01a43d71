// The witness of a generated case: a smooth joint trajectory through drawn
// configurations that is known to solve the case. The task path is its
// end-effector trace, sampled and written as the task's polyline, so that
// playing the samples back tracks the path to within kInterpolationTolerance;
// obstacles are then placed clear of the arm at every step of it.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clearance.hpp>
#include <rrlab/generators/generator_path.hpp>
#include <rrlab/model/model.hpp>
#include <rrlab/task/task.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

// Samples are spaced as widely as this allows (a whole number of steps, at
// most kMaxSampleSpacing): the played-back hand stays this close to the
// task's polyline at every step (m).
constexpr double kInterpolationTolerance = 5e-4;
constexpr double kMaxSampleSpacing = 0.1;  // s
// Pose tasks: the played-back hand's orientation stays this close to the
// task's (rad).
constexpr double kOrientationTolerance = 1e-3;
// Sample joint values are written to this step (rad, or m for prismatic joints).
constexpr double kSampleStep = 1e-6;
// Where joint velocity limits exist, the witness peaks at this share of them.
constexpr double kVelocityLimitShare = 0.9;
// The witness arm's checked link pairs (the allowed-collision matrix a case's
// robot gets, collision/allowed_collisions.hpp) keep more than this distance
// at every step (m), or half the thinnest link's radius when that is less
// (self_margin); a witness that comes closer is redrawn.
constexpr double kSelfClearance = 0.005;

struct GeneratedWitness {
  double dt = 0;                           // sample spacing, a whole number of steps
  std::vector<Eigen::VectorXd> samples;    // from t = 0 to the end (held there)
  std::vector<Eigen::Vector3d> hand;       // end-effector positions at the samples
  std::vector<Eigen::VectorXd> steps;      // played back: the configuration at every step, 0..N
  double step_dt = 0, duration = 0;        // s (the duration is a whole number of steps)
  double speed = 0;                        // the hand speed it was timed by (m/s)
  double length = 0;                       // of the hand's polyline (m)
  double interpolation_error = 0;          // largest |hand at a step − task reference| (m)
  double orientation_error = 0;            // pose tasks: largest hand orientation error at a step (rad)
  std::optional<Eigen::Vector3d> orientation_rpy;  // pose tasks: the task's fixed orientation (rad)
  double limit_margin = std::numeric_limits<double>::infinity();  // least distance to a limit (rad)
  double min_manipulability = 0;           // least sqrt(det(J Jᵀ)) of the task rows, over the samples
  double peak_joint_speed = 0;             // largest |q̇| of any joint over the steps (rad/s)
  double self_clearance = std::numeric_limits<double>::infinity();  // least self distance over the steps (m)
  std::string time_law;
};

// The witness through `configurations` (q0 first): per segment a straight
// line in joint space, timed by the time law ("quintic": rest to rest, smooth;
// "linear": constant joint rate), each segment long enough for the hand's
// speed (drawn from the options, or the default for `reach`) and for the
// joint velocity limits. Nullopt when it needs more samples than a task
// polyline may hold or steps than a scenario may run.
std::optional<GeneratedWitness> build_witness(const Model& model, const std::vector<Eigen::VectorXd>& configurations,
                                              const PathOptions& options, double reach, TaskSpace space, Rng& rng);

// The hand speed a witness is timed by: drawn from the options' `speed`, or
// kDefaultSpeedPerReach × reach; rounded to 1 mm/s, at least that.
double witness_speed(const PathOptions& options, double reach, Rng& rng);

// The witness's configuration at a step of its smooth trajectory (before sampling).
using SmoothWitness = std::function<void(long step, Eigen::VectorXd& q)>;

// The rest of a witness whose smooth trajectory has `steps` steps of `dt`:
// samples at the widest spacing that keeps the playback within the
// tolerances (position, and the orientation when given), the played-back
// steps, duration, length and difficulty measures. `w` has its speed and time
// law set. False when the samples do not fit a task polyline.
bool finish_witness(const Model& model, const SmoothWitness& smooth, long steps, double dt, TaskSpace space,
                    const Eigen::Matrix3d* orientation, GeneratedWitness& w);

// What a case's obstacles make of it (recorded when it has any): the
// witness arm's least `clearance` from them (m), how many come within twice
// the family's clearance of it at some step (`tight`), and how many the
// minimum-norm solution's arm meets in a pinv run (`blocking`).
struct ObstacleDifficulty {
  double clearance = 0;
  int tight = 0, blocking = 0;
};

// The document's "task" (a polyline through the witness's hand samples, one
// sample interval per segment, linear time law) and "witness" (samples and
// the case's difficulty: `clearance` (m), `tight_obstacles` and
// `blocking_obstacles` (when the case has obstacles), `limit_margin` (rad,
// when the arm has limits), `path_length` (m), `duration` (s),
// `min_manipulability`, `interpolation_error` (m)).
nlohmann::json witness_task(const GeneratedWitness& witness, TaskSpace space);
nlohmann::json witness_json(const GeneratedWitness& witness, const std::optional<ObstacleDifficulty>& obstacles);

// The least distance between the checked link pairs of `model` (its own
// allowed-collision matrix, as a case's robot gets it) over the steps, by
// the engine's self-collision code; +inf when no pair is checked.
double witness_self_clearance(const Model& model, const std::vector<Eigen::VectorXd>& steps);

// min(kSelfClearance, half the thinnest link's radius): tiny arms (links of
// a centimetre) fold closer than a fixed margin allows.
double self_margin(const Model& model);

// Sets w.self_clearance; false when it is not above self_margin (the witness
// self-collides or nearly: redraw).
bool keeps_self_clearance(const Model& model, GeneratedWitness& w);

// Draws an arm, waypoint configurations (draw_path) and the witness through
// them; `path` then holds the configurations and, as its points and length,
// the witness's hand trace (where obstacles are aimed). Nullopt when no path
// or witness was found for that arm.
struct WitnessedArm {
  GeneratedArm arm;
  GeneratedPath path;
  GeneratedWitness witness;
  ArmSweep sweep;
};
template <typename DrawArm>
std::optional<WitnessedArm> draw_witnessed_arm(DrawArm&& draw_arm, const PathOptions& options, TaskSpace space,
                                               Rng& rng) {
  GeneratedArm arm = draw_arm(rng);
  std::optional<GeneratedPath> path = draw_path(arm, options.waypoints.draw(rng), rng);
  if (!path) return std::nullopt;
  std::optional<GeneratedWitness> witness = build_witness(arm.model, path->configurations, options, arm.reach, space, rng);
  if (!witness || !keeps_self_clearance(arm.model, *witness)) return std::nullopt;
  path->points = witness->hand;
  path->length = witness->length;
  path->duration = witness->duration;
  path->speed = witness->speed;
  path->time_law = witness->time_law;
  ArmSweep sweep = arm_sweep(arm.model, witness->steps, options.dt);
  return WitnessedArm{std::move(arm), std::move(*path), std::move(*witness), std::move(sweep)};
}

// The least clearance of the witness arm from `obstacles` (scenario syntax)
// over its steps; infinity without obstacles.
double witness_clearance(const ArmSweep& sweep, const nlohmann::json& obstacles);

// The number of `obstacles` that come within `distance` of the witness arm at some step.
int obstacles_within(const ArmSweep& sweep, const nlohmann::json& obstacles, double distance);

// The document of a witnessed case: case_document() with the witness's task
// and its "witness", its difficulty measured against `obstacles` with the
// family's `clearance` (ObstacleDifficulty: this runs pinv on the case).
nlohmann::json witnessed_document(const GeneratorCase& c, const std::string& description, const WitnessedArm& drawn,
                                  const nlohmann::json& obstacles, TaskSpace space, double clearance);

// For descriptions: "the hand follows the witness's trace through 3 waypoint configurations, 4.12 m at 0.54 m/s (7.63 s, quintic time law)".
std::string witness_summary(const GeneratedWitness& witness, int waypoints);

}  // namespace rrlab
