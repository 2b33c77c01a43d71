// What qp_ik, hqp and diffik share around their own QPs: the parameters of
// the limits, dampers and posture task, the constraint set of each step
// (velocity_constraints.hpp), the least-violation fallback when the damper
// rows cannot all hold, and the common diagnostics and overlays.
#pragma once

#include <Eigen/Core>
#include <vector>

#include <rrlab/methods/method.hpp>
#include <rrlab/methods/velocity_constraints.hpp>
#include <rrlab/util/qp_solver.hpp>

namespace rrlab {

// The shared parameters (limits, dampers, posture), and a method's own
// parameters followed by them (what its registry row lists).
std::vector<ParamSpec> velocity_constraint_params();
std::vector<ParamSpec> with_velocity_constraint_params(std::vector<ParamSpec> own);

class ConstrainedVelocityMethod : public Method {
 protected:
  // specs: with_velocity_constraint_params(the method's own)
  ConstrainedVelocityMethod(std::vector<ParamSpec> specs, const MethodContext& ctx);

  // Builds this step's constraints; calls resize_problems() first when the
  // scene outgrew the row capacity (obstacles added: allocates once).
  void prepare(const StepInput& in);
  virtual void resize_problems() = 0;
  int row_capacity() const { return builder_.capacity(); }

  // Level 1: the least violation w* of the damper rows within the box;
  // afterwards the rows ask A q̇ ≥ b − w* (always feasible). Returns max w*.
  double relax_dampers();
  // The least-violation q̇ of the last relax_dampers() (a last resort).
  const Eigen::VectorXd& least_violation_qdot() const { return least_violation_.qdot(); }

  // q̇ of the posture task: k_p (q_rest − q).
  const Eigen::VectorXd& posture_velocity() const { return posture_velocity_; }
  double posture_weight() const { return p(kPostureWeight); }

  // Counts, overlays and the shared diagnostics of the step just solved by
  // `solver`, whose inequality rows first_row.. are the damper rows.
  void report(const QpSolver& solver, QpStatus status, int first_row, const Eigen::VectorXd& qdot,
              StepOutput& out);

  VelocityConstraints constraints_;

 private:
  void start_run(const StepInput& in);
  const ParamSlot kPositionGain = slot("position_gain"), kMaxStep = slot("max_step"),
                  kDetection = slot("detection_distance"), kSafety = slot("safety_distance"),
                  kDamperGain = slot("damper_gain"), kSelfPairs = slot("self_pairs"),
                  kPostureWeight = slot("posture_weight"), kPostureGain = slot("posture_gain"),
                  kRest = slot("rest");
  void on_param_changed(ParamSlot changed) override;

  int n_;
  VelocityConstraintBuilder builder_;
  LeastViolation least_violation_;
  Eigen::VectorXd slack_, rest_, posture_velocity_;
  double step_slack_ = 0, valid_detection_ = 0, valid_safety_ = 0;
  bool relaxed_ = false;
  long relaxed_count_ = 0;
  int status_, iterations_, damper_rows_, active_dampers_, active_bounds_, damper_slack_, relaxed_steps_,
      min_pair_distance_;
};

}  // namespace rrlab
