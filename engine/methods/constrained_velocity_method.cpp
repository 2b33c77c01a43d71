#include <rrlab/methods/constrained_velocity_method.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace rrlab {
namespace {

constexpr double kRelaxedRowMargin = 1e-9;  // the relaxed rows ask this much less than A q̇* reaches

}  // namespace

std::vector<ParamSpec> velocity_constraint_params() {
  return {
      {"position_gain", "Joint-limit gain γ", "",
       "γ of γ(q_min − q)/dt ≤ q̇ ≤ γ(q_max − q)/dt: the share of the room to a limit one step may use", 0.5, 0.01,
       1.0, 0.01, {}},
      {"max_step", "Step cap", "m",
       "no joint alone moves a point of the arm farther than this in one step, |q̇_i| dt R_i ≤ max_step (rrlab's "
       "stand-in for velocity limits a scenario lacks); 0 = off",
       0.02, 0.0, 10.0, 0.005, {}},
      {"detection_distance", "Damper detection distance d_i", "m",
       "pairs nearer than d_i get a velocity damper (Faverjon & Tournassoud); must exceed safety_distance", 0.08, 0.001,
       10.0, 0.01, {}},
      {"safety_distance", "Damper safety distance d_s", "m",
       "the distance the dampers keep: ḋ ≥ −ξ(d − d_s)/(d_i − d_s) reaches 0 at d_s", 0.01, 0.0, 10.0, 0.005, {}},
      {"damper_gain", "Damper gain ξ", "m/s",
       "ξ of ḋ ≥ −ξ(d − d_s)/(d_i − d_s): the fastest approach at d_i (the rate ξ/(d_i − d_s) is capped at 1/dt)",
       1.0, 0.0, 100.0, 0.05, {}},
      {"self_pairs", "Dampers on self pairs", "",
       "also damp the link pairs the robot checks for self-collision (Model::self_pairs)", 1, 0, 1, 1, {"off", "on"}},
      {"posture_weight", "Posture weight", "",
       "weight of the posture task ‖q̇ − k_p(q_rest − q)‖² (a low-priority term)", 1e-3, 0.0, 1e3, 1e-3, {}},
      {"posture_gain", "Posture gain k_p", "1/s", "gain of the posture task's velocity k_p(q_rest − q)", 1.0, 0.0,
       100.0, 0.1, {}},
      {"rest", "Rest configuration", "",
       "q_rest of the posture task: the configuration at the start, or the middle of each joint's range (the start "
       "where a joint has no range)",
       1, 0, 1, 1, {"start", "mid_range"}},
  };
}

std::vector<ParamSpec> with_velocity_constraint_params(std::vector<ParamSpec> own) {
  for (ParamSpec& spec : velocity_constraint_params()) own.push_back(std::move(spec));
  return own;
}

ConstrainedVelocityMethod::ConstrainedVelocityMethod(std::vector<ParamSpec> specs, const MethodContext& ctx)
    : Method(std::move(specs)),
      n_(ctx.model.dof()),
      builder_(ctx.model, ctx.obstacle_count),
      least_violation_(ctx.model.dof(), builder_.capacity()),
      slack_(Eigen::VectorXd::Zero(builder_.capacity())),
      rest_(Eigen::VectorXd::Zero(ctx.model.dof())),
      posture_velocity_(Eigen::VectorXd::Zero(ctx.model.dof())) {
  builder_.size(constraints_);
  valid_detection_ = p(kDetection);
  valid_safety_ = p(kSafety);
  status_ = declare_diagnostic("qp_status");
  iterations_ = declare_diagnostic("qp_iterations");
  damper_rows_ = declare_diagnostic("damper_rows");
  active_dampers_ = declare_diagnostic("active_dampers");
  active_bounds_ = declare_diagnostic("active_bounds");
  damper_slack_ = declare_diagnostic("damper_slack");
  relaxed_steps_ = declare_diagnostic("relaxed_steps");
  min_pair_distance_ = declare_diagnostic("min_damped_distance");
}

// d_i ≤ d_s leaves the damper without a band: refused, the previous value kept.
void ConstrainedVelocityMethod::on_param_changed(ParamSlot changed) {
  if (!(changed == kDetection || changed == kSafety)) return;
  const double detection = p(kDetection), safety = p(kSafety);
  if (detection > safety) {
    valid_detection_ = detection;
    valid_safety_ = safety;
    return;
  }
  const std::string name = specs()[size_t(changed.index)].name;
  set_param(name, changed == kDetection ? valid_detection_ : valid_safety_);
  throw ParamError(name, name + ": detection_distance (" + std::to_string(detection) +
                             " m) must exceed safety_distance (" + std::to_string(safety) + " m)");
}

void ConstrainedVelocityMethod::start_run(const StepInput& in) {
  relaxed_count_ = 0;
  const JointLimits& lim = in.model.limits;
  for (int i = 0; i < n_; ++i) {
    const bool ranged = std::isfinite(lim.lower[i]) && std::isfinite(lim.upper[i]);
    rest_[i] = choice(kRest) == 1 && ranged ? 0.5 * (lim.lower[i] + lim.upper[i]) : in.state.q[i];
  }
}

void ConstrainedVelocityMethod::prepare(const StepInput& in) {
  if (in.state.step == 0) start_run(in);
  if (builder_.needs_resize(in)) {
    builder_.resize(in.model, in.distances.obstacles);
    builder_.size(constraints_);
    least_violation_ = LeastViolation(n_, builder_.capacity());
    slack_.setZero(builder_.capacity());
    resize_problems();
  }
  const LimitSettings limits{p(kPositionGain), p(kMaxStep)};
  const DamperSettings dampers{p(kDetection), p(kSafety), p(kDamperGain), choice(kSelfPairs) == 1};
  builder_.build(in, limits, dampers, constraints_);
  posture_velocity_ = p(kPostureGain) * (rest_ - in.state.q);
  relaxed_ = false;
  step_slack_ = 0;
}

double ConstrainedVelocityMethod::relax_dampers() {
  const int rows = constraints_.rows;
  least_violation_.solve(constraints_, slack_);
  constraints_.b.head(rows) -= slack_.head(rows);
  constraints_.b.head(rows).array() -= kRelaxedRowMargin;
  relaxed_ = true;
  step_slack_ = rows > 0 ? slack_.head(rows).maxCoeff() : 0.0;
  return step_slack_;
}

void ConstrainedVelocityMethod::report(const QpSolver& solver, QpStatus status, int first_row,
                                       const Eigen::VectorXd& qdot, StepOutput& out) {
  if (out.overlays.segments.capacity() < size_t(row_capacity())) out.overlays.segments.reserve(size_t(row_capacity()));
  const int active = draw_active_dampers(solver, first_row, constraints_, out.overlays.segments);
  int bounds = 0;
  for (int i = 0; i < n_; ++i)  // bounds the solution sits on (whichever QP produced it)
    bounds += qdot[i] <= constraints_.lower[i] + 1e-12 || qdot[i] >= constraints_.upper[i] - 1e-12;
  double nearest = -1;
  for (int k = 0; k < constraints_.rows; ++k)
    nearest = nearest < 0 ? constraints_.pairs[size_t(k)].distance
                          : std::min(nearest, constraints_.pairs[size_t(k)].distance);
  relaxed_count_ += relaxed_;
  out.diag.values[status_] = double(static_cast<int>(status));
  out.diag.values[iterations_] = solver.iterations();
  out.diag.values[damper_rows_] = constraints_.rows;
  out.diag.values[active_dampers_] = active;
  out.diag.values[active_bounds_] = bounds;
  out.diag.values[damper_slack_] = step_slack_;
  out.diag.values[relaxed_steps_] = double(relaxed_count_);
  out.diag.values[min_pair_distance_] = nearest;
}

}  // namespace rrlab
