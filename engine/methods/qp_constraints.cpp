// Qiu, Cao & Sun: redundancy resolution as a QP with the physical limits and
// obstacle avoidance as inequalities and singularity avoidance as a revision
// of the task equality (Qiu, Cao, Sun, "Redundant manipulator control with constraints for subgoals").
//
//   minimise ½ q̇ᵀq̇                      (eq 8: H = I, φ = 0, minimum norm; the basis
//                                         p_i of eq 7 is the natural one, so λ = q̇)
//   s.t.     J q̇ = ẋ_R                   (eq 9, revised by eq 23)
//            lower ≤ q̇ ≤ upper           (eq 11–15: joint range, velocity, acceleration)
//            r_ocᵀ J_o q̇ ≥ t             (eq 19–20, one row per link within d_s + σ of an obstacle)
//
// Choices where the paper is silent (documented in README and the scenarios):
//  - critical point (eq 16–17, Fig 1): the point of the link nearest to the
//    obstacle, from the engine's distance table; for a point obstacle and a
//    segment link this is exactly Fig 1's three cases (foot of the
//    perpendicular, or the nearer joint), and it generalises to any shape;
//    r_oc (eq 18) is the table's unit normal obstacle → link.
//  - ρ(d) (eq 20) is the half-cosine bell ½(1 − cos(π (d − d_s)/σ)): 1 at the
//    outer edge of the buffer, 0 at d_s; P_c is the approach rate when the
//    pair entered the buffer, or −approach_rate if that is slower (a pair that
//    entered tangentially would otherwise be frozen at d_s + σ); either way
//    the constraint is not yet active at entry, so q̇ stays continuous.
//  - moving obstacles: the rate is taken relative, r_ocᵀ(J_o q̇ − v_o) ≥ t.
//  - a pair whose distance no joint can change (r_ocᵀJ_o = 0, e.g. a base
//    link turning about its own axis) gets no row: it could only make the QP
//    infeasible.
//  - empty bounds (eq 15 can give lower > upper): acceleration wins over
//    velocity, velocity over the joint-range step; bounds are shrunk by a
//    relative 1e-9 so rounding never reports a ratio above 1.
//  - u_s (eq 23) is oriented so that moving the end-effector along +u_s
//    increases σ_min (finite difference), so eq 23 removes only the motion
//    towards the singularity.
//  - φ (eq 8) is 0 unless `clearance_gain` k > 0: then φ = −k(1 − ρ(d))J_oᵀr_oc
//    summed over the obstacle rows, a separating push that grows through the
//    buffer (an extension; the examples use the minimum-norm objective).
//  - infeasible QP (§III end: "the constraints are over stringent
//    sometimes"): the task is relaxed with a slack s, J q̇ − s = ẋ_R, at
//    cost ½ w|s|² (w = slack_weight); if the bounds and obstacle rows alone
//    conflict (the acceleration bound cannot brake the approach in time), the
//    obstacle rows get one shared slack e ≥ 0 at cost ½·10³w·e² as well.
//    Reported in `relaxation` (0, 1, 2) and `obstacle_slack`.
#include <algorithm>
#include <cmath>

#include "methods/factories.hpp"
#include "util/qp_solver.hpp"

namespace rrlab {
namespace {

enum { kSafety, kBuffer, kEta, kSigmaS, kSlackWeight, kApproach, kClearanceGain };

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kShrink = 1.0 - 1e-9;

class QpConstraints final : public Method {
 public:
  explicit QpConstraints(const MethodContext& ctx)
      : Method(qp_constraints_params()),
        n_(ctx.model.dof()),
        m_(task_rows(ctx.space)),
        space_(ctx.space),
        jacobian_probe_(m_, n_),
        probe_(ctx.model),
        conditioning_(m_, n_),
        jjt_(m_, m_),
        eig_(m_),
        point_jacobian_(3, n_),
        xdot_(m_),
        residual_(m_),
        us_(m_),
        q_probe_(n_),
        lower_(n_),
        upper_(n_) {
    size_pairs(ctx.model.link_count(), ctx.obstacle_count);
    status_ = declare_diagnostic("qp_status");
    relaxation_ = declare_diagnostic("relaxation");
    task_slack_ = declare_diagnostic("task_slack");
    iterations_ = declare_diagnostic("qp_iterations");
    active_bounds_ = declare_diagnostic("active_bounds");
    obstacle_rows_ = declare_diagnostic("obstacle_rows");
    active_obstacle_rows_ = declare_diagnostic("active_obstacle_rows");
    obstacle_slack_ = declare_diagnostic("obstacle_slack");
    sigma_min_ = declare_diagnostic("sigma_min");
    revised_ = declare_diagnostic("singularity_revision");
    min_critical_ = declare_diagnostic("min_critical_distance");
    for (int l = 0; l < ctx.model.link_count(); ++l)
      link_distance_.push_back(declare_diagnostic("critical_distance_" + std::to_string(l + 1)));
  }

  void step(const StepInput& in, StepOutput& out) override {
    if (in.state.step == 0) start_run();  // a (re)started run replays bit for bit
    if (in.distances.links * in.distances.obstacles > pair_capacity_)
      size_pairs(in.distances.links, in.distances.obstacles);  // obstacles added (allocates once)
    revise_task_velocity(in, out);
    joint_bounds(in);
    const int rows = obstacle_rows(in, out);

    // stage 0: the paper's QP; 1: task slack; 2: task and obstacle slack
    QpStatus status = solve_strict(in, rows);
    int relaxation = 0;
    if (status == QpStatus::optimal) {
      out.qdot = strict_solver_.x();
    } else {
      relaxation = 1;
      status = solve_relaxed(in, rows, false);
      if (status != QpStatus::optimal) {
        relaxation = 2;
        status = solve_relaxed(in, rows, true);
      }
      if (status == QpStatus::optimal)
        out.qdot = relaxed_solver_.x().head(n_);
      else  // not expected (stage 2 is always feasible): stop as fast as allowed
        out.qdot = lower_.cwiseMax(upper_.cwiseMin(Eigen::VectorXd::Zero(n_)));
    }
    const QpSolver& used = relaxation == 0 ? strict_solver_ : relaxed_solver_;
    int active_bounds = 0, active_rows = 0;
    for (int i = 0; i < n_; ++i) active_bounds += used.lower_active(i) + used.upper_active(i);
    for (int k = 0; k < rows; ++k) active_rows += used.inequality_active(k);
    out.diag.values[obstacle_slack_] = relaxation == 2 ? relaxed_solver_.x()[n_ + m_] : 0.0;
    out.diag.values[status_] = static_cast<double>(status);
    out.diag.values[relaxation_] = relaxation;
    residual_.noalias() = in.task_jacobian * out.qdot;
    residual_ -= xdot_;
    out.diag.values[task_slack_] = residual_.norm();
    out.diag.values[iterations_] = used.iterations();
    out.diag.values[active_bounds_] = active_bounds;
    out.diag.values[obstacle_rows_] = rows;
    out.diag.values[active_obstacle_rows_] = active_rows;
  }

 private:
  void size_pairs(int links, int obstacles) {
    pair_capacity_ = std::max(1, links * obstacles);
    entered_.assign(pair_capacity_, false);
    approach_at_entry_.assign(pair_capacity_, 0.0);
    strict_ = std::make_unique<QpProblem>(n_, m_, pair_capacity_);
    relaxed_ = std::make_unique<QpProblem>(n_ + m_ + 1, m_, pair_capacity_);
    strict_solver_ = QpSolver(n_, m_, pair_capacity_);
    relaxed_solver_ = QpSolver(n_ + m_ + 1, m_, pair_capacity_);
    // relaxed problem, x = [q̇; s; e]: H = diag(I, w I, w_o), J q̇ − s = ẋ_R with s
    // free, and every obstacle row r_ocᵀJ_o q̇ + e ≥ t with e ≥ 0 (stage 2 only)
    relaxed_->eq_count = m_;
    relaxed_->A_eq.block(0, n_, m_, m_) = -Eigen::MatrixXd::Identity(m_, m_);
    relaxed_->A_eq.col(n_ + m_).setZero();
    relaxed_->A_in.col(n_ + m_).setOnes();
    set_slack_weight();
  }

  // Forget what the previous run left: buffer entries and warm starts.
  void start_run() {
    std::fill(entered_.begin(), entered_.end(), false);
    std::fill(approach_at_entry_.begin(), approach_at_entry_.end(), 0.0);
    strict_solver_.forget_warm_start();
    relaxed_solver_.forget_warm_start();
  }

  void set_slack_weight() {
    relaxed_->H.setIdentity();
    relaxed_->H.block(n_, n_, m_, m_) *= p(kSlackWeight);
    relaxed_->H(n_ + m_, n_ + m_) = 1e3 * p(kSlackWeight);  // obstacles before the task
  }
  void on_param_changed(int index) override {
    if (index == kSlackWeight && relaxed_) set_slack_weight();
  }

  // Qiu eq 21–24: when σ_min ≤ σ_s, remove the component of ẋ that drives
  // the end-effector towards the singularity along u_s.
  void revise_task_velocity(const StepInput& in, StepOutput& out) {
    xdot_ = in.ref.xdot;
    jjt_.noalias() = in.task_jacobian * in.task_jacobian.transpose();
    eig_.compute(jjt_);  // ascending eigenvalues: σ_i² of eq 21–22
    const double sigma_min = std::sqrt(std::max(0.0, eig_.eigenvalues()[0]));
    out.diag.values[sigma_min_] = sigma_min;
    out.diag.values[revised_] = 0;
    if (!(sigma_min <= p(kSigmaS))) return;  // eq 24: k = 0
    us_ = eig_.eigenvectors().col(0);
    orient_singular_direction(in, sigma_min);
    const double along = us_.dot(xdot_);
    if (along < 0) {  // eq 23 with k = 1: (1 − sign(u_s·ẋ))/2 = 1
      xdot_ -= along * us_;
      out.diag.values[revised_] = 1;
    }
  }

  // Makes +u_s the task direction in which σ_min grows: probe q + h J⁺u_s.
  void orient_singular_direction(const StepInput& in, double sigma_min) {
    const double h = 1e-6;
    // J⁺u_s = Jᵀ(JJᵀ)⁺u_s; (JJᵀ)⁺u_s = u_s/σ² — use Jᵀu_s, same sign of motion along u_s
    q_probe_.noalias() = in.task_jacobian.transpose() * us_;
    const double norm = q_probe_.norm();
    if (norm < 1e-12) return;  // exactly singular: keep the eigenvector's sign
    q_probe_ = in.state.q + (h / norm) * q_probe_;
    forward_kinematics(in.model, q_probe_, probe_);
    task_jacobian(in.model, probe_, space_, jacobian_probe_);
    conditioning_.compute(jacobian_probe_);
    if (conditioning_.sigma_min() < sigma_min) us_ = -us_;
  }

  // Qiu eq 11–15, merged: lower = max(range, velocity, acceleration), upper = min(…).
  void joint_bounds(const StepInput& in) {
    const JointLimits& lim = in.model.limits;
    const double dt = in.dt;
    for (int i = 0; i < n_; ++i) {
      const double qd_prev = in.state.qdot[i];
      double lo = qd_prev - kShrink * dt * lim.acceleration[i];  // eq 13
      double hi = qd_prev + kShrink * dt * lim.acceleration[i];
      intersect(lo, hi, -kShrink * lim.velocity[i], kShrink * lim.velocity[i]);  // eq 12
      const double range_lo = (lim.lower[i] - in.state.q[i]) / dt;  // eq 11
      const double range_hi = (lim.upper[i] - in.state.q[i]) / dt;
      intersect(lo, hi, range_lo, range_hi);
      lower_[i] = lo;
      upper_[i] = hi;
    }
  }

  // [lo, hi] ∩ [a, b]; when empty, the point of [lo, hi] nearest to [a, b].
  static void intersect(double& lo, double& hi, double a, double b) {
    if (hi < a) {
      lo = hi;
    } else if (lo > b) {
      hi = lo;
    } else {
      lo = std::max(lo, a);
      hi = std::min(hi, b);
    }
  }

  // Qiu eq 16–20: one row r_ocᵀ J_o q̇ ≥ t per link–obstacle pair within
  // d_s + σ; fills the strict problem's A_in/b_in, returns the row count.
  int obstacle_rows(const StepInput& in, StepOutput& out) {
    const double ds = p(kSafety), sigma = p(kBuffer), eta = p(kEta);
    const DistanceTable& table = in.distances;
    int rows = 0;
    double min_critical = kInf;
    strict_->g.setZero();
    for (int link = 0; link < table.links; ++link) {
      double link_min = kInf;
      for (int o = 0; o < table.obstacles; ++o) {
        const LinkObstacleDistance& pair = table.at(link, o);
        const int key = link * table.obstacles + o;
        const double d = pair.distance;
        link_min = std::min(link_min, d);
        if (d > ds + sigma) {  // eq 20, first case: t = P, no constraint
          entered_[key] = false;
          continue;
        }
        // critical point O_c and r_oc (eq 16–18); J_o at O_c
        point_jacobian_linear(in.model, in.kin, link, pair.on_link, point_jacobian_);
        const Eigen::Vector3d& r_oc = pair.normal;
        const Eigen::Vector3d& v_obstacle = in.scene.obstacles[o].velocity;
        auto row = strict_->A_in.row(rows);
        row.noalias() = r_oc.transpose() * point_jacobian_;  // P = r_ocᵀ J_o q̇ (eq 19)
        if (row.squaredNorm() < 1e-18) continue;  // no joint changes this distance (e.g. the base link): no row
        double t;
        if (d > ds) {
          if (!entered_[key]) {  // P_c: the approach rate when entering the buffer
            entered_[key] = true;
            approach_at_entry_[key] =
                std::min(-p(kApproach), row.dot(in.state.qdot) - r_oc.dot(v_obstacle));
          }
          const double rho = 0.5 * (1.0 - std::cos(M_PI * (d - ds) / sigma));  // bell ρ(d)
          t = rho * approach_at_entry_[key];  // eq 20, buffer zone
        } else {
          entered_[key] = true;  // back in the buffer later: approach slowly
          approach_at_entry_[key] = -p(kApproach);
          t = eta;  // eq 20, inside the safety margin: push away
        }
        strict_->b_in[rows] = t + r_oc.dot(v_obstacle);
        // eq 8's linear term φ (free in the paper; 0 by default): −k(1 − ρ)(r_ocᵀJ_o)ᵀ
        // favours separating motion inside the buffer before the row binds
        if (p(kClearanceGain) > 0) {
          const double rho = d > ds ? 0.5 * (1.0 - std::cos(M_PI * (d - ds) / sigma)) : 0.0;
          strict_->g.noalias() -= (p(kClearanceGain) * (1.0 - rho)) * row.transpose();
        }
        ++rows;
      }
      if (link < static_cast<int>(link_distance_.size()))
        out.diag.values[link_distance_[link]] = std::isfinite(link_min) ? link_min : -1.0;
      min_critical = std::min(min_critical, link_min);
    }
    out.diag.values[min_critical_] = std::isfinite(min_critical) ? min_critical : -1.0;
    return rows;
  }

  QpStatus solve_strict(const StepInput& in, int rows) {
    QpProblem& qp = *strict_;
    qp.eq_count = m_;
    qp.A_eq.topRows(m_) = in.task_jacobian;
    qp.b_eq.head(m_) = xdot_;
    qp.ineq_count = rows;
    qp.lower = lower_;
    qp.upper = upper_;
    return strict_solver_.solve(qp);
  }

  QpStatus solve_relaxed(const StepInput& in, int rows, bool soften_obstacles) {
    QpProblem& qp = *relaxed_;
    qp.A_eq.topLeftCorner(m_, n_) = in.task_jacobian;
    qp.b_eq.head(m_) = xdot_;
    qp.ineq_count = rows;
    if (rows > 0) {
      qp.A_in.topLeftCorner(rows, n_) = strict_->A_in.topRows(rows);
      qp.A_in.block(0, n_, rows, m_).setZero();  // column n + m stays 1: e
      qp.b_in.head(rows) = strict_->b_in.head(rows);
    }
    qp.g.head(n_) = strict_->g;
    qp.lower.head(n_) = lower_;
    qp.upper.head(n_) = upper_;
    qp.lower[n_ + m_] = 0.0;
    qp.upper[n_ + m_] = soften_obstacles ? kInf : 0.0;
    return relaxed_solver_.solve(qp);
  }

  int n_, m_;
  TaskSpace space_;
  int pair_capacity_ = 0;
  std::unique_ptr<QpProblem> strict_, relaxed_;
  QpSolver strict_solver_{1, 0, 0}, relaxed_solver_{1, 0, 0};
  std::vector<bool> entered_;
  std::vector<double> approach_at_entry_;
  Eigen::MatrixXd jacobian_probe_;
  KinematicsData probe_;
  JacobianConditioning conditioning_;
  Eigen::MatrixXd jjt_;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_;
  Eigen::MatrixXd point_jacobian_;
  Eigen::VectorXd xdot_, residual_, us_, q_probe_, lower_, upper_;
  std::vector<int> link_distance_;
  int status_, relaxation_, task_slack_, iterations_, active_bounds_, obstacle_rows_, active_obstacle_rows_, obstacle_slack_,
      sigma_min_, revised_, min_critical_;
};

}  // namespace

std::vector<ParamSpec> qp_constraints_params() {
  return {{"d_s", "Safety margin d_s", "m", "distance the links keep from obstacles (Qiu eq 20)", 0.1, 0.0,
           10.0, 0.01, {}},
          {"sigma", "Buffer width σ", "m",
           "width of the buffer zone [d_s, d_s + σ] in which the approach rate is smoothed to 0 (eq 20)", 0.2,
           1e-4, 10.0, 0.01, {}},
          {"eta", "Push-away rate η", "m/s", "separation rate required inside the safety margin (eq 20)",
           0.01, 0.0, 10.0, 0.001, {}},
          {"sigma_s", "Singular-value bound σ_s", "",
           "below it the task velocity towards the singularity is removed (eq 23–24); 0 disables", 0.06,
           0.0, 10.0, 0.01, {}},
          {"slack_weight", "Task slack weight", "",
           "weight w of ½w|s|² when the constraints make the exact task infeasible", 1e6, 1.0, 1e12, 1e3, {}},
          {"approach_rate", "Buffer entry approach rate", "m/s",
           "least approach rate |P_c| allowed at the outer edge of the buffer (eq 20); the entry rate when faster",
           0.1, 0.0, 10.0, 0.01, {}},
          {"clearance_gain", "Clearance gain k (linear term φ)", "m/s",
           "φ = −k(1 − ρ(d)) J_oᵀr_oc for each pair in the buffer (eq 8's linear term, not used in the paper's "
           "examples): moves links away before their rows bind; 0 = the paper's minimum-norm objective",
           0.0, 0.0, 100.0, 0.1, {}}};
}
std::unique_ptr<Method> make_qp_constraints(const MethodContext& ctx) {
  return std::make_unique<QpConstraints>(ctx);
}

}  // namespace rrlab
