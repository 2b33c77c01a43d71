// Sezgin, Seneviratne & Earles (1997): obstacle avoidance with configuration
// control points (CCPs) on the arm.
//  - DI (eq. 10): maximise Σ_i ‖f_i(θ) − x_i‖, x_i the obstacle vertex nearest
//    to CCP i (collision/voronoi_points.hpp says what a "vertex" is per shape);
//  - DM (eq. 11): minimise Σ_i ‖f_i(θ) − V_i‖, V_i the Voronoi-boundary
//    control point nearest to CCP i (recomputed each step from the scene, so
//    it follows moving obstacles);
//  - hybrid (§3.2, Ex3): DI until the end-effector comes within
//    `switch_distance` of a Voronoi-boundary point, then DM while the
//    end-effector or a CCP stays that near, then DI again (the paper switches
//    "based on a preset threshold distance ... and vice versa" without saying
//    which distance).
// The nearest vertex x_i of eq. 10 is chosen once per step (the paper's
// sampling period) at the step's configuration and held over the step's RK4
// stages or Newton iterations; with `hysteresis` h > 0 a CCP keeps its vertex
// until another one is nearer by more than h (the paper does not say when the
// CCP changes vertex; its Figs. 3-4 depend on it). DM's Voronoi points are
// re-chosen at every evaluation, without hysteresis.
// Up to five CCPs (Fig. 5 uses three and four; Table 2 times up to five).
// Integrators (§2, §4.1):
//  - rk4: Liégeois' gradient projection, eq. 4, θ̇ = J⁺ẋ + λ(I − J⁺J)∇H (λ > 0
//    for DI, λ < 0 for DM), integrated with classic fourth-order Runge–Kutta
//    over one step; ẋ at each stage is the task's closed-loop command at the
//    stage's time and configuration, and the obstacles are moved to the
//    stage's time. The paper's λ acts once per sampling period, and its
//    sampling periods are equal steps along the path (0.02 units), so λ is a
//    gain per unit of path length: here λ = gain · ‖ẋ_path‖, `gain` in 1/unit
//    and ẋ_path the path's feed-forward velocity, so that dθ/ds = J⁺ dx/ds +
//    gain (I − J⁺J)∇H does not depend on how fast the path is traversed (a
//    target at rest gives no null-space motion; joystick: the commanded speed);
//  - lagrangian: Chang's position method, eq. 6–7: at each step solve
//    f(θ) = X_d(t + dt) together with Z∇H(θ) = 0, Z = [(J_a⁻¹J_b)ᵀ  −I]
//    (J_a m independent columns of J, J_b the rest), by Newton's method with a
//    forward-difference Jacobian, warm-started at the previous θ. First step
//    (`lagrangian_start`): climb (DI uphill along the self-motion from θ0 to
//    a maximum, then Newton; the paper uses the Lagrangian method for the
//    initial condition of every run) or theta0 (Newton from θ0 straight
//    away: the stationary point nearest to θ0, of any kind).
// The CCP Jacobians are point Jacobians of the kinematics module (the paper's
// eq. 12–13 specialised to its 3-link arm).
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <string>
#include <cmath>
#include <limits>

#include <rrlab/collision/voronoi_points.hpp>
#include <rrlab/methods/factories.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {
namespace {

constexpr int kMaxCcp = 5;
constexpr double kTiny = 1e-12;
// Defaults fitted to Sezgin et al.'s Table 1 (Ex1, L-shape, the three
// one-CCP cases): the (gain, hysteresis) pair that minimises the mean over 35
// knots of the largest joint difference, the run interpolated at each knot's
// position along the path (4.06 deg; within 0.3 deg of it over gain 10..11,
// hysteresis 0.1..0.3). The paper's sampling distance is 0.02 units, so its
// λ per sampling period is 0.02 · 10.75 = 0.215.
constexpr double kCcpDefaultGain = 10.75;
constexpr double kCcpDefaultHysteresis = 0.1;

class CcpVoronoi final : public Method {
  // Parameters and labels by name (Method::slot). CCP 1's link and position
  // are ccp_link and ccp_at, CCP n's ccpn_link and ccpn_at.
  const ParamSlot kMode = slot("mode"), kIntegrator = slot("integrator"), kGain = slot("gain"),
                  kHysteresis = slot("hysteresis"), kSwitch = slot("switch_distance"),
                  kMidpoints = slot("edge_midpoints"), kNewtonIters = slot("newton_iterations"),
                  kLagrangeStart = slot("lagrangian_start");
  const int kDM = label(kMode, "DM"), kHybrid = label(kMode, "hybrid"), kRk4 = label(kIntegrator, "rk4"),
            kClimb = label(kLagrangeStart, "climb");
  const std::array<ParamSlot, kMaxCcp> kCcpLink = ccp_slots("link"), kCcpAt = ccp_slots("at");

  std::array<ParamSlot, kMaxCcp> ccp_slots(const std::string& what) const {
    std::array<ParamSlot, kMaxCcp> slots;
    for (int i = 0; i < kMaxCcp; ++i) slots[i] = slot(i == 0 ? "ccp_" + what : "ccp" + std::to_string(i + 1) + "_" + what);
    return slots;
  }

 public:
  explicit CcpVoronoi(const MethodContext& ctx)
      : Method(ccp_voronoi_params()),
        n_(ctx.model.dof()),
        m_(task_rows(ctx.space)),
        links_(ctx.model.link_count()),
        space_(ctx.space),
        probe_(ctx.model),
        jac_(m_, n_),
        point_jac_(3, n_),
        inverse_(m_, n_),
        ref_(ctx.space),
        grad_(n_),
        null_(n_),
        k1_(n_), k2_(n_), k3_(n_), k4_(n_), q_stage_(n_),
        theta_(n_), theta_probe_(n_), residual_(n_), residual_probe_(n_), delta_(n_),
        newton_jac_(n_, n_),
        newton_lu_(n_),
        head_lu_(m_),
        w_(m_, std::max(0, n_ - m_)),
        ja_(m_, m_),
        jb_(m_, std::max(0, n_ - m_)),
        ga_(m_),
        gb_(std::max(0, n_ - m_)),
        colpiv_(m_, n_),
        split_(n_) {
    // sized for the worst case up front (scenario limits: 1024 vertices per
    // polygon; ties of the smallest gap are rare), so steps do not allocate
    vertices_.reserve(2 * 1024 + 8);
    scratch_b_.reserve(2 * 1024 + 8);
    voronoi_.reserve(size_t(64 + 4 * ctx.obstacle_count * ctx.obstacle_count));
    criterion_ = declare_diagnostic("criterion");
    dm_active_ = declare_diagnostic("dm_active");
    target_distance_[0] = declare_diagnostic("ccp1_target_distance");
    target_distance_[1] = declare_diagnostic("ccp2_target_distance");
    voronoi_count_ = declare_diagnostic("voronoi_points");
    switch_measure_ = declare_diagnostic("switch_measure");
    newton_iterations_ = declare_diagnostic("newton_iterations");
    newton_residual_ = declare_diagnostic("newton_residual");
    for (int i = 2; i < kMaxCcp; ++i) target_distance_[i] = declare_diagnostic("ccp" + std::to_string(i + 1) + "_target_distance");
    vertex_switches_ = declare_diagnostic("vertex_switches");
    for (int i = 0; i < kMaxCcp; ++i) valid_link_[i] = p(kCcpLink[i]);
  }

  void step(const StepInput& in, StepOutput& out) override {
    out.diag.clear();
    collect_ccps();
    if (in.state.step == 0) {
      for (Held& h : held_) h = Held{};
      switches_ = 0;
    }
    const bool dm = use_dm(in);
    if (!dm) choose_vertices(in);
    out.diag.values[vertex_switches_] = double(switches_);
    out.diag.values[dm_active_] = dm ? 1.0 : 0.0;
    if (choice(kIntegrator) == kRk4)
      step_rk4(in, out, dm);
    else
      step_lagrangian(in, out, dm);
    // report at the current state (criterion value, targets, overlays)
    report_ = &out;
    out.diag.values[criterion_] = criterion_gradient(in.model, in.kin, in.scene, 0.0, dm, grad_);
    report_ = nullptr;
  }

 protected:
  // A CCP on a link the arm does not have is refused (the previous value stays).
  void on_param_changed(ParamSlot changed) override {
    for (int i = 0; i < kMaxCcp; ++i) {
      if (changed != kCcpLink[i]) continue;
      const std::string name = specs()[size_t(changed.index)].name;
      if (p(changed) > links_) {
        set_param(name, valid_link_[i]);
        throw ParamError(name, name + ": the arm has " + std::to_string(links_) + " links");
      }
      valid_link_[i] = p(changed);
    }
  }

 private:
  struct Ccp {
    int link;   // 0-based
    double at;  // 0 proximal joint .. 1 distal end
  };

  // A CCP whose vertex is being followed (obstacle, candidate; -1: none yet).
  struct Held {
    int obstacle = -1, candidate = -1;
  };

  void collect_ccps() {
    ccp_count_ = 0;
    // defaults beyond a short arm's last link fall on its last link
    for (int i = 0; i < kMaxCcp; ++i) {
      const double link = p(kCcpLink[i]);
      if (link < 1) continue;
      ccps_[ccp_count_++] = {std::min(int(link), links_) - 1, p(kCcpAt[i])};
    }
  }

  // Eq. 10's x_i for every CCP at the step's configuration: the nearest
  // obstacle vertex, except that a CCP keeps its previous vertex while no
  // other is nearer by more than `hysteresis` (rrlab's choice; 0 = always the
  // nearest). Held over the step (RK4 stages, Newton iterations).
  void choose_vertices(const StepInput& in) {
    const bool midpoints = p(kMidpoints) > 0.5;
    for (int i = 0; i < ccp_count_; ++i) {
      const Eigen::Vector3d f = ccp_point(in.kin, ccps_[i]);
      const NearestObstaclePoint nearest = nearest_obstacle_point(in.scene, f, 0.0, midpoints, vertices_);
      Held& h = held_[i];
      if (!nearest.found) {
        h = Held{};
        continue;
      }
      const NearestObstaclePoint kept =
          obstacle_candidate(in.scene, h.obstacle, h.candidate, f, 0.0, midpoints, vertices_);
      const bool same = kept.found && kept.obstacle == nearest.obstacle && kept.candidate == nearest.candidate;
      if (kept.found && (same || nearest.distance >= kept.distance - p(kHysteresis))) continue;
      if (h.obstacle >= 0) ++switches_;
      h = {nearest.obstacle, nearest.candidate};
    }
  }

  Eigen::Vector3d ccp_point(const KinematicsData& kin, const Ccp& c) const {
    return kin.link_start.col(c.link) + c.at * (kin.link_end.col(c.link) - kin.link_start.col(c.link));
  }

  // Hybrid switching (Ex3: "DI is used to make the links align with the gap
  // and, when the end effector has reached the gap, DM is used"): DM engages
  // when the end-effector comes within switch_distance of a Voronoi-boundary
  // point, and holds while the end-effector or a CCP stays that near.
  bool use_dm(const StepInput& in) {
    const int mode = choice(kMode);
    if (mode != kHybrid) return mode == kDM;
    voronoi_control_points(in.scene, 0.0, vertices_, scratch_b_, voronoi_);
    auto nearest = [&](const Eigen::Vector3d& x) {
      double best = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& v : voronoi_) best = std::min(best, (x - v).norm());
      return best;
    };
    const double ee = nearest(in.kin.end_effector().translation());
    double held = ee;
    for (int i = 0; i < ccp_count_; ++i) held = std::min(held, nearest(ccp_point(in.kin, ccps_[i])));
    last_switch_measure_ = ee;
    hybrid_dm_ = ee < p(kSwitch) || (hybrid_dm_ && held < p(kSwitch));
    return hybrid_dm_;
  }

  // H (DI: eq. 10, DM: eq. 11) and its gradient ∇H = Σ J_iᵀ (f_i − x_i)/‖f_i − x_i‖,
  // the targets x_i held fixed (obstacles at t + tau).
  double criterion_gradient(const Model& model, const KinematicsData& kin, const Scene& scene, double tau,
                            bool dm, Eigen::VectorXd& grad) {
    grad.setZero();
    double h = 0;
    if (dm) voronoi_control_points(scene, tau, vertices_, scratch_b_, voronoi_);
    if (report_) {
      report_->overlays.points.clear();
      report_->overlays.segments.clear();
      if (report_->overlays.points.capacity() < voronoi_.capacity() + kMaxCcp) {
        report_->overlays.points.reserve(voronoi_.capacity() + kMaxCcp);
        report_->overlays.segments.reserve(kMaxCcp);
      }
    }
    for (int i = 0; i < ccp_count_; ++i) {
      const Eigen::Vector3d f = ccp_point(kin, ccps_[i]);
      Eigen::Vector3d target;
      bool found = false;
      if (dm) {
        double best = std::numeric_limits<double>::infinity();
        for (const Eigen::Vector3d& v : voronoi_)
          if ((v - f).norm() < best) best = (v - f).norm(), target = v, found = true;
      } else {
        const NearestObstaclePoint np = obstacle_candidate(scene, held_[i].obstacle, held_[i].candidate, f, tau,
                                                           p(kMidpoints) > 0.5, vertices_);
        found = np.found;
        target = np.point;
      }
      if (!found) continue;
      const Eigen::Vector3d d = f - target;
      const double len = d.norm();
      h += len;
      if (report_) {
        report_->diag.values[target_distance_[i]] = len;
        report_->overlays.points.push_back(f);
        report_->overlays.segments.emplace_back(f, target);
      }
      if (len < kTiny) continue;
      point_jacobian_linear(model, kin, ccps_[i].link, f, point_jac_);
      grad.noalias() += point_jac_.transpose() * (d / len);
    }
    if (report_) {
      report_->diag.values[voronoi_count_] = double(voronoi_.size());
      report_->diag.values[switch_measure_] = last_switch_measure_;
      if (dm || choice(kMode) == kHybrid)
        for (const Eigen::Vector3d& v : voronoi_) report_->overlays.points.push_back(v);
    }
    return h;
  }

  // Eq. 4: θ̇ = J⁺ẋ + λ(I − J⁺J)∇H at time t_step + tau and configuration q.
  void velocity(const StepInput& in, double tau, const Eigen::VectorXd& q, bool dm, Eigen::VectorXd& qdot) {
    forward_kinematics(in.model, q, probe_);
    task_jacobian(in.model, probe_, space_, jac_);
    in.task.reference(in.state.t + tau, probe_.end_effector(), ref_);
    const int rows = std::min(3, m_);
    double speed = 0;  // ‖ẋ_path‖ at the stage's instant
    if (!in.task.is_joystick()) {
      // RK4 wants the path velocity at the stage's instant, not the mean over
      // the coming step that the reference carries for Euler integrators
      const double t = in.state.t + tau, h = 1e-3 * in.dt;
      const Eigen::Vector3d v = (in.task.target_position(t + h) - in.task.target_position(std::max(0.0, t - h))) /
                                (t + h - std::max(0.0, t - h));
      ref_.xdot.head(rows) = v.head(rows) + in.task.gain() * ref_.error.head(rows);
      speed = v.head(rows).norm();
    } else {
      speed = in.task.joystick_linear().head(rows).norm();
    }
    inverse_.factor_pinv(jac_);  // eq. 3
    inverse_.apply(ref_.xdot, qdot);
    criterion_gradient(in.model, probe_, in.scene, tau, dm, grad_);
    // λ per unit of path length times the path speed (see the top of the file)
    const double lambda = (dm ? -p(kGain) : p(kGain)) * speed;  // maximise DI, minimise DM
    grad_ *= lambda;
    inverse_.null_project(grad_, null_);
    qdot += null_;
  }

  void step_rk4(const StepInput& in, StepOutput& out, bool dm) {
    const double h = in.dt;
    const Eigen::VectorXd& q = in.state.q;
    velocity(in, 0.0, q, dm, k1_);
    q_stage_ = q + 0.5 * h * k1_;
    velocity(in, 0.5 * h, q_stage_, dm, k2_);
    q_stage_ = q + 0.5 * h * k2_;
    velocity(in, 0.5 * h, q_stage_, dm, k3_);
    q_stage_ = q + h * k3_;
    velocity(in, h, q_stage_, dm, k4_);
    out.qdot = (k1_ + 2.0 * k2_ + 2.0 * k3_ + k4_) / 6.0;
    out.q_next = q + h * out.qdot;
    out.integrated = true;
  }

  // Eq. 6–7 residual at θ for the reference at t + dt: [X_d − f(θ); Z∇H].
  bool lagrange_residual(const StepInput& in, const Eigen::VectorXd& theta, bool dm, Eigen::VectorXd& r) {
    forward_kinematics(in.model, theta, probe_);
    task_jacobian(in.model, probe_, space_, jac_);
    in.task.reference(in.state.t + in.dt, probe_.end_effector(), ref_);
    r.head(m_) = ref_.error;
    if (n_ <= m_) return true;
    criterion_gradient(in.model, probe_, in.scene, in.dt, dm, grad_);
    // J = [J_a J_b] over the step's column split (see choose_split)
    for (int c = 0; c < n_; ++c) {
      const int j = split_[c];
      if (c < m_) ja_.col(c) = jac_.col(j), ga_[c] = grad_[j];
      else jb_.col(c - m_) = jac_.col(j), gb_[c - m_] = grad_[j];
    }
    head_lu_.compute(ja_);
    if (std::abs(head_lu_.determinant()) < 1e-12) return false;
    w_ = head_lu_.solve(jb_);  // J_a⁻¹ J_b
    r.tail(n_ - m_).noalias() = w_.transpose() * ga_;
    r.tail(n_ - m_) -= gb_;  // Z∇H, eq. 7
    return true;
  }

  // Eq. 7 splits J into an invertible m x m block J_a and the rest; the paper's
  // arm uses the first m columns. Here the split is chosen once per step by
  // column-pivoted QR of J at the current configuration (the m best-conditioned
  // columns), so that an arm posture where the first m columns are dependent
  // does not stop the method; Z∇H = 0 is the same condition for any invertible split.
  void choose_split(const StepInput& in) {
    colpiv_.compute(in.task_jacobian);
    for (int c = 0; c < n_; ++c) split_[c] = colpiv_.colsPermutation().indices()[c];
  }

  // Start of the Lagrangian run: Newton finds the nearest stationary point of
  // H on the self-motion manifold, which may be a minimum of DI (or a maximum
  // of DM); so the first step first climbs (DI) or descends (DM) along the
  // self-motion, θ += J⁺e + α(I − J⁺J)(±∇H) with a step of at most 0.05 rad,
  // until the projected gradient vanishes; Newton then follows that branch.
  // Newton steps are damped (at most 0.2 rad, backtracking on ‖F‖); a step
  // where Newton does not converge takes at most 20 such climbing iterations
  // instead (reported as newton_iterations = −1).
  void settle_on_optimum(const StepInput& in, bool dm, int max_iterations) {
    for (int it = 0; it < max_iterations; ++it) {
      forward_kinematics(in.model, theta_, probe_);
      task_jacobian(in.model, probe_, space_, jac_);
      in.task.reference(in.state.t + in.dt, probe_.end_effector(), ref_);
      inverse_.factor_pinv(jac_);
      criterion_gradient(in.model, probe_, in.scene, in.dt, dm, grad_);
      if (dm) grad_ = -grad_;
      inverse_.null_project(grad_, null_);
      const double size = null_.cwiseAbs().maxCoeff();
      inverse_.apply(ref_.error, delta_);
      if (size < 1e-6) {
        theta_ += delta_;
        if (delta_.cwiseAbs().maxCoeff() < 1e-9) break;
        continue;
      }
      theta_ += delta_ + (std::min(0.05, size) / size) * null_;
    }
  }

  void step_lagrangian(const StepInput& in, StepOutput& out, bool dm) {
    theta_ = in.state.q;
    choose_split(in);
    if (in.state.step == 0 && choice(kLagrangeStart) == kClimb) settle_on_optimum(in, dm, 2000);
    int iterations = 0;
    double norm = std::numeric_limits<double>::infinity();
    const int max_iterations = int(p(kNewtonIters));
    const double fd = 1e-7;
    bool ok = lagrange_residual(in, theta_, dm, residual_);
    if (ok) norm = residual_.norm();
    for (; ok && iterations < max_iterations && norm >= 1e-10; ++iterations) {
      for (int j = 0; j < n_; ++j) {
        theta_probe_ = theta_;
        theta_probe_[j] += fd;
        lagrange_residual(in, theta_probe_, dm, residual_probe_);
        newton_jac_.col(j) = (residual_probe_ - residual_) / fd;
      }
      newton_lu_.compute(newton_jac_);
      delta_ = newton_lu_.solve(residual_);
      const double largest = delta_.cwiseAbs().maxCoeff();
      if (!std::isfinite(largest)) break;
      if (largest > 0.2) delta_ *= 0.2 / largest;  // at most 0.2 rad per iteration
      // backtracking: accept the largest of 1, 1/2, 1/4, ... that lowers ‖F‖
      bool improved = false;
      for (double alpha = 1.0; alpha > 1e-3 && !improved; alpha *= 0.5) {
        theta_probe_ = theta_ - alpha * delta_;
        if (lagrange_residual(in, theta_probe_, dm, residual_probe_) && residual_probe_.norm() < norm) {
          theta_ = theta_probe_;
          residual_ = residual_probe_;
          norm = residual_.norm();
          improved = true;
        }
      }
      if (!improved) break;
    }
    // No stationary point nearby (the branch ended, or the nearest vertex
    // switched): fall back to a bounded climb along the self-motion from the
    // current configuration, which also keeps the end-effector on the path.
    const bool converged = norm < 1e-8;
    if (!converged) {
      theta_ = in.state.q;
      settle_on_optimum(in, dm, 20);
    }
    out.diag.values[newton_iterations_] = converged ? iterations : -1;
    out.diag.values[newton_residual_] = norm;
    out.q_next = theta_;
    out.qdot = (theta_ - in.state.q) / in.dt;
    out.integrated = true;
  }

  int n_, m_, links_;
  TaskSpace space_;
  KinematicsData probe_;
  Eigen::MatrixXd jac_, point_jac_;
  RightInverse inverse_;
  TaskRef ref_;
  Eigen::VectorXd grad_, null_, k1_, k2_, k3_, k4_, q_stage_;
  Eigen::VectorXd theta_, theta_probe_, residual_, residual_probe_, delta_;
  Eigen::MatrixXd newton_jac_;
  Eigen::PartialPivLU<Eigen::MatrixXd> newton_lu_, head_lu_;
  Eigen::MatrixXd w_, ja_, jb_;
  Eigen::VectorXd ga_, gb_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> colpiv_;
  Eigen::VectorXi split_;
  std::vector<ControlPoint> vertices_, scratch_b_;
  std::vector<Eigen::Vector3d> voronoi_;
  Ccp ccps_[kMaxCcp];
  Held held_[kMaxCcp];
  long switches_ = 0;
  int ccp_count_ = 0;
  StepOutput* report_ = nullptr;
  double last_switch_measure_ = 0;
  bool hybrid_dm_ = false;
  double valid_link_[kMaxCcp] = {};
  int criterion_, dm_active_, target_distance_[kMaxCcp], voronoi_count_, switch_measure_, newton_iterations_,
      newton_residual_, vertex_switches_;
};

}  // namespace

std::vector<ParamSpec> ccp_voronoi_params() {
  std::vector<ParamSpec> specs = {
      {"mode", "Criterion", "",
       "DI: maximise CCP distances to the nearest obstacle vertices (eq. 10); DM: minimise CCP distances to "
       "Voronoi-boundary control points (eq. 11); hybrid: DM near the Voronoi boundary, DI elsewhere",
       0, 0, 2, 1, {"DI", "DM", "hybrid"}},
      {"integrator", "Integrator", "",
       "rk4: gradient projection (eq. 4) integrated by RK4; lagrangian: position method (eq. 6-7) by Newton",
       0, 0, 1, 1, {"rk4", "lagrangian"}},
      {"gain", "Gradient gain |λ| per path length", "1/m",
       "λ of eq. 4 per unit of end-effector path length (rk4 only): λ = gain · path speed, so the same path "
       "gives the same motion at any speed. Default: fitted to Sezgin et al.'s Table 1",
       kCcpDefaultGain, 0.0, 1000.0, 0.1, {}},
      {"hysteresis", "Vertex hysteresis", "m",
       "DI: a CCP keeps its nearest obstacle vertex until another is nearer by more than this (0: always the "
       "nearest)",
       kCcpDefaultHysteresis, 0.0, 10.0, 0.01, {}},
      {"ccp_link", "CCP link", "", "1-based link carrying the first CCP", 3, 1, 64, 1, {}},
      {"ccp_at", "CCP position", "", "0 = the link's proximal joint, 0.5 = its middle, 1 = its distal end", 0.0,
       0.0, 1.0, 0.05, {}},
  };
  for (int i = 2; i <= kMaxCcp; ++i) {
    const std::string n = std::to_string(i);
    specs.push_back({"ccp" + n + "_link", "CCP " + n + " link", "", "1-based link of CCP " + n + "; 0 = unused",
                     0, 0, 64, 1, {}});
    specs.push_back({"ccp" + n + "_at", "CCP " + n + " position", "", "as ccp_at, for CCP " + n, 0.5, 0.0, 1.0,
                     0.05, {}});
  }
  specs.push_back({"switch_distance", "Hybrid switch distance", "m",
                   "hybrid: DM from when the end-effector comes this near a Voronoi-boundary point, while it or a "
                   "CCP stays as near",
                   0.3, 0.0, 100.0, 0.01, {}});
  specs.push_back({"edge_midpoints", "Edge midpoints as vertices", "",
                   "1: polygon edge midpoints count as obstacle vertices for DI (Ex4: the wall's end and middle "
                   "points)",
                   0, 0, 1, 1, {}});
  specs.push_back(
      {"newton_iterations", "Newton iterations", "", "lagrangian: most Newton iterations per step", 20, 1, 200, 1, {}});
  specs.push_back({"lagrangian_start", "Lagrangian start", "",
                   "lagrangian, first step: climb = along the self-motion from theta0 to a maximum of DI (minimum "
                   "of DM), then Newton; theta0 = Newton from theta0 (the nearest stationary point)",
                   0, 0, 1, 1, {"climb", "theta0"}});
  return specs;
}
std::unique_ptr<Method> make_ccp_voronoi(const MethodContext& ctx) { return std::make_unique<CcpVoronoi>(ctx); }

}  // namespace rrlab
