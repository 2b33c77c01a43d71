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
// obstacle clearance ψ4 = −min_link d_link, minimised.
//
// Choices where the paper is silent (README, scenarios 22–23):
//  - θ_i,max is the joint's half range (the displacement from mid-range to
//    the limit); joints without both limits do not count in JRA.
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
//  - the perturbed joints are the set bits of `perturb_mask` (bit i−1:
//    joint i), at most n − m of them and at most 6 (729 options); default
//    joints 1, 2, 3, 5 as in the paper's 81-option example.
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
//  - ψ4 uses the first-order change of each link's distance to its nearest
//    obstacle, d + nᵀJ_p(θ − θ_curr), from the step's distance table
//    (exact to O(Δ²); no collision query per option).
//  - DM mixes lengths and angles: its value depends on the length unit of
//    the position rows, which the paper does not give. Here the position
//    rows are divided by a stated characteristic length L (`dm_length`, m),
//    so DM values are comparable only at the same L and robot, never with
//    the paper's numbers.
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
#include <bitset>
#include <cstdint>
#include <cmath>

#include <rrlab/methods/factories.hpp>
#include <rrlab/util/extreme_eigenvalues.hpp>
#include <rrlab/util/right_inverse.hpp>
#include <rrlab/util/small_lu.hpp>

namespace rrlab {
namespace {

enum { kJra, kJvm, kDm, kObstacle, kCriteria };

constexpr int kMaxPerturbed = 6;
constexpr int kMaxOptions = 729;  // 3^6
constexpr int kPower3[kMaxPerturbed] = {1, 3, 9, 27, 81, 243};
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
        jjt_(m_, m_),
        eigenvalues_(m_),
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
        delta_theta_(n_),
        distance_rows_(std::max(1, ctx.model.link_count()), n_),
        distances_now_(std::max(1, ctx.model.link_count())),
        point_jacobian_(3, n_),
        square_block_(m_, m_),
        recovery_inverse_(m_, n_),
        recovery_step_(n_),
        recovery_q_(n_),
        probe_q_(n_) {
    block_.assign(n_, 0);
    theta_previous_ = Eigen::VectorXd::Zero(n_);
    joint_range_weights(ctx.model.limits);
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
    use_joint_set(mask_bits_);
    for (int c = 0; c < block_count_; ++c) block_jacobian_.col(c) = in.task_jacobian.col(block_[c]);
    block_inverse_.factor_pinv(block_jacobian_);
    bool switched = false;
    if (p(kBlockSwitch) > 0 && block_inverse_.sigma_min() < p(kBlockSwitch) && !alternatives_.empty()) {
      // §3.1: "the full rank submatrix with the largest determinant" — only
      // when the chosen block is near singular
      use_joint_set(largest_determinant_set(in.task_jacobian, 0));
      for (int c = 0; c < block_count_; ++c) block_jacobian_.col(c) = in.task_jacobian.col(block_[c]);
      block_inverse_.factor_pinv(block_jacobian_);
      switched = true;
    }
    prepare_distance_rows(in);

    // the DM rule looks at the current configuration
    const double dm_now = dexterity(in.task_jacobian);
    if (p(kDmFraction) > 0 && p(kDmReference) > 0 && dm_now >= p(kDmFraction) * p(kDmReference)) rule_active_ = true;
    out.diag.values[current_dm_diag_] = std::isfinite(dm_now) ? dm_now : -1.0;

    double weights[kCriteria] = {p(kWJra), p(kWJvm), p(kWDm), p(kWObstacle)};
    if (rule_active_) weights[kJra] *= 0.8, weights[kJvm] *= 0.2;
    // DM (an eigen-decomposition per option) only where the selection weighs it
    const bool with_dm = weights[kDm] > 0;

    // 1. generate options (eq 1–6); when no option meets eq 5 within the
    // ranges and speeds, once more with the largest-determinant block (§3.1)
    int feasible = generate_options(in, with_dm);
    if (feasible == 0 && p(kBlockSwitch) > 0 && !alternatives_.empty()) {
      // the block must not hold a joint that its options pushed past a limit:
      // perturbed, such a joint keeps its value or moves by ±Δ
      const unsigned long long best = largest_determinant_set(in.task_jacobian, out_of_range_bits(in.model.limits));
      if (best != current_bits_) {
        use_joint_set(best);
        for (int c = 0; c < block_count_; ++c) block_jacobian_.col(c) = in.task_jacobian.col(block_[c]);
        block_inverse_.factor_pinv(block_jacobian_);
        switched = true;
        feasible = generate_options(in, with_dm);
      }
    }
    out.diag.values[block_sigma_diag_] = block_inverse_.sigma_min();
    out.diag.values[switched_diag_] = switched;
    const int count = option_count();

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
      criteria_(chosen, kDm) = dexterity(jacobian_);
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
    if (!has_distances_ || chosen < 0) out.diag.values[chosen_diag_[kObstacle]] = -1.0;
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
    const int count = option_count();
    max_iterations_used_ = 0;
    int feasible = 0;
    // eq 3 with eq 6 is linear in δθ_p: J_b⁺(δx − J_p δθ_p) = J_b⁺δx −
    // Σ_i δθ_i J_b⁺ J_p,i, so its 1 + k products are formed once here
    // instead of once per option
    block_inverse_.apply(error0_, base_step_);
    for (int i = 0; i < perturbed_count_; ++i) {
      rhs_ = in.task_jacobian.col(perturbed_[i]);
      block_inverse_.apply(rhs_, block_step_);
      compensation_.col(i) = block_step_;
    }
    for (int s = 0; s < count; ++s) {
      // options in the order where the first perturbed joint changes slowest:
      // consecutive options share the kinematics of the joints before the
      // first one they differ in (probe_fk); the selection does not depend on
      // this order, only on the option's index j
      const int j = option_of_sequence(s);
      theta_ = q;
      int code = j;
      double d[kMaxPerturbed];
      for (int i = 0; i < perturbed_count_; ++i) {
        d[i] = (code % 3 - 1) * p(kDelta);  // −Δ, 0, +Δ
        code /= 3;
        theta_[perturbed_[i]] += d[i];
      }
      for (int c = 0; c < block_count_; ++c) {  // eq 3 with eq 6, J_b at the current configuration
        double step = base_step_[c];
        for (int i = 0; i < perturbed_count_; ++i) step -= d[i] * compensation_(c, i);  // eq 6: −J_p δθ_p
        theta_[block_[c]] += step;
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
        if (!chord) task_jacobian_columns(in.model, probe_, space_, block_.data(), block_count_, jacobian_);  // J_b at θ
        // eq 3 with J_b at θ (a full Newton step; the block is often poorly conditioned)
        if (block_count_ == m_) {  // the paper's square J_m×m: eq 3 by LU
          if (!chord) lu_.compute_columns(jacobian_, block_.data());
          lu_.solve(error_, block_step_);
          for (int c = 0; c < block_count_; ++c) theta_[block_[c]] += block_step_[c];
        } else {
          if (!chord) {
            for (int c = 0; c < block_count_; ++c) block_jacobian_.col(c) = jacobian_.col(block_[c]);
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
      criteria_(j, kJra) = (theta_ - centre_).cwiseAbs2().dot(inv_half_range_);
      criteria_(j, kJvm) = (theta_ - q).squaredNorm();
      if (feasible_[j] && with_dm) task_jacobian(in.model, probe_, space_, jacobian_);  // J at θ^j, for DM only
      criteria_(j, kDm) = feasible_[j] && with_dm ? dexterity(jacobian_) : kNaN;
      criteria_(j, kObstacle) = -estimated_clearance(q);
    }
    return feasible;
  }

  void on_param_changed(ParamSlot changed) override {
    if (changed == kMask) choose_joints();
    if (changed == kDmFraction || changed == kDmReference) rule_active_ = false;
  }

  // DM = σmax/σmin with the position rows of pose tasks divided by the characteristic length L.
  double dexterity(const Eigen::MatrixXd& jacobian) {
    switch (m_) {  // a fixed size unrolls J Jᵀ's loops (the same sums in the same order)
      case 2: gram<2>(jacobian); break;
      case 3: gram<3>(jacobian); break;
      default: gram<6>(jacobian); break;
    }
    eigenvalues_.compute(jjt_);  // the two ends of the spectrum only
    const double lo = eigenvalues_.min(), hi = eigenvalues_.max();
    return lo > 0 ? std::sqrt(hi / lo) : kInf;
  }

  // jjt_ ← J̃ J̃ᵀ (M = m_ rows; J̃: the position rows of a pose task divided by
  // L), a column at a time (contiguous, no scaled copy); L's scaling is
  // applied to the sums (1/L² on position × position, 1/L on mixed entries),
  // which keeps divisions out of the loop.
  template <int M>
  void gram(const Eigen::MatrixXd& jacobian) {
    double jjt[M][M] = {};
    for (int k = 0; k < n_; ++k) {
      const double* col = jacobian.col(k).data();
      for (int r = 0; r < M; ++r)
        for (int c = 0; c <= r; ++c) jjt[r][c] += col[r] * col[c];
    }
    if (M == 6) {  // pose: the position rows in units of L
      const double inverse = 1.0 / p(kDmLength), inverse2 = inverse * inverse;
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c <= r && c < 3; ++c) jjt[r][c] *= r < 3 ? inverse2 : inverse;
    }
    for (int r = 0; r < M; ++r)
      for (int c = 0; c <= r; ++c) jjt_(r, c) = jjt_(c, r) = jjt[r][c];
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

  // The option index j of the s-th generated option: s's base-3 digits in
  // reverse (the first perturbed joint is j's lowest digit, s's highest).
  int option_of_sequence(int s) const {
    int j = 0;
    for (int i = perturbed_count_ - 1; i >= 0; --i) j += (s % 3) * kPower3[i], s /= 3;
    return j;
  }

  int option_count() const {
    int count = 1;
    for (int i = 0; i < perturbed_count_; ++i) count *= 3;
    return count;
  }

  // Perturbed joints: the mask's set bits (joint index < n), at most n − m and 6.
  void choose_joints() {
    const long mask = static_cast<long>(p(kMask));
    const int allowed = std::min(kMaxPerturbed, std::max(0, n_ - m_));
    mask_bits_ = 0;
    int count = 0;
    for (int i = 0; i < n_ && i < 64; ++i)
      if (((mask >> i) & 1) && count < allowed) mask_bits_ |= 1ULL << i, ++count;
    use_joint_set(mask_bits_);
    // a parameter change may allocate; steady-state steps do not
    block_inverse_ = RightInverse(m_, std::max(1, block_count_));
    option_inverse_ = RightInverse(m_, std::max(1, block_count_));
    block_jacobian_ = Eigen::MatrixXd::Zero(m_, std::max(1, block_count_));
    block_step_ = Eigen::VectorXd::Zero(std::max(1, block_count_));
    base_step_ = Eigen::VectorXd::Zero(std::max(1, block_count_));
    compensation_ = Eigen::MatrixXd::Zero(std::max(1, block_count_), kMaxPerturbed);
    alternative_block_ = Eigen::MatrixXd::Zero(m_, std::max(1, block_count_));
    // every other set of as many perturbed joints, for the block switch
    alternatives_.clear();
    if (block_count_ >= m_ && n_ <= 20) {
      for (unsigned long long bits = 0; bits < (1ULL << n_); ++bits)
        if (static_cast<int>(std::bitset<64>(bits).count()) == count) alternatives_.push_back(bits);
    }
  }

  void use_joint_set(unsigned long long bits) {
    current_bits_ = bits;
    perturbed_count_ = 0;
    block_count_ = 0;
    for (int i = 0; i < n_; ++i) {
      if (i < 64 && ((bits >> i) & 1))
        perturbed_[perturbed_count_++] = i;
      else
        block_[block_count_++] = i;
    }
  }

  // The perturbed set whose block has the largest |det J_b| (square block,
  // §3.1) or, for a wide block, the largest det(J_b J_bᵀ) = Π σ² (the same
  // order for a square one).
  // Sets whose perturbed joints include `required` come first (any set when none does).
  unsigned long long largest_determinant_set(const Eigen::MatrixXd& jacobian, unsigned long long required) {
    double best = -1;
    bool best_has_required = false;
    unsigned long long best_bits = mask_bits_;
    for (unsigned long long bits : alternatives_) {
      const bool has_required = (bits & required) == required;
      if (best_has_required && !has_required) continue;
      int columns[64], c = 0;
      for (int i = 0; i < n_; ++i)
        if (!((bits >> i) & 1)) columns[c++] = i;
      if (block_count_ == m_) {
        lu_.compute_columns(jacobian, columns);  // |det J_b|, in place
      } else {
        for (int k = 0; k < c; ++k) alternative_block_.col(k) = jacobian.col(columns[k]);
        square_block_.noalias() = alternative_block_ * alternative_block_.transpose();
        lu_.compute(square_block_);  // det(J_b J_bᵀ)
      }
      double det = std::abs(lu_.determinant());
      if (!std::isfinite(det)) det = 0;  // a block of non-finite entries is no candidate
      if (det > best || (has_required && !best_has_required)) best = det, best_bits = bits, best_has_required = has_required;
    }
    return best_bits;
  }

  // Joints outside their range in some generated option.
  unsigned long long out_of_range_bits(const JointLimits& limits) const {
    unsigned long long bits = 0;
    const int count = option_count();
    for (int j = 0; j < count; ++j)
      for (int i = 0; i < n_ && i < 64; ++i)
        if (options_(i, j) < limits.lower[i] || options_(i, j) > limits.upper[i]) bits |= 1ULL << i;
    return bits;
  }

  void joint_range_weights(const JointLimits& limits) {
    centre_ = Eigen::VectorXd::Zero(n_);
    inv_half_range_ = Eigen::VectorXd::Zero(n_);
    for (int i = 0; i < n_; ++i) {
      if (!std::isfinite(limits.lower[i]) || !std::isfinite(limits.upper[i])) continue;
      centre_[i] = 0.5 * (limits.lower[i] + limits.upper[i]);
      const double half = 0.5 * (limits.upper[i] - limits.lower[i]);
      if (half > 0) inv_half_range_[i] = 1.0 / half;
    }
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
    for (int c = 0; c < block_count_; ++c) theta_[block_[c]] += block_step_[c];
  }

  // Rows nᵀJ_p of each link's nearest obstacle pair, for the clearance criterion.
  void prepare_distance_rows(const StepInput& in) {
    has_distances_ = false;
    links_with_distance_ = 0;
    const DistanceTable& table = in.distances;
    for (int link = 0; link < table.links && link < distance_rows_.rows(); ++link) {
      const int o = table.nearest_obstacle(link);
      if (o < 0) continue;
      const LinkObstacleDistance& pair = table.at(link, o);
      point_jacobian_linear(in.model, in.kin, link, pair.on_link, point_jacobian_);
      distance_rows_.row(links_with_distance_).noalias() = pair.normal.transpose() * point_jacobian_;
      distances_now_[links_with_distance_] = pair.distance;
      ++links_with_distance_;
      has_distances_ = true;
    }
  }

  double estimated_clearance(const Eigen::VectorXd& q) {
    double clearance = 0;  // no obstacles: the criterion is constant
    if (!has_distances_) return clearance;
    clearance = kInf;
    delta_theta_.noalias() = theta_ - q;
    for (int l = 0; l < links_with_distance_; ++l)
      clearance = std::min(clearance, distances_now_[l] + distance_rows_.row(l).dot(delta_theta_));
    return clearance;
  }

  int n_, m_;
  TaskSpace space_;
  KinematicsData probe_;
  Eigen::MatrixXd jacobian_;
  ExtremeEigenvalues::Matrix jjt_;  // at most 6 x 6 (pose), fixed capacity
  ExtremeEigenvalues eigenvalues_;
  Eigen::MatrixXd block_jacobian_;
  RightInverse block_inverse_, option_inverse_;
  Eigen::MatrixXd options_, criteria_;
  Eigen::VectorXd residual_;
  Eigen::Matrix<bool, Eigen::Dynamic, 1> feasible_;
  Eigen::VectorXd theta_, error_, error0_, error_previous_, rhs_, delta_theta_, block_step_, base_step_;
  Eigen::MatrixXd compensation_;  // column i: J_b⁺ J_p,i at the current configuration
  Eigen::MatrixXd distance_rows_;
  Eigen::VectorXd distances_now_;
  Eigen::MatrixXd point_jacobian_, square_block_;
  SmallLu lu_;
  unsigned long long mask_bits_ = 0, current_bits_ = 0;
  Eigen::MatrixXd alternative_block_;
  Eigen::VectorXd theta_previous_;
  int max_iterations_used_ = 0;
  std::vector<unsigned long long> alternatives_;
  Eigen::VectorXd centre_, inv_half_range_;
  Eigen::Vector3d target_position_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d target_orientation_ = Eigen::Matrix3d::Identity();
  int perturbed_[kMaxPerturbed] = {}, perturbed_count_ = 0;
  std::vector<int> block_;  // the non-perturbed joints (n entries reserved)
  int block_count_ = 0;
  bool rule_active_ = false, has_distances_ = false;
  int links_with_distance_ = 0;
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
