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
// Integrators (§2, §4.1):
//  - rk4: Liégeois' gradient projection, eq. 4, θ̇ = J⁺ẋ + λ(I − J⁺J)∇H (λ > 0
//    for DI, λ < 0 for DM: the parameter `gain` is |λ|), integrated with
//    classic fourth-order Runge–Kutta over one step; ẋ at each stage is the
//    task's closed-loop command at the stage's time and configuration, and
//    the obstacles are moved to the stage's time;
//  - lagrangian: Chang's position method, eq. 6–7: at each step solve
//    f(θ) = X_d(t + dt) together with Z∇H(θ) = 0, Z = [(J_a⁻¹J_b)ᵀ  −I]
//    (J_a m independent columns of J, J_b the rest), by Newton's method with a
//    forward-difference Jacobian, warm-started at the previous θ. The first
//    step jumps to the constrained stationary point near θ0 (the paper uses
//    the Lagrangian method for the initial condition of every run).
// The CCP Jacobians are point Jacobians of the kinematics module (the paper's
// eq. 12–13 specialised to its 3-link arm).
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <string>
#include <cmath>
#include <limits>

#include "collision/voronoi_points.hpp"
#include "methods/factories.hpp"
#include "util/right_inverse.hpp"

namespace rrlab {
namespace {

enum { kMode, kIntegrator, kGain, kCcpLink, kCcpAt, kCcp2Link, kCcp2At, kSwitch, kMidpoints, kNewtonIters };
enum { kDI, kDM, kHybrid };
enum { kRk4, kLagrangian };
constexpr int kMaxCcp = 2;
constexpr double kTiny = 1e-12;

class CcpVoronoi final : public Method {
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
    valid_link_[0] = p(kCcpLink);
    valid_link_[1] = p(kCcp2Link);
  }

  void step(const StepInput& in, StepOutput& out) override {
    out.diag.clear();
    collect_ccps();
    const bool dm = use_dm(in);
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
  void on_param_changed(int index) override {
    if (index != kCcpLink && index != kCcp2Link) return;
    const int slot = index == kCcpLink ? 0 : 1;
    const char* name = slot == 0 ? "ccp_link" : "ccp2_link";
    if (p(index) > links_) {
      set_param(name, valid_link_[slot]);
      throw ParamError(name, std::string(name) + ": the arm has " + std::to_string(links_) + " links");
    }
    valid_link_[slot] = p(index);
  }

 private:
  struct Ccp {
    int link;   // 0-based
    double at;  // 0 proximal joint .. 1 distal end
  };

  void collect_ccps() {
    ccp_count_ = 0;
    // defaults beyond a short arm's last link fall on its last link
    if (p(kCcpLink) >= 1) ccps_[ccp_count_++] = {std::min(int(p(kCcpLink)), links_) - 1, p(kCcpAt)};
    if (p(kCcp2Link) >= 1) ccps_[ccp_count_++] = {std::min(int(p(kCcp2Link)), links_) - 1, p(kCcp2At)};
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
        const NearestObstaclePoint np =
            nearest_obstacle_point(scene, f, tau, p(kMidpoints) > 0.5, vertices_);
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
    if (!in.task.is_joystick()) {
      // RK4 wants the path velocity at the stage's instant, not the mean over
      // the coming step that the reference carries for Euler integrators
      const double t = in.state.t + tau, h = 1e-3 * in.dt;
      const Eigen::Vector3d v = (in.task.target_position(t + h) - in.task.target_position(std::max(0.0, t - h))) /
                                (t + h - std::max(0.0, t - h));
      const int rows = std::min(3, m_);
      ref_.xdot.head(rows) = v.head(rows) + in.task.gain() * ref_.error.head(rows);
    }
    inverse_.factor_pinv(jac_);  // eq. 3
    inverse_.apply(ref_.xdot, qdot);
    criterion_gradient(in.model, probe_, in.scene, tau, dm, grad_);
    const double lambda = dm ? -p(kGain) : p(kGain);  // maximise DI, minimise DM
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
    if (in.state.step == 0) settle_on_optimum(in, dm, 2000);
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
  int ccp_count_ = 0;
  StepOutput* report_ = nullptr;
  double last_switch_measure_ = 0;
  bool hybrid_dm_ = false;
  double valid_link_[kMaxCcp] = {0, 0};
  int criterion_, dm_active_, target_distance_[kMaxCcp], voronoi_count_, switch_measure_, newton_iterations_,
      newton_residual_;
};

}  // namespace

std::vector<ParamSpec> ccp_voronoi_params() {
  return {
      {"mode", "Criterion", "",
       "DI: maximise CCP distances to the nearest obstacle vertices (eq. 10); DM: minimise CCP distances to "
       "Voronoi-boundary control points (eq. 11); hybrid: DM near the Voronoi boundary, DI elsewhere",
       0, 0, 2, 1, {"DI", "DM", "hybrid"}},
      {"integrator", "Integrator", "",
       "rk4: gradient projection (eq. 4) integrated by RK4; lagrangian: position method (eq. 6-7) by Newton",
       0, 0, 1, 1, {"rk4", "lagrangian"}},
      {"gain", "Gradient gain |λ|", "1/s", "λ of eq. 4 (rk4 only): speed of the null-space motion", 1.0, 0.0,
       1000.0, 0.1, {}},
      {"ccp_link", "CCP link", "", "1-based link carrying the first CCP", 3, 1, 64, 1, {}},
      {"ccp_at", "CCP position", "", "0 = the link's proximal joint, 0.5 = its middle, 1 = its distal end", 0.0,
       0.0, 1.0, 0.05, {}},
      {"ccp2_link", "Second CCP link", "", "1-based link of a second CCP; 0 = unused", 0, 0, 64, 1, {}},
      {"ccp2_at", "Second CCP position", "", "as ccp_at, for the second CCP", 0.5, 0.0, 1.0, 0.05, {}},
      {"switch_distance", "Hybrid switch distance", "m",
       "hybrid: DM from when the end-effector comes this near a Voronoi-boundary point, while it or a CCP stays as near", 0.3, 0.0,
       100.0, 0.01, {}},
      {"edge_midpoints", "Edge midpoints as vertices", "",
       "1: polygon edge midpoints count as obstacle vertices for DI (Ex4: the wall's end and middle points)", 0,
       0, 1, 1, {}},
      {"newton_iterations", "Newton iterations", "", "lagrangian: most Newton iterations per step", 20, 1, 200, 1,
       {}},
  };
}
std::unique_ptr<Method> make_ccp_voronoi(const MethodContext& ctx) { return std::make_unique<CcpVoronoi>(ctx); }

}  // namespace rrlab
