// Qiu, Cao & Sun: redundancy resolution as a QP with the physical limits and
// obstacle avoidance as inequalities and singularity avoidance as a revision
// of the task equality (Qiu, Cao, Sun, "Redundant manipulator control with constraints for subgoals").
//
//   minimise ½ q̇ᵀq̇ + φᵀq̇                (eq 8 with H = I and the natural basis p_i of
//                                         eq 7, so λ = q̇; φ: the criterion term below)
//   s.t.     J q̇ = ẋ_R                   (eq 9, revised by eq 23)
//            lower ≤ q̇ ≤ upper           (eq 11–15: joint range, velocity, acceleration)
//            r_ocᵀ J_o q̇ ≥ t             (eq 19–20, one row per link within d_s + σ of an obstacle)
//
// The criterion term φ (eq 7–8). The paper's remark after eq 7: with a basis
// vector p_j = ∂g_j/∂q of a criterion g_j and its component λ_j > 0, the
// solution raises g_j. Here the criteria are the clearances d_k of the
// link–obstacle pairs in the buffer and the joints' distances to their range
// limits; φ = −k Σ w_k ∂d_k/∂q (weights w below) is the same thing in the
// natural basis: the unconstrained optimum is q̇ = J⁺ẋ + (I − J⁺J)(−φ), the
// minimum-norm solution plus a positive component along the criterion
// gradients projected on the null space [N_q of eq 5–7]. It raises the
// clearance while a link crosses the buffer, before its row binds; with φ = 0
// (clearance_gain = limit_gain = 0, the paper's minimum-norm examples) the
// links slide along their rows at d_s and the task gives way (20_qiu_circle:
// 0.138 m), a local trap of the minimum-norm objective.
//
// Choices where the paper is silent (documented in README and the scenarios):
//  - critical point (eq 16–17, Fig 1): the point of the link nearest to the
//    obstacle, from the engine's distance table; for a point obstacle and a
//    segment link this is exactly Fig 1's three cases (foot of the
//    perpendicular, or the nearer joint), and it generalises to any shape;
//    r_oc (eq 18) is the table's unit normal obstacle → link. Against an
//    obstacle with faces (box, polygon, wall) the link's two ends get rows
//    too, their distance measured to the tangent plane at the nearest point
//    (a link nearly parallel to a face has two near points; with one row the
//    other end swings in). Points and spheres have a unique, smoothly moving
//    nearest point: one row (Fig 1 exactly).
//  - ρ(d) (eq 20) is the half-cosine bell ½(1 − cos(π (d − d_s)/σ)): 1 at the
//    outer edge of the buffer, 0 at d_s; P_c is the approach rate when the
//    pair entered the buffer, or −approach_rate if that is slower (a pair that
//    entered tangentially would otherwise be frozen at d_s + σ); either way
//    the constraint is not yet active at entry, so q̇ stays continuous.
//  - the d_s floor: every row also demands that the linearised distance after
//    the step stays ≥ min(d, d_s), t ≥ (min(d, d_s) − d)/dt (a fast entry
//    with a large |P_c| could otherwise cross d_s in one step).
//  - moving obstacles: the rate is taken relative, r_ocᵀ(J_o q̇ − v_o) ≥ t.
//  - a pair whose distance no joint can change (r_ocᵀJ_o = 0, e.g. a base
//    link turning about its own axis) gets no row: it could only make the QP
//    infeasible.
//  - φ: w_k = 1 − ρ(d_k) for a pair in the buffer (0 at its outer edge, so q̇
//    stays continuous; 1 at and inside d_s), k = clearance_gain; for a joint
//    within limit_buffer·(range) of a limit, a push k_l(1 − ρ_l) towards the
//    inside (k_l = limit_gain, ρ_l the same bell over the joint's buffer).
//  - joint range (eq 11): the bound keeps 1e-9 rad inside the limit (so the
//    Euler step q + dt·q̇ never lands a rounding error past it) and, with
//    acceleration limits, the velocity from which the joint can still brake
//    before the limit, v²/(2a) + 1.5·v·dt ≤ q_u − q (eq 11 and 13 together;
//    without it eq 13 can leave no velocity that stops in time).
//  - empty bounds (eq 15 can give lower > upper): acceleration wins over
//    velocity, velocity over the joint-range step; bounds are shrunk by a
//    relative 1e-9 so rounding never reports a ratio above 1.
//  - step cap (not in the paper, whose examples have velocity limits; max_step
//    = 0 turns it off): no
//    point of the arm moves more than c = min(max_step, σ) in one step, so a
//    link outside the buffer cannot reach d_s in one step and no step jumps
//    through a thin obstacle. Each joint alone: |q̇_i|·dt·R_i ≤ c (R_i: the
//    farthest capsule point beyond joint i from its axis), a bound of the QP;
//    all joints together: the solution is scaled down when a link end (plus
//    |ω|·radius) would move more than c, or more than the link's clearance
//    (at least c/10), so a link cannot swing into an obstacle between two
//    distance checks (the acceleration bound, when it cannot brake that much,
//    wins). `capped_steps` counts the scaled steps.
//  - u_s (eq 23) is oriented so that moving the end-effector along +u_s
//    increases σ_min (finite difference), so eq 23 removes only the motion
//    towards the singularity.
//  - infeasible QP (§III end: "the constraints are over stringent
//    sometimes"): stage 1, the task gives way: J q̇ − s = ẋ_R at cost ½w|s|²
//    (w = slack_weight); stage 2, the obstacle rows' smoothing (buffer rate,
//    η push-away) gets a shared slack e ≥ 0 at cost ½·10³w·e², the d_s floor
//    staying hard; stage 3, as 2 without the acceleration bound (it cannot
//    brake in time; range, velocity and step cap stay); stage 4 (a moving
//    obstacle faster than the arm can retreat): the d_s floor softened too.
//    Reported per step in `relaxation` (0–4) and `obstacle_slack`, and counted
//    over the run (the last frame holds the totals) in `relaxed_steps` (≥ 1),
//    `slack_steps` (≥ 2), `acceleration_relaxed_steps` (≥ 3) and
//    `margin_broken_steps` (4): d_s is never broken by stages 0–3.
#include <algorithm>
#include <cmath>

#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/velocity_constraints.hpp>
#include <rrlab/util/qp_solver.hpp>

namespace rrlab {
namespace {


constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kShrink = 1.0 - 1e-9;
constexpr double kRangeMargin = 1e-9;  // rad (m): the range bound stays this far inside

// ½(1 − cos(π x)) on [0, 1]: 0 at 0, 1 at 1, flat at both ends (the bell ρ of eq 20)
double bell(double x) { return 0.5 * (1.0 - std::cos(M_PI * std::clamp(x, 0.0, 1.0))); }

class QpConstraints final : public Method {
  // Parameters by name (Method::slot).
  const ParamSlot kSafety = slot("d_s"), kBuffer = slot("sigma"), kEta = slot("eta"), kSigmaS = slot("sigma_s"),
                  kSlackWeight = slot("slack_weight"), kApproach = slot("approach_rate"),
                  kClearanceGain = slot("clearance_gain"), kLimitGain = slot("limit_gain"),
                  kLimitBuffer = slot("limit_buffer"), kMaxStep = slot("max_step");

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
        upper_(n_),
        lower_free_(n_),
        upper_free_(n_),
        phi_(n_),
        reach_(n_) {
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
    step_scale_ = declare_diagnostic("step_scale");
    relaxed_steps_ = declare_diagnostic("relaxed_steps");
    slack_steps_ = declare_diagnostic("slack_steps");
    acceleration_steps_ = declare_diagnostic("acceleration_relaxed_steps");
    broken_steps_ = declare_diagnostic("margin_broken_steps");
    capped_steps_ = declare_diagnostic("capped_steps");
    for (int l = 0; l < ctx.model.link_count(); ++l)
      link_distance_.push_back(declare_diagnostic("critical_distance_" + std::to_string(l + 1)));
  }

  void step(const StepInput& in, StepOutput& out) override {
    if (in.state.step == 0) start_run();  // a (re)started run replays bit for bit
    if (in.distances.links * in.distances.obstacles > pair_capacity_)
      size_pairs(in.distances.links, in.distances.obstacles);  // obstacles added (allocates once)
    revise_task_velocity(in, out);
    clamp_task_velocity(in);
    joint_bounds(in);
    const int rows = obstacle_rows(in, out);
    limit_criterion(in);

    // stage 0: the paper's QP; 1: task slack; 2: + obstacle-row slack above the
    // d_s floor; 3: + no acceleration bound; 4: + the d_s floor softened
    QpStatus status = solve_strict(in, rows);
    int relaxation = 0;
    if (status == QpStatus::optimal) {
      out.qdot = strict_solver_.x();
    } else {
      const bool has_acceleration = in.model.limits.has_acceleration();
      for (relaxation = 1; relaxation <= 4; ++relaxation) {
        if (relaxation == 3 && !has_acceleration) continue;  // stage 2 again
        if (relaxation >= 2 && rows == 0) continue;           // nothing to soften
        status = solve_relaxed(rows, relaxation);
        if (status == QpStatus::optimal) break;
      }
      relaxation = std::min(relaxation, 4);
      if (status == QpStatus::optimal)
        out.qdot = relaxed_solver_.x().head(n_);
      else  // not expected (stage 4 is always feasible): stop as fast as allowed
        out.qdot = lower_.cwiseMax(upper_.cwiseMin(Eigen::VectorXd::Zero(n_)));
    }
    const bool free_bounds = relaxation >= 3;
    const double scale = cap_step(in, out.qdot, free_bounds ? lower_free_ : lower_, free_bounds ? upper_free_ : upper_);

    const QpSolver& used = relaxation == 0 ? strict_solver_ : relaxed_solver_;
    int active_bounds = 0, active_rows = 0;
    for (int i = 0; i < n_; ++i) active_bounds += used.lower_active(i) + used.upper_active(i);
    for (int k = 0; k < rows; ++k) active_rows += used.inequality_active(k);
    out.diag.values[obstacle_slack_] = relaxation >= 2 ? relaxed_solver_.x()[n_ + m_] : 0.0;
    out.diag.values[status_] = static_cast<double>(status);
    out.diag.values[relaxation_] = relaxation;
    residual_.noalias() = in.task_jacobian * out.qdot;
    residual_ -= xdot_;
    out.diag.values[task_slack_] = residual_.norm();
    out.diag.values[iterations_] = used.iterations();
    out.diag.values[active_bounds_] = active_bounds;
    out.diag.values[obstacle_rows_] = rows;
    out.diag.values[active_obstacle_rows_] = active_rows;
    out.diag.values[step_scale_] = scale;
    relaxed_count_ += relaxation >= 1;
    slack_count_ += relaxation >= 2;
    acceleration_count_ += relaxation >= 3;
    broken_count_ += relaxation >= 4;
    capped_count_ += scale < 1.0;
    out.diag.values[relaxed_steps_] = static_cast<double>(relaxed_count_);
    out.diag.values[slack_steps_] = static_cast<double>(slack_count_);
    out.diag.values[acceleration_steps_] = static_cast<double>(acceleration_count_);
    out.diag.values[broken_steps_] = static_cast<double>(broken_count_);
    out.diag.values[capped_steps_] = static_cast<double>(capped_count_);
  }

 private:
  void size_pairs(int links, int obstacles) {
    pair_capacity_ = std::max(1, links * obstacles);
    entered_.assign(pair_capacity_, false);
    approach_at_entry_.assign(pair_capacity_, 0.0);
    floor_.resize(3 * pair_capacity_);  // up to three rows per pair (O_c and the link's ends)
    strict_ = std::make_unique<QpProblem>(n_, m_, 3 * pair_capacity_);
    // relaxed: each row twice (softened, and its d_s floor)
    relaxed_ = std::make_unique<QpProblem>(n_ + m_ + 1, m_, 6 * pair_capacity_);
    strict_solver_ = QpSolver(n_, m_, 3 * pair_capacity_);
    relaxed_solver_ = QpSolver(n_ + m_ + 1, m_, 6 * pair_capacity_);
    // relaxed problem, x = [q̇; s; e]: H = diag(I, w I, w_o), J q̇ − s = ẋ_R with s
    // free, every obstacle row r_ocᵀJ_o q̇ + e ≥ t with e ≥ 0 (stages 2–4), and
    // from stage 2 on a floor row r_ocᵀJ_o q̇ ≥ floor without e (stages 2–3)
    relaxed_->eq_count = m_;
    relaxed_->A_eq.block(0, n_, m_, m_) = -Eigen::MatrixXd::Identity(m_, m_);
    relaxed_->A_eq.col(n_ + m_).setZero();
    set_slack_weight();
  }

  // Forget what the previous run left: buffer entries, warm starts, counts.
  void start_run() {
    std::fill(entered_.begin(), entered_.end(), false);
    std::fill(approach_at_entry_.begin(), approach_at_entry_.end(), 0.0);
    strict_solver_.forget_warm_start();
    relaxed_solver_.forget_warm_start();
    relaxed_count_ = slack_count_ = acceleration_count_ = broken_count_ = capped_count_ = 0;
  }

  void set_slack_weight() {
    relaxed_->H.setIdentity();
    relaxed_->H.block(n_, n_, m_, m_) *= p(kSlackWeight);
    relaxed_->H(n_ + m_, n_ + m_) = 1e3 * p(kSlackWeight);  // obstacles before the task
  }
  void on_param_changed(ParamSlot changed) override {
    if (changed == kSlackWeight && relaxed_) set_slack_weight();
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

  // The step cap applies to the hand too: a request to move it farther than c
  // in one step (the task loop after a large error, K·e) is scaled to c, so a
  // relaxed step heads for the target instead of saturating every bound.
  void clamp_task_velocity(const StepInput& in) {
    if (!step_capped()) return;
    const double limit = step_cap() / in.dt;
    const double speed = xdot_.head(std::min(m_, 3)).norm();
    if (speed > limit) xdot_ *= limit / speed;
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

  // The step cap's c: no point of the arm moves more than this in one step.
  // max_step = 0: no cap at all (the paper has none).
  bool step_capped() const { return p(kMaxStep) > 0; }
  double step_cap() const { return step_capped() ? std::min(p(kMaxStep), p(kBuffer)) : kInf; }

  // Qiu eq 11–15, merged: lower = max(range, velocity, acceleration), upper = min(…);
  // then the step cap. lower_free_/upper_free_: the same without eq 13 (stage 3).
  void joint_bounds(const StepInput& in) {
    const JointLimits& lim = in.model.limits;
    const double dt = in.dt;
    const double cap = step_cap();
    joint_reach(in.model, in.kin, reach_);  // R_i (velocity_constraints.hpp)
    for (int i = 0; i < n_; ++i) {
      const double qd_prev = in.state.qdot[i];
      const double acc = lim.acceleration[i];
      // eq 11, 1e-9 inside, and the braking velocity v: v²/(2a) + 1.5 v dt ≤ room
      double range_lo = -kInf, range_hi = kInf;
      if (std::isfinite(lim.upper[i])) range_hi = braking_velocity(lim.upper[i] - in.state.q[i] - kRangeMargin, acc, dt);
      if (std::isfinite(lim.lower[i])) range_lo = -braking_velocity(in.state.q[i] - lim.lower[i] - kRangeMargin, acc, dt);
      const double cap_i = reach_[i] > 1e-12 ? kShrink * cap / (dt * reach_[i]) : kInf;
      double lo = -kShrink * lim.velocity[i], hi = kShrink * lim.velocity[i];  // eq 12
      intersect(lo, hi, range_lo, range_hi);
      intersect(lo, hi, -cap_i, cap_i);
      lower_free_[i] = lo;
      upper_free_[i] = hi;
      lo = qd_prev - kShrink * dt * acc;  // eq 13
      hi = qd_prev + kShrink * dt * acc;
      intersect(lo, hi, lower_free_[i], upper_free_[i]);
      lower_[i] = lo;
      upper_[i] = hi;
    }
  }

  // The largest velocity towards a limit `room` away (≥ 0: towards it; < 0:
  // already past, come back) that one step of it and then braking at `acc`
  // keeps inside: the step, plus the braking distance v²/(2a) + ½v·dt of the
  // discrete deceleration v, v − a dt, …
  static double braking_velocity(double room, double acc, double dt) {
    if (room <= 0 || !std::isfinite(acc)) return room / dt;  // eq 11 alone
    return rrlab::braking_velocity(room, acc, dt);           // velocity_constraints.hpp
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

  // Scales q̇ down when some link end (plus |ω|·radius) would move more than the
  // cap in this step, as far as [lower, upper] lets it (the box keeps the
  // acceleration bound). Returns the factor applied (1: none).
  double cap_step(const StepInput& in, Eigen::VectorXd& qdot, const Eigen::VectorXd& lower,
                  const Eigen::VectorXd& upper) {
    if (!step_capped()) return 1.0;
    const Model& model = in.model;
    double largest = 0;  // the largest ratio of a link's displacement to its cap
    for (int l = 0; l < model.link_count(); ++l) {
      Eigen::Vector3d v0 = Eigen::Vector3d::Zero(), v1 = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();
      const Eigen::Vector3d p0 = in.kin.link_start.col(l), p1 = in.kin.link_end.col(l);
      for (int i = 0; i <= model.links[l].last_joint && i < n_; ++i) {
        const Eigen::Vector3d u = in.kin.axis_dirs.col(i);
        if (model.joints[i].type == JointType::prismatic) {
          v0 += qdot[i] * u;
          v1 += qdot[i] * u;
        } else {
          const Eigen::Vector3d a = in.kin.axis_points.col(i);
          v0 += qdot[i] * u.cross(p0 - a);
          v1 += qdot[i] * u.cross(p1 - a);
          w += qdot[i] * u;
        }
      }
      // this link's cap: c, and not farther than its clearance (at least c/10)
      double cap_l = step_cap();
      for (int o = 0; o < in.distances.obstacles && l < in.distances.links; ++o)
        cap_l = std::min(cap_l, std::max(in.distances.at(l, o).distance, 0.1 * step_cap()));
      const double move = (std::max(v0.norm(), v1.norm()) + w.norm() * model.links[l].radius) * in.dt;
      if (move > 0) largest = std::max(largest, move / cap_l);
    }
    if (!(largest > 1.0)) return 1.0;
    double scale = 1.0 / largest;
    for (int i = 0; i < n_; ++i) {  // s·q̇ must stay in the box, which holds q̇
      if (qdot[i] > 0 && lower[i] > 0) scale = std::max(scale, lower[i] / qdot[i]);
      if (qdot[i] < 0 && upper[i] < 0) scale = std::max(scale, upper[i] / qdot[i]);
    }
    scale = std::min(scale, 1.0);
    qdot *= scale;
    return scale;
  }

  // Qiu eq 16–20: one row r_ocᵀ J_o q̇ ≥ t per link–obstacle pair within
  // d_s + σ; fills the strict problem's A_in/b_in and the floors, and the
  // clearance part of φ; returns the row count.
  int obstacle_rows(const StepInput& in, StepOutput& out) {
    const double ds = p(kSafety), sigma = p(kBuffer), eta = p(kEta), gain = p(kClearanceGain);
    const DistanceTable& table = in.distances;
    int rows = 0;
    double min_critical = kInf;
    phi_.setZero();
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
        const Eigen::Vector3d& r_oc = pair.normal;
        const Eigen::Vector3d& v_obstacle = in.scene.obstacles[o].velocity;
        const double v_along = r_oc.dot(v_obstacle);
        if (!entered_[key] && d > ds) {  // P_c: the approach rate when entering the buffer
          point_jacobian_linear(in.model, in.kin, link, pair.on_link, point_jacobian_);
          entered_[key] = true;
          approach_at_entry_[key] = std::min(-p(kApproach), r_oc.dot(point_jacobian_ * in.state.qdot) - v_along);
        } else if (d <= ds) {
          entered_[key] = true;  // back in the buffer later: approach slowly
          approach_at_entry_[key] = -p(kApproach);
        }
        // rows at O_c and, against the same tangent plane, at the link's two
        // ends: a link nearly parallel to a face has two near points, and a
        // row at one of them alone lets the other end swing in
        const Eigen::Vector3d ends[3] = {pair.on_link, in.kin.link_start.col(link), in.kin.link_end.col(link)};
        const double radius = in.model.links[link].radius;
        for (int e = 0; e < (has_faces(in.scene.obstacles[o].shape) ? 3 : 1); ++e) {
          const double de = e == 0 ? d : r_oc.dot(ends[e] - pair.on_obstacle) - radius;
          if (e > 0 && (de > ds + sigma || (ends[e] - pair.on_link).squaredNorm() < 1e-12)) continue;
          point_jacobian_linear(in.model, in.kin, link, ends[e], point_jacobian_);
          auto row = strict_->A_in.row(rows);
          row.noalias() = r_oc.transpose() * point_jacobian_;  // P = r_ocᵀ J_o q̇ (eq 19)
          if (row.squaredNorm() < 1e-18) continue;  // no joint changes this distance (e.g. the base link): no row
          double t, rho = 0;
          if (de > ds) {
            rho = bell((de - ds) / sigma);        // bell ρ(d)
            t = rho * approach_at_entry_[key];  // eq 20, buffer zone
          } else {
            t = eta;  // eq 20, inside the safety margin: push away
          }
          const double floor = (std::min(de, ds) - de) / in.dt;  // the d_s floor
          floor_[rows] = floor + v_along;
          strict_->b_in[rows] = std::max(t, floor) + v_along;
          // eq 7–8's criterion term: φ −= k (1 − ρ) ∂d/∂q, ∂d/∂q = (r_ocᵀJ_o)ᵀ (O_c only)
          if (e == 0 && gain > 0) phi_.noalias() -= (gain * (1.0 - rho)) * row.transpose();
          ++rows;
        }
      }
      if (link < static_cast<int>(link_distance_.size()))
        out.diag.values[link_distance_[link]] = std::isfinite(link_min) ? link_min : -1.0;
      min_critical = std::min(min_critical, link_min);
    }
    out.diag.values[min_critical_] = std::isfinite(min_critical) ? min_critical : -1.0;
    return rows;
  }

  // eq 7–8's criterion term for the joint range: φ_i −= ±k_l (1 − ρ_l) within
  // limit_buffer·(upper − lower) of a limit, towards the inside.
  void limit_criterion(const StepInput& in) {
    const double gain = p(kLimitGain), fraction = p(kLimitBuffer);
    if (!(gain > 0) || !(fraction > 0)) return;
    const JointLimits& lim = in.model.limits;
    for (int i = 0; i < n_; ++i) {
      if (!std::isfinite(lim.lower[i]) || !std::isfinite(lim.upper[i])) continue;
      const double width = fraction * (lim.upper[i] - lim.lower[i]);
      if (!(width > 0)) continue;
      const double q = in.state.q[i];
      if (q - lim.lower[i] < width) phi_[i] -= gain * (1.0 - bell((q - lim.lower[i]) / width));
      if (lim.upper[i] - q < width) phi_[i] += gain * (1.0 - bell((lim.upper[i] - q) / width));
    }
  }

  QpStatus solve_strict(const StepInput& in, int rows) {
    QpProblem& qp = *strict_;
    qp.eq_count = m_;
    qp.A_eq.topRows(m_) = in.task_jacobian;
    qp.b_eq.head(m_) = xdot_;
    qp.ineq_count = rows;
    qp.lower = lower_;
    qp.upper = upper_;
    qp.g = phi_;
    return strict_solver_.solve(qp);
  }

  // Stage 1: task slack; 2: + obstacle slack e above the hard d_s floor rows;
  // 3: as 2 without the acceleration bound; 4: e without the floor rows.
  QpStatus solve_relaxed(int rows, int stage) {
    QpProblem& qp = *relaxed_;
    const bool floors = stage == 2 || stage == 3;
    qp.A_eq.topLeftCorner(m_, n_) = strict_->A_eq.topRows(m_);
    qp.b_eq.head(m_) = xdot_;
    qp.ineq_count = floors ? 2 * rows : rows;
    if (rows > 0) {
      qp.A_in.topLeftCorner(rows, n_) = strict_->A_in.topRows(rows);
      qp.A_in.block(0, n_, rows, m_).setZero();
      qp.A_in.block(0, n_ + m_, rows, 1).setOnes();  // + e
      qp.b_in.head(rows) = strict_->b_in.head(rows);
      if (floors) {
        qp.A_in.block(rows, 0, rows, n_) = strict_->A_in.topRows(rows);
        qp.A_in.block(rows, n_, rows, m_ + 1).setZero();
        qp.b_in.segment(rows, rows) = floor_.head(rows);
      }
    }
    qp.g.head(n_) = phi_;
    qp.lower.head(n_) = stage >= 3 ? lower_free_ : lower_;
    qp.upper.head(n_) = stage >= 3 ? upper_free_ : upper_;
    qp.lower[n_ + m_] = 0.0;
    qp.upper[n_ + m_] = stage >= 2 ? kInf : 0.0;
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
  Eigen::VectorXd xdot_, residual_, us_, q_probe_, lower_, upper_, lower_free_, upper_free_, phi_, reach_, floor_;
  std::vector<int> link_distance_;
  long relaxed_count_ = 0, slack_count_ = 0, acceleration_count_ = 0, broken_count_ = 0, capped_count_ = 0;
  int status_, relaxation_, task_slack_, iterations_, active_bounds_, obstacle_rows_, active_obstacle_rows_, obstacle_slack_,
      sigma_min_, revised_, min_critical_, step_scale_, relaxed_steps_, slack_steps_, acceleration_steps_,
      broken_steps_, capped_steps_;
};

}  // namespace

std::vector<ParamSpec> qp_constraints_params() {
  return {{"d_s", "Safety margin d_s", "m", "distance the links keep from obstacles (Qiu eq 20; the paper's examples: 0.1)", 0.01, 0.0,
           10.0, 0.01, {}},
          {"sigma", "Buffer width σ", "m",
           "width of the buffer zone [d_s, d_s + σ] in which the approach rate is smoothed to 0 (eq 20; the paper's "
           "examples: 0.2)",
           0.05,
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
          {"clearance_gain", "Clearance gain k (criterion term φ)", "m/s",
           "φ = −k Σ(1 − ρ(d)) J_oᵀr_oc over the pairs in the buffer (eq 7–8's criterion term): raises the "
           "clearance before the rows bind; 0 = the minimum-norm objective of the paper's examples",
           30.0, 0.0, 1000.0, 0.1, {}},
          {"limit_gain", "Joint-limit gain k_l (criterion term φ)", "rad/s",
           "push towards the inside for a joint within limit_buffer of its range limit (eq 7–8's criterion "
           "term); 0 = off",
           0.0, 0.0, 1000.0, 0.1, {}},
          {"limit_buffer", "Joint-limit buffer", "",
           "share of each joint's range, at either end, in which limit_gain acts", 0.1, 0.0, 0.5, 0.01, {}},
          {"max_step", "Step cap", "m",
           "no point of the arm moves more than min(max_step, σ) in one step (so no step jumps through an "
           "obstacle, also without velocity limits); 0 = no cap (the paper has none)",
           0.02, 0.0, 10.0, 0.01, {}}};
}
std::unique_ptr<Method> make_qp_constraints(const MethodContext& ctx) {
  return std::make_unique<QpConstraints>(ctx);
}

}  // namespace rrlab
