// What the simulator records for every step, and the run summary.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/methods/method.hpp>

namespace rrlab {

struct Frame {
  long step = 0;
  double t = 0;
  Eigen::VectorXd q, qdot;  // state at t, and the velocity applied over [t, t + dt]
  Eigen::Vector3d ee_position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond ee_orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  // pose tasks: the desired orientation at t (for drawing; not stored with frames)
  std::optional<Eigen::Quaterniond> target_orientation;
  double task_error = 0;         // position error norm, m
  double orientation_error = 0;  // rad (pose tasks)
  double min_distance = 0;       // +inf without obstacles
  int min_distance_link = -1;
  bool collided = false;          // an obstacle contact
  double min_self_distance = 0;   // +inf without self pairs
  int self_link_a = -1, self_link_b = -1;  // the nearest self pair
  bool self_collided = false;
  double joint_limit_margin = 0;  // min over bounded joints of the distance to a limit; +inf if none
  double manipulability = 0, condition_number = 0;
  Eigen::VectorXd diagnostics;    // the method's named scalars
  Overlays overlays;              // what the method wants drawn
  double step_us = 0;             // compute time: not deterministic, kept apart
};

struct StepTimeStats {
  double mean = 0, p50 = 0, p99 = 0;
};

// Joint acceleration (rad/s², m/s² for prismatic joints) and jerk (/s³) of
// the motion a run made: RMS and largest over its steps of the Euclidean norm
// over joints (joint_smoothness.hpp). Empty when the run is too short: the
// acceleration needs 2 steps, the jerk 3.
struct JointSmoothness {
  std::optional<double> rms_qddot, max_qddot;
  std::optional<double> rms_jerk, max_jerk;
};

struct Summary {
  std::string scenario, method;
  long steps = 0;
  bool collided = false;           // any collision: with an obstacle or of the arm with itself
  bool obstacle_collided = false, self_collided = false;
  double min_distance = 0;
  std::optional<double> min_self_distance;  // absent when no link pair is checked
  double max_tracking_error = 0, final_tracking_error = 0;
  bool joint_limit_violated = false;
  double min_joint_limit_margin = 0;
  std::optional<double> max_qdot_ratio, max_qddot_ratio;  // absent without such limits
  // Steps that ended past a joint position limit (the integrated q), and
  // steps whose applied velocity exceeded a velocity limit (absent without
  // velocity limits): what the arm did, not what the method commanded.
  long position_limit_steps = 0;
  std::optional<long> velocity_limit_steps;
  double max_condition_number = 0;
  long nonfinite_steps = 0;  // steps whose method output was not finite (zeroed)
  JointSmoothness smoothness;
  Eigen::VectorXd final_q;
  StepTimeStats step_us;
};

// The summary's format: absent (1) before self-collision, when `collided`
// meant an obstacle contact only; 2 adds obstacle_collided, self_collided,
// min_self_distance and the smoothness fields (rms_qddot, max_qddot,
// rms_jerk, max_jerk), and `collided` is any collision; 3 adds
// position_limit_steps and velocity_limit_steps. A stored summary is
// re-simulated and compared under the rules of its format.
inline constexpr int kSummaryFormat = 3;

// The run summary JSON of `rrlab run` (docs/cli.md, run); non-finite numbers are written as null.
nlohmann::json summary_to_json(const Summary& summary);
nlohmann::json finite_or_null(double value);
nlohmann::json finite_or_null(const std::optional<double>& value);  // empty: null
nlohmann::json finite_or_null(const Eigen::VectorXd& values);  // an array

}  // namespace rrlab
