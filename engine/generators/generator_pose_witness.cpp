#include <rrlab/generators/generator_pose_witness.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include <rrlab/generators/generator_case.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/task/task.hpp>
#include <rrlab/task/trajectory.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {

namespace {

constexpr int kPoseNewtonIterations = 20;
constexpr double kPoseTolerance = 1e-10;  // m, rad
constexpr double kPoseDamping = 1e-6;
constexpr double kPosturePull = 1.0;      // 1/s: null-space rate toward the drawn posture
constexpr int kPoseSlowdowns = 2;             // halvings of the speed when a joint is too fast
constexpr long kMaxPoseWitnessSteps = 100'000;

// [r, p, y] (rad) of R = Rz(y) Ry(p) Rx(r), the scenario's convention.
Eigen::Vector3d pose_rpy_of(const Eigen::Matrix3d& r) {
  const Eigen::Vector3d ypr = r.eulerAngles(2, 1, 0);
  return {ypr[2], ypr[1], ypr[0]};
}

// Every step's configuration along the hand's lines at `speed`; empty when
// the pose was lost, a joint left the box or moved faster than allowed.
std::vector<Eigen::VectorXd> follow_pose(const GeneratedArm& arm, const Eigen::VectorXd& q0, const Eigen::VectorXd& posture,
                                    const Eigen::Matrix3d& orientation,
                                    const std::vector<Eigen::Vector3d>& hand, double speed, const PathOptions& options,
                                    bool& too_fast) {
  const Model& model = arm.model;
  const int n = model.dof();
  KinematicsData kin(model);
  Eigen::MatrixXd jac(6, n);
  RightInverse inverse(6, n);
  Eigen::VectorXd error(6), dq(n), pull(n), q = q0;
  const TimeLaw law = options.time_law == "linear" ? TimeLaw::linear : TimeLaw::quintic;
  std::vector<Eigen::VectorXd> steps{q0};
  too_fast = false;
  if (!q0.allFinite() || !std::isfinite(speed) || !(speed > 0)) return {};
  for (size_t i = 1; i < hand.size(); ++i) {
    if (!hand[i].allFinite() || !hand[i - 1].allFinite()) return {};
    const long count = std::max(1L, long(std::ceil((hand[i] - hand[i - 1]).norm() / speed / options.dt - 1e-9)));
    if (long(steps.size()) + count > kMaxPoseWitnessSteps) return {};
    for (long k = 1; k <= count; ++k) {
      const Eigen::Vector3d target = hand[i - 1] + time_law_progress(law, double(k) / double(count)) * (hand[i] - hand[i - 1]);
      const Eigen::VectorXd previous = q;
      bool held = false;
      for (int it = 0; it < kPoseNewtonIterations; ++it) {
        forward_kinematics(model, q, kin);
        error.head<3>() = target - kin.end_effector().translation();
        error.tail<3>() = orientation_error(orientation, kin.end_effector().linear());
        if (error.norm() < kPoseTolerance) {
          held = true;
          break;
        }
        task_jacobian(model, kin, TaskSpace::pose, jac);
        inverse.factor_dls(jac, kPoseDamping);
        inverse.apply(error, dq);
        if (it == 0) {  // the redundancy drifts toward the posture, invisibly at the hand
          inverse.null_project(kPosturePull * options.dt * (posture - q), pull);
          dq += pull;
        }
        q += dq;
      }
      if (!held) return {};
      for (int j = 0; j < n; ++j) {
        if (q[j] < arm.draw_lower[j] || q[j] > arm.draw_upper[j]) return {};
        const double limit = model.limits.velocity.size() ? model.limits.velocity[j] : INFINITY;
        if (std::isfinite(limit) && std::abs(q[j] - previous[j]) > kVelocityLimitShare * limit * options.dt) {
          too_fast = true;
          return {};
        }
      }
      steps.push_back(q);
    }
  }
  return steps;
}

}  // namespace

std::optional<GeneratedWitness> build_pose_witness(const GeneratedArm& arm, const Eigen::VectorXd& q0,
                                                   const std::vector<Eigen::Vector3d>& points,
                                                   const PathOptions& options, Rng& rng) {
  const Model& model = arm.model;
  KinematicsData kin(model);
  forward_kinematics(model, q0, kin);
  GeneratedWitness w;
  w.step_dt = options.dt;
  w.time_law = options.time_law;
  Eigen::Vector3d rpy = pose_rpy_of(kin.end_effector().linear());
  for (int k = 0; k < 3; ++k) rpy[k] = rounded(rpy[k], kSampleStep);
  w.orientation_rpy = rpy;
  const Eigen::Matrix3d orientation = rpy_matrix({rpy.x(), rpy.y(), rpy.z()});  // as the task's parser reads it
  std::vector<Eigen::Vector3d> hand{kin.end_effector().translation()};
  hand.insert(hand.end(), points.begin(), points.end());
  double speed = witness_speed(options, arm.reach, rng);
  // a self-motion of its own: the witness is not the minimum-norm motion
  const Eigen::VectorXd posture = draw_configuration(arm, rng);
  std::vector<Eigen::VectorXd> steps;
  for (int attempt = 0; attempt <= kPoseSlowdowns; ++attempt, speed = rounded(speed / 2, 1e-3)) {
    bool too_fast = false;
    steps = follow_pose(arm, q0, posture, orientation, hand, speed, options, too_fast);
    if (!steps.empty() || !too_fast) break;
  }
  if (steps.empty()) return std::nullopt;
  w.speed = speed;
  if (!finish_witness(model, [&](long k, Eigen::VectorXd& q) { q = steps[size_t(std::min<long>(k, long(steps.size()) - 1))]; },
                      long(steps.size()) - 1, options.dt, TaskSpace::pose, &orientation, w))
    return std::nullopt;
  if (w.interpolation_error > kInterpolationTolerance || w.orientation_error > kOrientationTolerance) return std::nullopt;
  return w;
}

std::optional<WitnessedArm> pose_witnessed_arm(GeneratedArm arm, const Eigen::VectorXd& q0,
                                               const std::vector<Eigen::Vector3d>& points, const PathOptions& options,
                                               Rng& rng) {
  std::optional<GeneratedWitness> witness = build_pose_witness(arm, q0, points, options, rng);
  if (!witness || !keeps_self_clearance(arm.model, *witness)) return std::nullopt;
  GeneratedPath path;
  path.configurations = {q0};
  path.points = witness->hand;
  path.length = witness->length;
  path.duration = witness->duration;
  path.speed = witness->speed;
  path.time_law = witness->time_law;
  ArmSweep sweep = arm_sweep(arm.model, witness->steps, options.dt);
  return WitnessedArm{std::move(arm), std::move(path), std::move(*witness), std::move(sweep)};
}

}  // namespace rrlab
