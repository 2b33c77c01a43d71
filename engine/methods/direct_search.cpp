// Kapoor, Cetin & Tesar (1998): redundancy resolution by direct search
// (Kapoor, Cetin, Tesar, "Performance based redundancy resolution with multiple criteria" (DETC 1998)). Every step:
//  1. generate options (§3.1, eq 1–6): the k perturbed joints take −Δ, 0, +Δ
//     (3^k combinations); the other joints form the block J_b that meets the
//     end-effector constraint: δθ_b = J_b⁻¹(δx − J_p δθ_p) (eq 3 with eq 6),
//     then Newton iterations on the block through the forward kinematics
//     (eq 1–4) until |x − x̄| < ε (eq 5);
//  2. select (§3.2, eq 7–8): each criterion normalised over the feasible
//     options, R_j = (1/ℓ) Σ w_i ψ̄_i(θ^j), θ* = argmin_j R_j.
// Criteria: JRA ψ1 = Σ (θ_i − θ'_i)²/θ_i,max, JVM ψ2 = Σ (θ_i − θ_i,curr)²,
// DM ψ3 = σmax/σmin of the task Jacobian, and (not in the paper) the engine's
// obstacle clearance ψ4 = −min_link d_link, minimised: direct_search_criteria.*
// (with the choices for θ_i,max, ψ4 and DM's length unit). Which joints are
// perturbed, and the block switch's largest-determinant set: direct_search_joint_sets.*
//
// Choices where the paper is silent (README, scenarios 22–23):
//  - the block is every joint not perturbed; with exactly n − m perturbed
//    joints it is the paper's square J_m×m (inverse); otherwise J_b⁺. The
//    first compensation (eq 3 with eq 6) uses J_b at the current
//    configuration, the Newton iterations J_b at the option (full Newton:
//    quadratic convergence even where the block is poorly conditioned); an
//    option whose residual grows keeps its last better iterate (infeasible
//    unless that met eq 5). After an iteration that cut the residual
//    100-fold, the next reuses the last LU (a chord step: J_b moved by about
//    those small steps, so it contracts as much again); one that does not
//    cut it 10-fold is undone and replaced by the full step.
//  - the target is the reference pose at t + dt (the method places the arm
//    itself: it sets q_next, `integrated`).
//  - option feasibility: Newton converged within `newton_iterations`, every
//    joint within its range and within its velocity limit over the step (a
//    near-singular block can otherwise converge on another IK branch).
//  - block switch (`block_switch` > 0, not in the paper's experiment): when
//    the mask's block gets near singular (σ_min below it), the step uses the
//    set of as many perturbed joints whose block has the largest |det J_b|
//    (det J_b J_bᵀ for a wide block) — the choice §3.1 calls desirable but
//    did not employ. When no option is feasible the step is generated once
//    more with that set, restricted to sets that perturb every joint some
//    option pushed past a limit (perturbed, it moves by 0 or ±Δ only). With
//    still no feasible option the option nearest the target within the
//    joint ranges and speeds is taken if it is nearer than the arm is, else
//    the arm stays (feasible_options = 0 reports it). Without these a
//    singular block or a block joint at its limit froze the arm for good.
//  - recovery (rrlab's, not in the paper, whose scheme starts with the hand on
//    the path): when no option is feasible, a damped least-squares step
//    toward the target over all joints, δθ = Jᵀ(JJᵀ + λ²I)⁻¹δx with
//    λ = `recovery_damping`, scaled uniformly into the joint velocity limits
//    over the step and clamped to the joint ranges, is taken when it ends
//    nearer the target than the nearest option and than staying. Without it
//    a hand that starts (or is pushed) a few cm off the path never gets an
//    option that meets eq 5 within the joint speeds, and the arm stays.
//  - DM rule (`dm_rule_fraction` f and `dm_rule_reference` D > 0): when the
//    current DM reaches f·D, the weights of JRA and JVM are scaled by 0.8
//    and 0.2 (the paper's change from (1, 1, 1) to (0.8, 0.2, 1.0)) and stay
//    so until f or D is changed. The threshold is relative because the
//    paper's 250 is an absolute DM of an unknown length unit: D is the peak
//    DM of the equal-weight run at the same L, and the paper's threshold was
//    250 of the more than 300 its equal-weight run reached (f ≈ 0.83).
//  - defaults for the generated families (chosen on held-out seed 1001):
//    Δ = 0.02 rad (the paper's 0.002 moves the null space too slowly to keep
//    joints off their limits), w_dm = 0 (DM pulled options away from
//    obstacle clearance), block_switch = 0.02.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>

#include <rrlab/methods/direct_search_criteria.hpp>
#include <rrlab/methods/direct_search_joint_sets.hpp>
#include <rrlab/methods/factories.hpp>
#include <rrlab/util/right_inverse.hpp>
#include <rrlab/util/small_lu.hpp>

namespace rrlab {
namespace {

using kapoor::kCriteria;
using kapoor::kDm;
using kapoor::kJra;
using kapoor::kJvm;
using kapoor::kObstacle;
constexpr int kMaxPerturbed = kapoor::JointSets::kMaxPerturbed;
constexpr int kMaxOptions = kapoor::JointSets::kMaxOptions;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();  // a criterion not computed
// chord step: taken after a Newton iteration that cut the residual by at
// least kChordStart, kept when it cuts it by at least kChordContraction
constexpr double kChordStart = 1e-2, kChordContraction = 1e-1;

class DirectSearch final : public Method {
  // Parameters by name (Method::slot).
  const ParamSlot kDelta = slot("delta"), kMask = slot("perturb_mask"), kWJra = slot("w_jra"), kWJvm = slot("w_jvm"),
                  kWDm = slot("w_dm"), kWObstacle = slot("w_obstacle"), kDmFraction = slot("dm_rule_fraction"),
                  kDmReference = slot("dm_rule_reference"), kIterations = slot("newton_iterations"),
                  kTolerance = slot("tolerance"), kDmLength = slot("dm_length"), kBlockSwitch = slot("block_switch"),
                  kRecovery = slot("recovery_damping");

 public:
  explicit DirectSearch(const MethodContext& ctx)
      : Method(direct_search_params()),
        n_(ctx.model.dof()),
        m_(task_rows(ctx.space)),
        space_(ctx.space),
        probe_(ctx.model),
        jacobian_(m_, n_),
        psi_(ctx.model, ctx.space),
        sets_(n_, m_),
        block_jacobian_(m_, n_),
        block_inverse_(m_, std::max(1, n_ - 1)),
        option_inverse_(m_, std::max(1, n_ - 1)),
        options_(n_, kMaxOptions),
        criteria_(kMaxOptions, kCriteria),
        residual_(kMaxOptions),
        feasible_(kMaxOptions),
        theta_(n_),
        error_(m_),
        error0_(m_),
        error_previous_(m_),
        rhs_(m_),
        recovery_inverse_(m_, n_),
        recovery_step_(n_),
        recovery_q_(n_),
        probe_q_(n_) {
    theta_previous_ = Eigen::VectorXd::Zero(n_);
    choose_joints();
    const char* names[] = {"jra", "jvm", "dm", "obstacle_clearance"};
    for (int c = 0; c < kCriteria; ++c) chosen_diag_[c] = declare_diagnostic(names[c]);
    const char* weights[] = {"w_jra", "w_jvm", "w_dm", "w_obstacle"};
    for (int c = 0; c < kCriteria; ++c) weight_diag_[c] = declare_diagnostic(weights[c]);
    feasible_diag_ = declare_diagnostic("feasible_options");
    options_diag_ = declare_diagnostic("options");
    chosen_diag_index_ = declare_diagnostic("chosen_option");
    rule_diag_ = declare_diagnostic("dm_rule_active");
    current_dm_diag_ = declare_diagnostic("current_dm");
    iterations_diag_ = declare_diagnostic("newton_iterations");
    residual_diag_ = declare_diagnostic("residual");
    block_sigma_diag_ = declare_diagnostic("block_sigma_min");
    switched_diag_ = declare_diagnostic("block_switched");
    recovery_diag_ = declare_diagnostic("recovery");
  }

  void step(const StepInput& in, StepOutput& out) override {
    const Eigen::VectorXd& q = in.state.q;
    if (in.state.step == 0) rule_active_ = false;  // a (re)started run replays bit for bit
    probe_valid_ = false;
    set_target(in);
    // eq 2: δx at the current configuration
    pose_error(in.kin, error0_);
    // the block J_b and the perturbed columns J_p, from the current Jacobian
    sets_.use(sets_.mask_bits());
    for (int c = 0; c < sets_.block_count(); ++c) block_jacobian_.col(c) = in.task_jacobian.col(sets_.block(c));
    block_inverse_.factor_pinv(block_jacobian_);
    bool switched = false;
    if (p(kBlockSwitch) > 0 && block_inverse_.sigma_min() < p(kBlockSwitch) && sets_.has_alternatives()) {
      // §3.1: "the full rank submatrix with the largest determinant" — only
      // when the chosen block is near singular
      sets_.use(sets_.largest_determinant_set(in.task_jacobian, 0));
      for (int c = 0; c < sets_.block_count(); ++c) block_jacobian_.col(c) = in.task_jacobian.col(sets_.block(c));
      block_inverse_.factor_pinv(block_jacobian_);
      switched = true;
    }
    psi_.prepare_clearance(in);

    // the DM rule looks at the current configuration
    const double dm_now = psi_.dexterity(in.task_jacobian, p(kDmLength));
    if (p(kDmFraction) > 0 && p(kDmReference) > 0 && dm_now >= p(kDmFraction) * p(kDmReference)) rule_active_ = true;
    out.diag.values[current_dm_diag_] = std::isfinite(dm_now) ? dm_now : -1.0;

    double weights[kCriteria] = {p(kWJra), p(kWJvm), p(kWDm), p(kWObstacle)};
    if (rule_active_) weights[kJra] *= 0.8, weights[kJvm] *= 0.2;
    // DM (an eigen-decomposition per option) only where the selection weighs it
    const bool with_dm = weights[kDm] > 0;

    // 1. generate options (eq 1–6); when no option meets eq 5 within the
    // ranges and speeds, once more with the largest-determinant block (§3.1)
    int feasible = generate_options(in, with_dm);
    if (feasible == 0 && p(kBlockSwitch) > 0 && sets_.has_alternatives()) {
      // the block must not hold a joint that its options pushed past a limit:
      // perturbed, such a joint keeps its value or moves by ±Δ
      const unsigned long long best =
          sets_.largest_determinant_set(in.task_jacobian, sets_.out_of_range_bits(options_, in.model.limits));
      if (best != sets_.current_bits()) {
        sets_.use(best);
        for (int c = 0; c < sets_.block_count(); ++c) block_jacobian_.col(c) = in.task_jacobian.col(sets_.block(c));
        block_inverse_.factor_pinv(block_jacobian_);
        switched = true;
        feasible = generate_options(in, with_dm);
      }
    }
    out.diag.values[block_sigma_diag_] = block_inverse_.sigma_min();
    out.diag.values[switched_diag_] = switched;
    const int count = sets_.option_count();

    // 2. selection (eq 7–8)
    int chosen = -1;
    bool recovered = false;
    if (feasible > 0) {
      double lo[kCriteria], hi[kCriteria];
      for (int c = 0; c < kCriteria; ++c) lo[c] = kInf, hi[c] = -kInf;
      for (int j = 0; j < count; ++j) {
        if (!feasible_[j]) continue;
        for (int c = 0; c < kCriteria; ++c) lo[c] = std::min(lo[c], criteria_(j, c)), hi[c] = std::max(hi[c], criteria_(j, c));
      }
      double best = kInf;
      for (int j = 0; j < count; ++j) {
        if (!feasible_[j]) continue;
        double r = 0;
        for (int c = 0; c < kCriteria; ++c) {
          const double span = hi[c] - lo[c];
          // normalised ψ̄ (eq 7); a criterion equal on every option counts 0
          if (span > 0 && std::isfinite(span)) r += weights[c] * (criteria_(j, c) - lo[c]) / span;
        }
        r /= static_cast<double>(kCriteria);  // R_j = (1/ℓ) Σ w_i ψ̄_i
        if (r < best) best = r, chosen = j;  // eq 8 (ties: the first option)
      }
    } else {
      // no feasible option: the option nearest the target within the joint
      // ranges and speeds, if it is nearer than staying; else stay
      double best = error0_.cwiseAbs().maxCoeff();
      for (int j = 0; j < count; ++j)
        if (residual_[j] < best && within_limits(in.model.limits, options_.col(j)) &&
            within_speed(in.model.limits, options_.col(j), q, in.dt))
          best = residual_[j], chosen = j;
      // rrlab's recovery: a damped step toward the target, if it ends nearer still
      if (p(kRecovery) > 0 && recovery_step(in) < best) recovered = true, chosen = -1;
    }

    if (chosen >= 0 && std::isnan(criteria_(chosen, kDm))) {
      // its DM was not needed to choose it: the diagnostic's, at its kinematics
      theta_ = options_.col(chosen);
      probe_fk(in.model, theta_);
      task_jacobian(in.model, probe_, space_, jacobian_);
      criteria_(chosen, kDm) = psi_.dexterity(jacobian_, p(kDmLength));
    }
    out.integrated = true;
    if (recovered)
      out.q_next = recovery_q_;
    else if (chosen >= 0)
      out.q_next = options_.col(chosen);
    else
      out.q_next = q;
    out.qdot = (out.q_next - q) / in.dt;
    for (int c = 0; c < kCriteria; ++c) {  // −1: no option taken (the arm stays)
      const double v = chosen >= 0 ? criteria_(chosen, c) : -1.0;
      out.diag.values[chosen_diag_[c]] = std::isfinite(v) ? v : -1.0;
      out.diag.values[weight_diag_[c]] = weights[c];
    }
    if (!psi_.has_distances() || chosen < 0) out.diag.values[chosen_diag_[kObstacle]] = -1.0;
    else out.diag.values[chosen_diag_[kObstacle]] = -criteria_(chosen, kObstacle);
    out.diag.values[feasible_diag_] = feasible;
    out.diag.values[options_diag_] = count;
    out.diag.values[chosen_diag_index_] = chosen;
    out.diag.values[rule_diag_] = rule_active_;
    out.diag.values[iterations_diag_] = max_iterations_used_;
    out.diag.values[residual_diag_] = recovered ? recovery_residual_ : chosen >= 0 ? residual_[chosen] : -1.0;
    out.diag.values[recovery_diag_] = recovered;
  }

 private:
  // rrlab's recovery step into recovery_q_: δθ = Jᵀ(JJᵀ + λ²I)⁻¹δx at the
  // current configuration, scaled into the joint speeds over the step and
  // clamped to the ranges. Returns its end-effector residual (max |δx|).
  double recovery_step(const StepInput& in) {
    const JointLimits& limits = in.model.limits;
    recovery_inverse_.factor_dls(in.task_jacobian, p(kRecovery));
    recovery_inverse_.apply(error0_, recovery_step_);
    double scale = 1.0;
    for (int i = 0; i < n_; ++i) {
      const double reach = limits.velocity[i] * in.dt, move = std::abs(recovery_step_[i]);
      if (std::isfinite(reach) && move > reach) scale = std::min(scale, reach / move);
    }
    recovery_q_ = in.state.q + scale * recovery_step_;
    recovery_q_ = recovery_q_.cwiseMax(limits.lower).cwiseMin(limits.upper);
    probe_fk(in.model, recovery_q_);
    pose_error(probe_, error_);
    recovery_residual_ = error_.cwiseAbs().maxCoeff();
    return std::isfinite(recovery_residual_) ? recovery_residual_ : kInf;
  }

  // Eq 1–6 for every option with the current joint set; returns the number
  // of feasible options. DM is computed for feasible options only with_dm.
  int generate_options(const StepInput& in, bool with_dm) {
    const Eigen::VectorXd& q = in.state.q;
    const int count = sets_.option_count();
    max_iterations_used_ = 0;
    int feasible = 0;
    // eq 3 with eq 6 is linear in δθ_p: J_b⁺(δx − J_p δθ_p) = J_b⁺δx −
    // Σ_i δθ_i J_b⁺ J_p,i, so its 1 + k products are formed once here
    // instead of once per option
    block_inverse_.apply(error0_, base_step_);
    for (int i = 0; i < sets_.perturbed_count(); ++i) {
      rhs_ = in.task_jacobian.col(sets_.perturbed(i));
      block_inverse_.apply(rhs_, block_step_);
      compensation_.col(i) = block_step_;
    }
    for (int s = 0; s < count; ++s) {
      // options in the order where the first perturbed joint changes slowest:
      // consecutive options share the kinematics of the joints before the
      // first one they differ in (probe_fk); the selection does not depend on
      // this order, only on the option's index j
      const int j = sets_.option_of_sequence(s);
      theta_ = q;
      int code = j;
      double d[kMaxPerturbed];
      for (int i = 0; i < sets_.perturbed_count(); ++i) {
        d[i] = (code % 3 - 1) * p(kDelta);  // −Δ, 0, +Δ
        code /= 3;
        theta_[sets_.perturbed(i)] += d[i];
      }
      for (int c = 0; c < sets_.block_count(); ++c) {  // eq 3 with eq 6, J_b at the current configuration
        double step = base_step_[c];
        for (int i = 0; i < sets_.perturbed_count(); ++i) step -= d[i] * compensation_(c, i);  // eq 6: −J_p δθ_p
        theta_[sets_.block(c)] += step;
      }
      int it = 0;
      double residual = kInf, previous = kInf, before_previous = kInf;
      bool chord = false, chord_failed = false;
      while (true) {  // eq 1–5: Newton on the block through the kinematics
        probe_fk(in.model, theta_);
        pose_error(probe_, error_);
        residual = error_.cwiseAbs().maxCoeff();
        if (chord) {
          chord = false;
          if (!(residual < p(kTolerance)) && !(residual <= kChordContraction * previous)) {
            // the chord step fell short of what Newton does there: back to
            // its start, and on with full Newton steps as without it
            theta_ = theta_previous_;
            probe_fk(in.model, theta_);
            error_ = error_previous_;
            residual = previous, previous = before_previous;
            --it;
            chord_failed = true;
          }
        }
        if (!(residual < previous) && it > 0) {
          // diverging: keep the last better iterate (infeasible unless it met eq 5)
          theta_ = theta_previous_;
          probe_fk(in.model, theta_);
          residual = previous;
          break;
        }
        if (residual < p(kTolerance) || it >= static_cast<int>(p(kIterations))) break;
        // a step after one that cut the residual 100-fold reuses the last
        // factors (a chord step): inside Newton's quadratic region J_b has
        // moved by about those small steps, so the chord contracts by as
        // much again (and the kinematics' Jacobian and the LU are saved)
        chord = it >= 1 && !chord_failed && residual <= kChordStart * previous;
        before_previous = previous;
        previous = residual;
        theta_previous_ = theta_;
        if (chord) error_previous_ = error_;
        if (!chord)  // J_b at θ
          task_jacobian_columns(in.model, probe_, space_, sets_.block_joints(), sets_.block_count(), jacobian_);
        // eq 3 with J_b at θ (a full Newton step; the block is often poorly conditioned)
        if (sets_.block_count() == m_) {  // the paper's square J_m×m: eq 3 by LU
          if (!chord) lu_.compute_columns(jacobian_, sets_.block_joints());
          lu_.solve(error_, block_step_);
          for (int c = 0; c < sets_.block_count(); ++c) theta_[sets_.block(c)] += block_step_[c];
        } else {
          if (!chord) {
            for (int c = 0; c < sets_.block_count(); ++c) block_jacobian_.col(c) = jacobian_.col(sets_.block(c));
            option_inverse_.factor_pinv(block_jacobian_);
          }
          apply_block_step(option_inverse_, error_);
        }
        ++it;
      }
      max_iterations_used_ = std::max(max_iterations_used_, it);
      options_.col(j) = theta_;
      residual_[j] = residual;
      feasible_[j] = residual < p(kTolerance) && within_limits(in.model.limits, theta_) &&
                     within_speed(in.model.limits, theta_, q, in.dt);
      feasible += feasible_[j];
      // criteria at θ^j (probe_ and jacobian_ hold its kinematics)
      criteria_(j, kJra) = psi_.joint_range(theta_);
      criteria_(j, kJvm) = kapoor::Criteria::joint_velocity(theta_, q);
      if (feasible_[j] && with_dm) task_jacobian(in.model, probe_, space_, jacobian_);  // J at θ^j, for DM only
      criteria_(j, kDm) = feasible_[j] && with_dm ? psi_.dexterity(jacobian_, p(kDmLength)) : kNaN;
      criteria_(j, kObstacle) = -psi_.estimated_clearance(theta_, q);
    }
    return feasible;
  }

  void on_param_changed(ParamSlot changed) override {
    if (changed == kMask) choose_joints();
    if (changed == kDmFraction || changed == kDmReference) rule_active_ = false;
  }

  // probe_ ← the kinematics at theta (frames and axes; its link segments are
  // never read), recomputed from the first joint where
  // theta differs from the configuration probe_ holds (bit for bit the same
  // as a full forward_kinematics).
  void probe_fk(const Model& model, const Eigen::VectorXd& theta) {
    int first = 0;
    if (probe_valid_)  // the same bits (== would take −0 for +0, whose sines differ in sign)
      while (first < n_ && std::bit_cast<std::uint64_t>(theta[first]) == std::bit_cast<std::uint64_t>(probe_q_[first]))
        ++first;
    if (probe_valid_ && first == n_) return;
    forward_kinematics_from(model, theta, probe_, first, false);  // frames and axes only: no link segments
    probe_q_ = theta;
    probe_valid_ = true;
  }

  // Perturbed joints from the mask (direct_search_joint_sets.hpp), and the
  // buffers sized by its block (a parameter change may allocate; steady-state steps do not).
  void choose_joints() {
    sets_.choose(static_cast<long>(p(kMask)));
    const int block_count = std::max(1, sets_.block_count());
    block_inverse_ = RightInverse(m_, block_count);
    option_inverse_ = RightInverse(m_, block_count);
    block_jacobian_ = Eigen::MatrixXd::Zero(m_, block_count);
    block_step_ = Eigen::VectorXd::Zero(block_count);
    base_step_ = Eigen::VectorXd::Zero(block_count);
    compensation_ = Eigen::MatrixXd::Zero(block_count, kMaxPerturbed);
  }

  template <typename Vector>
  static bool within_limits(const JointLimits& limits, const Vector& q) {
    return (q.array() >= limits.lower.array()).all() && (q.array() <= limits.upper.array()).all();
  }

  // |θ_i − q_i| ≤ q̇_i,max · dt for every joint (no jump to another IK branch).
  template <typename Vector>
  static bool within_speed(const JointLimits& limits, const Vector& theta, const Eigen::VectorXd& q, double dt) {
    return ((theta - q).cwiseAbs().array() <= limits.velocity.array() * dt).all();
  }

  // The pose to reach at t + dt.
  void set_target(const StepInput& in) {
    if (in.task.is_joystick())
      target_position_ = in.ref.position + in.dt * in.task.joystick_linear();
    else
      target_position_ = in.task.target_position(in.state.t + in.dt);
    target_orientation_ = in.ref.orientation;
    if (space_ == TaskSpace::pose) {
      const Eigen::Vector3d w = in.ref.xdot_ff.tail<3>() * in.dt;
      if (w.norm() > 0) target_orientation_ = Eigen::AngleAxisd(w.norm(), w.normalized()) * target_orientation_;
    }
  }

  // Task-space error target − actual in the rows of the task space.
  void pose_error(const KinematicsData& kin, Eigen::VectorXd& e) const {
    const Eigen::Vector3d dp = target_position_ - kin.end_effector().translation();
    switch (space_) {
      case TaskSpace::xy: e = dp.head<2>(); break;
      case TaskSpace::xyz: e = dp; break;
      case TaskSpace::pose:
        e.head<3>() = dp;
        e.tail<3>() = orientation_error_from_skew(target_orientation_, kin.end_effector().linear());
        break;
    }
  }

  // θ_b += J_b⁺ e (eq 3)
  void apply_block_step(RightInverse& inverse, const Eigen::VectorXd& e) {
    inverse.apply(e, block_step_);
    for (int c = 0; c < sets_.block_count(); ++c) theta_[sets_.block(c)] += block_step_[c];
  }

  int n_, m_;
  TaskSpace space_;
  KinematicsData probe_;
  Eigen::MatrixXd jacobian_;
  kapoor::Criteria psi_;   // ψ1–ψ4 (direct_search_criteria.hpp)
  kapoor::JointSets sets_;  // the perturbed joints and the block (direct_search_joint_sets.hpp)
  Eigen::MatrixXd block_jacobian_;
  RightInverse block_inverse_, option_inverse_;
  Eigen::MatrixXd options_, criteria_;
  Eigen::VectorXd residual_;
  Eigen::Matrix<bool, Eigen::Dynamic, 1> feasible_;
  Eigen::VectorXd theta_, error_, error0_, error_previous_, rhs_, block_step_, base_step_;
  Eigen::MatrixXd compensation_;  // column i: J_b⁺ J_p,i at the current configuration
  SmallLu lu_;
  Eigen::VectorXd theta_previous_;
  int max_iterations_used_ = 0;
  Eigen::Vector3d target_position_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d target_orientation_ = Eigen::Matrix3d::Identity();
  bool rule_active_ = false;
  RightInverse recovery_inverse_;
  Eigen::VectorXd recovery_step_, recovery_q_;
  Eigen::VectorXd probe_q_;  // the configuration probe_ holds when probe_valid_
  bool probe_valid_ = false;
  double recovery_residual_ = 0;
  int recovery_diag_ = 0;
  int chosen_diag_[kCriteria], weight_diag_[kCriteria];
  int feasible_diag_, options_diag_, chosen_diag_index_, rule_diag_, current_dm_diag_, iterations_diag_,
      residual_diag_, block_sigma_diag_, switched_diag_;
};

}  // namespace

std::vector<ParamSpec> direct_search_params() {
  return {{"delta", "Perturbation Δ", "rad", "step of the perturbed joints: options −Δ, 0, +Δ (§3.1; the paper 0.002)", 0.02, 0.0,
           0.5, 0.001, {}},
          {"perturb_mask", "Perturbed joints (bit mask)", "",
           "bit i−1 set: joint i is perturbed (at most n − m and 6 joints; 23 = joints 1, 2, 3, 5)", 23, 0,
           (1 << 20) - 1, 1, {}},
          {"w_jra", "Weight: joint range availability", "", "w1 of eq 7 (JRA)", 1.0, 0.0, 1.0, 0.05, {}},
          {"w_jvm", "Weight: joint velocity measure", "", "w2 of eq 7 (JVM)", 1.0, 0.0, 1.0, 0.05, {}},
          {"w_dm", "Weight: dexterity measure", "", "w3 of eq 7 (DM = σmax/σmin; the paper 1)", 0.0, 0.0, 1.0, 0.05, {}},
          {"w_obstacle", "Weight: obstacle clearance", "", "weight of the engine's obstacle distance criterion",
           1.0, 0.0, 1.0, 0.05, {}},
          {"dm_rule_fraction", "DM rule: fraction of the reference", "",
           "when DM reaches dm_rule_fraction x dm_rule_reference, the JRA and JVM weights are scaled by 0.8 and 0.2 "
           "(the paper: 250 of the more than 300 its equal-weight run reached, about 0.83); 0 = off",
           0.0, 0.0, 1.0, 0.01, {}},
          {"dm_rule_reference", "DM rule: reference DM", "",
           "the peak DM of the same task run with equal weights (1, 1, 1), with the same L; 0 = rule off", 0.0, 0.0,
           1e9, 1, {}},
          {"newton_iterations", "Newton iterations", "", "most iterations of eq 1–4 per option", 8, 1, 100, 1, {}},
          {"tolerance", "End-effector tolerance ε", "m, rad", "eq 5: an option is feasible below it", 1e-9,
           1e-14, 1e-2, 1e-9, {}},
          {"dm_length", "DM characteristic length L", "m",
           "position rows of a pose task's Jacobian are divided by L for DM (DM = σmax/σmin mixes m and rad; "
           "its value depends on L)", 1.0, 1e-4, 1e3, 0.01, {}},
          {"block_switch", "Block switch below σ", "",
           "when the block of the non-perturbed joints has σ_min below it, or no option is feasible, perturb "
           "instead the joints whose block has the largest determinant (§3.1) for that step; 0 = never",
           0.02, 0.0, 10.0, 0.01, {}},
          {"recovery_damping", "Recovery damping λ", "",
           "rrlab's, not the paper's: when no option is feasible, a damped least-squares step toward the target "
           "(λ), scaled into the joint speeds, is taken if it ends nearer than the nearest option and than staying "
           "(a hand off the path comes back); 0 = off",
           0.05, 0.0, 10.0, 0.01, {}}};
}
std::unique_ptr<Method> make_direct_search(const MethodContext& ctx) {
  return std::make_unique<DirectSearch>(ctx);
}

}  // namespace rrlab
