// Chen, Liu, Lee & Liang (2002): on-line multi-criteria posture generation.
//   q̇ = J_E* ẋ_E + (I − J_E* J_E) J_C* ẋ_C                       (eq. 9, J* of eq. 8, λ)
// with the constraint task generated link by link from the end-effector back
// to the base (the posture generation rule, eq. 13):
//   ẋ_{n+1} = ẋ_E;  for i = n … 1:  x̃_{i+1} = x_{i+1} + ẋ_{i+1}Δt   (eq. 17)
//     Φ^j = ω(γ1 dΓ123/dθ_i^j + (1 − γ1)[γ2/ω θ_i^C + (1 − γ2) dΓ4/dθ_i^j])   (eq. 29)
//     r_i = Σ_j Φ^j d(−O_i)/dθ_i^j,  ẋ_i = ẋ_{i+1} + r_i              (eq. 13)
//   ẋ_C = [r_1; …; r_n],  J_C = dΩ/dθ, Ω = −[O_1; …; O_n]          (eq. 14–15)
//   J_C* = (J_CᵀJ_C + λ²I)⁻¹J_Cᵀ                                   (eq. 16)
// θ_i^j are the joints of link i (one about z for planar chains, the x/z pair
// for spatial_xz chains, eq. 11–12); d(−O_i)/dθ_i^j = a_j × (−O_i) turns the
// link about its distal end x̃_{i+1}, which is held (clamped).
// Criteria of link i (their weights are parameters, default 1):
//  Γ1 collision cone (eq. 18, exact derivative, see criteria.hpp) against the
//     nearest point b_ki of every obstacle, B_ki = b_ki − x̃_{i+1},
//     φ_i = atan(η/‖O_i‖); active when ‖B_ki‖ <= ‖O_i‖ (the paper's
//     d(B_k, x̃_{i+1}), estimated by the distance to b_ki) and Ψ < φ_i;
//  Γ2 adjacent link (eq. 20–22): ρ the vector from link i−1 to obstacle k
//     (capsule surface distance along the nearest-point normal),
//     D̄ = −O_i − D_ik = −ρ − (ρ·ẋ_{i+1}Δt)ρ/‖ρ‖² (the projected motion over
//     one sample, as eq. 17 does), active when ‖D̄‖ <= η;
//  Γ3 joint limits as virtual obstacles (eq. 23–24) with cone half-angle
//     `influence_deg`: for a joint about a fixed axis the included angle
//     between −O_i and B_i^J is the joint's distance to its limit, so the
//     cone is evaluated on joint angles: the link's own joint j (+1 per unit
//     rotation of the link) and the same-position joint of link i+1 (−1: the
//     distal joint opens as the link turns with the next link held). Exact
//     for planar chains; in 3D the turn δ·a_j of link i (next link held) moves
//     joint k of link i+1 by −δ(a_j·a_k) to first order, the part of the turn
//     that joint can take (for x/z pairs and DH chains with perpendicular
//     consecutive axes this is 0 or partial; an earlier −1 for "the same axis
//     type" pushed joints whose axes are not parallel, the wrong way on DH
//     arms). Joints of zero-length links (DH offsets) get no Γ3 push of their
//     own: the rule has no link direction to turn there. Limits: ±`limit_deg`, clipped
//     to the model's limits, only on joints that have limits in the model
//     (Chen's base rotation −π in Simulations 2–3 has none);
//  θ^C connection (eq. 26): least squares of d(−O_i)/dθ θ̇ = −ẋ_{i+1};
//  Γ4 elastic posture (eq. 27–28) toward the bisector of the neighbours
//     (one neighbour at either end of the chain); not on link 1 unless
//     `elastic_first_link` (the paper's simulations leave it off).
//  γ1 (eq. 30) is the largest closeness term of the active criteria (cos Ψ of
//  active cones, cos(‖D̄‖π/2η) of active Γ2 terms), 0 when none is active, so
//  that a free link is driven by connection and elasticity alone; γ2 = 1 −
//  exp(−‖ẋ_{i+1}‖/δ).
// Eq. 29 prints d(−O_i/‖O_i‖)/dθ, eq. 13 J_c = d(−O_i)/dθ; we use the latter,
// so that r_i is the velocity of the proximal joint x_i (a length, as eq. 13's
// sum ẋ_i = ẋ_{i+1} + r_i needs) and matches eq. 15's J_C row for row. As ‖O_i‖
// is constant under a rotation, d(−O_i)/dθ = ‖O_i‖·d(−O_i/‖O_i‖)/dθ: the
// choice multiplies link i's r_i by its length. That is a reweighting, not a
// sign fix: in eq. 16's least squares J_C's rows of link i carry the same
// factor, so where J_C can meet every r_i (a planar chain, or any chain with
// J_C of full column rank and λ → 0) the link rates Φ come out unchanged, and
// where it cannot, longer links weigh more (by ‖O_i‖²) in the residual. The
// criteria themselves are not scaled: Γ1/Γ3 use dΨ/dθ (length-free), Γ4 the
// normalised O_i, only Γ2's dΓ2/dθ = d(−O_i)/dθ·D̄/‖D̄‖ and θ^C carry lengths,
// as their own definitions do. The one sign that differs is eq. 14's
// ẋ_C = −[r]: we use +[r], the sign that climbs the criteria (tested: Γ1 grows).
// Rotation order (spatial_xz chains): eq. 11 prints O_i = R_i⋯R_1 L_i; the
// chain here is serial, each pair's axes riding on the previous link, so
// O_i = R_1⋯R_i L_i (R_k = R_x(θ_k^x)R_z(θ_k^z) of eq. 12, the printed passive
// R_x). The two agree for planar chains (rotations about one axis commute)
// and differ in 3D: the printed order turns link i about axes fixed in the
// world, which is not a chain of joints. Chen's q0 of Simulations 2–3 gives
// different arms under the two orders (Sim 3's hand at (2.13, 1.85, 3) here,
// (−2.75, −0.64, 3) under the printed order).
// Defaults (rrlab's, for cases nobody tuned): ω = 1 1/s and w_limits = 2.
// The paper's criteria are unweighted and its ω is 0.1–0.2 per cycle; the
// paper scenarios (16–18) set ω, w_limits = 1 and max_null_step = 0 (no cap)
// themselves. With ω = 0.1 and
// w_limits = 1 the Γ3 push (ω·dΓ3/dΨ ≈ 0.15 rad/s near a limit) is outweighed
// in the null-space projection by the other links' connection terms, and on
// generated planar_limits cases posture_generation crossed a limit farther
// than minimum norm did (seed 77: 4 of 200 crossed, 2 deeper than pinv, one by
// 49° where pinv crossed by 4°). Chosen on seeds 77, 5 and 1001 (200
// planar_limits and 100 of each obstacle family per seed) over ω ∈ {0.1 … 2}
// × w_limits ∈ {1 … 10}: at ω = 1, w_limits = 2 1 of 200 runs per seed crosses
// a limit (deeper than pinv on 2 of 600), planar_limits succeeds 197–200 of
// 200, narrow_passage 28 → 68–71 and moving_obstacles 45 → 58–66 of 100; a
// larger w_limits (5–10) or ω = 2 lets Γ3 fight the task (planar_limits
// success 38–158 of 200), and w_limits = 20 swamped the collision cone
// in Chen's Simulation 2 (min distance 0.041 → −0.217 m from w_limits = 5).
// Units: rates per second; the paper's "per cycle" numbers (ω, δ, 0.1 per
// cycle) are per second of scenario time, with dt a fraction of a cycle.
#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>

#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/posture_generation_criteria.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {
namespace {

constexpr int kMaxJointsPerLink = 3;
constexpr double kDeg = M_PI / 180.0;

class PostureGeneration final : public Method {
  // Parameters by name (Method::slot).
  const ParamSlot kEta = slot("eta"), kOmega = slot("omega"), kDelta = slot("delta"), kLimit = slot("limit_deg"),
                  kInfluence = slot("influence_deg"), kLambda = slot("lambda"), kWCollision = slot("w_collision"),
                  kWAdjacent = slot("w_adjacent"), kWLimits = slot("w_limits"), kWConnection = slot("w_connection"),
                  kMaxNullStep = slot("max_null_step"),
                  kWElastic = slot("w_elastic"), kElasticFirst = slot("elastic_first_link");

 public:
  explicit PostureGeneration(const MethodContext& ctx)
      : Method(posture_generation_params()),
        n_(ctx.model.dof()),
        links_(ctx.model.link_count()),
        primary_(task_rows(ctx.space), n_),
        jc_(3 * links_, n_),
        xc_(3 * links_),
        normal_(n_, n_),
        z_(n_),
        rhs_(n_),
        projected_(n_),
        first_joint_(links_),
        gamma_(links_, 6) {
    for (int l = 0; l < links_; ++l) first_joint_[l] = l == 0 ? 0 : ctx.model.links[l - 1].last_joint + 1;
    lower_ = ctx.model.limits.lower;
    upper_ = ctx.model.limits.upper;
    d_gamma_[0] = declare_diagnostic("Gamma1");
    d_gamma_[1] = declare_diagnostic("Gamma2");
    d_gamma_[2] = declare_diagnostic("Gamma3");
    d_gamma_[3] = declare_diagnostic("Gamma4");
    d_weight_[0] = declare_diagnostic("gamma1");
    d_weight_[1] = declare_diagnostic("gamma2");
    d_link_ = declare_diagnostic("constrained_link");
    normal_.setZero();
  }

  void step(const StepInput& in, StepOutput& out) override {
    const double lambda = p(kLambda);
    primary_.factor_dls(in.task_jacobian, lambda);
    primary_.apply(in.ref.xdot, out.qdot);  // J_E* ẋ_E, eq. 8

    const size_t most = size_t(links_) * size_t(std::max(1, in.distances.obstacles));
    if (out.overlays.segments.capacity() < most) {  // once: no allocation in steady state
      out.overlays.points.reserve(most);
      out.overlays.segments.reserve(most);
    }
    out.overlays.points.clear();  // x̃_{i+1} of links with an active cone
    out.overlays.segments.clear();  // x̃_{i+1} → b_ki of each active cone (Γ1)
    overlays_ = &out.overlays;
    Eigen::Vector3d xdot_next = Eigen::Vector3d::Zero();  // ẋ_{n+1} = ẋ_E
    xdot_next.head(std::min<Eigen::Index>(3, in.ref.xdot.size())) =
        in.ref.xdot.head(std::min<Eigen::Index>(3, in.ref.xdot.size()));
    for (int l = links_ - 1; l >= 0; --l) {  // posture generation rule: end-effector → base
      const Eigen::Vector3d r = link_motion(in, l, xdot_next);
      xc_.segment<3>(3 * l) = r;
      xdot_next += r;  // eq. 13: ẋ_i = ẋ_{i+1} + r_i
    }
    constraint_jacobian(in);
    // eq. 16: J_C* ẋ_C = (J_CᵀJ_C + λ²I)⁻¹ J_Cᵀ ẋ_C
    normal_.noalias() = jc_.transpose() * jc_;
    normal_.diagonal().array() += lambda * lambda;
    llt_.compute(normal_);
    rhs_.noalias() = jc_.transpose() * xc_;
    z_ = llt_.solve(rhs_);
    primary_.null_project(z_, projected_);  // (I − J_E* J_E) J_C* ẋ_C, eq. 9
    // rrlab's: the null-space term moves no joint more than max_null_step per
    // step (scaled as a whole, so its direction stays): a step along the
    // self-motion leaks into the task to second order, ~|Δθ|², and at a
    // coarse dt the leak outgrows the task's feedback
    const double peak = projected_.cwiseAbs().maxCoeff() * in.dt;
    if (p(kMaxNullStep) > 0 && peak > p(kMaxNullStep)) projected_ *= p(kMaxNullStep) / peak;
    out.qdot += projected_;
    report(out);
  }

 private:
  // r_i of one link (eq. 29 with eq. 13's J_c); records Γ1..Γ4, γ1, γ2.
  // Stays whole (over 100 lines): it follows Chen et al.'s eq. 13-29 in their
  // order for one link, each term next to the one it is summed with.
  Eigen::Vector3d link_motion(const StepInput& in, int l, const Eigen::Vector3d& xdot_next) {
    const KinematicsData& kin = in.kin;
    const Eigen::Vector3d o = kin.link_end.col(l) - kin.link_start.col(l);
    const double len = o.norm();
    gamma_.row(l).setZero();
    if (len < 1e-9) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d u = -o;                                          // −O_i
    const Eigen::Vector3d tip = kin.link_end.col(l) + xdot_next * in.dt;  // x̃_{i+1}, eq. 17
    const double phi = std::atan(p(kEta) / len);
    const int j0 = first_joint_[l], j1 = in.model.links[l].last_joint;
    const int count = std::min(j1 - j0 + 1, kMaxJointsPerLink);

    Eigen::Vector3d du[kMaxJointsPerLink];
    double d123[kMaxJointsPerLink] = {0, 0, 0}, d4[kMaxJointsPerLink] = {0, 0, 0};
    double g1 = 0, g2 = 0, g3 = 0, g4 = 0, closeness = 0;
    bool revolute[kMaxJointsPerLink];
    for (int c = 0; c < count; ++c) {
      const int j = j0 + c;
      revolute[c] = in.model.joints[j].type == JointType::revolute;
      du[c] = revolute[c] ? Eigen::Vector3d(kin.axis_dirs.col(j).cross(u)) : Eigen::Vector3d::Zero();
    }

    // Γ1: collision cones (eq. 18–19)
    for (int k = 0; k < in.distances.obstacles; ++k) {
      const Eigen::Vector3d b = in.distances.at(l, k).on_obstacle - tip;  // B_ki
      if (b.norm() > len) { g1 += 1; continue; }
      bool counted = false;
      for (int c = 0; c < count; ++c) {
        if (!revolute[c]) continue;
        const chen::Angle a = chen::included_angle(u, du[c], b);
        const chen::Cone cn = chen::cone(a.psi, phi);
        if (!counted) g1 += cn.value, counted = true;
        if (!cn.active) continue;
        d123[c] += p(kWCollision) * cn.slope * a.dpsi;
        closeness = std::max(closeness, cn.closeness);
        if (c == 0 && overlays_) {
          overlays_->points.push_back(tip);
          overlays_->segments.emplace_back(tip, in.distances.at(l, k).on_obstacle);
        }
      }
      if (!counted) g1 += 1;
    }
    // Γ2: the adjacent link i−1 (eq. 20–22)
    if (l > 0) {
      for (int k = 0; k < in.distances.obstacles; ++k) {
        const LinkObstacleDistance& pair = in.distances.at(l - 1, k);
        const Eigen::Vector3d rho = -pair.normal * std::max(pair.distance, 1e-9);
        const Eigen::Vector3d step = xdot_next * in.dt;
        const Eigen::Vector3d dbar = -rho - (rho.dot(step) / rho.squaredNorm()) * rho;
        bool counted = false;
        for (int c = 0; c < count; ++c) {
          if (!revolute[c]) continue;
          const chen::Adjacent t = chen::adjacent_term(dbar, du[c], p(kEta));
          if (!counted) g2 += t.value, counted = true;
          if (!t.active) continue;
          d123[c] += p(kWAdjacent) * t.grad;
          closeness = std::max(closeness, t.closeness);
        }
        if (!counted) g2 += 1;
      }
    }
    // Γ3: joint limits as virtual obstacles (eq. 23–24)
    const double influence = p(kInfluence) * kDeg, limit = p(kLimit) * kDeg;
    for (int c = 0; c < count; ++c) {
      if (!revolute[c]) continue;
      auto limit_term = [&](int j, double sign) {  // sign: dq_j per unit turn of link i
        if (j < 0 || j >= n_) return;
        const double q = in.state.q[j];
        if (std::isfinite(upper_[j])) {
          const chen::Cone cn = chen::cone(std::min(upper_[j], limit) - q, influence);
          g3 += cn.value;
          if (cn.active) d123[c] += p(kWLimits) * cn.slope * -sign, closeness = std::max(closeness, cn.closeness);
        }
        if (std::isfinite(lower_[j])) {
          const chen::Cone cn = chen::cone(q - std::max(lower_[j], -limit), influence);
          g3 += cn.value;
          if (cn.active) d123[c] += p(kWLimits) * cn.slope * sign, closeness = std::max(closeness, cn.closeness);
        }
      };
      limit_term(j0 + c, +1.0);
      if (l + 1 < links_) {  // every joint of the next link, by the projection −a_j·a_k
        const Eigen::Vector3d a = kin.axis_dirs.col(j0 + c);
        for (int k = first_joint_[l + 1]; k <= in.model.links[l + 1].last_joint; ++k) {
          if (in.model.joints[k].type != JointType::revolute) continue;
          const double share = a.dot(kin.axis_dirs.col(k));
          if (std::abs(share) > 1e-6) limit_term(k, -share);
        }
      }
    }
    // Γ4: elastic posture (eq. 27–28)
    const bool elastic = l > 0 || p(kElasticFirst) > 0.5;
    if (elastic) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      if (l + 1 < links_) e += unit(kin.link_end.col(l + 1) - kin.link_start.col(l + 1));
      if (l > 0) e += unit(kin.link_end.col(l - 1) - kin.link_start.col(l - 1));
      for (int c = 0; c < count; ++c) {
        const chen::Elastic t = chen::elastic_term(o, -du[c], e);
        g4 = t.value;
        d4[c] = p(kWElastic) * t.grad;
      }
    }
    // θ^C (eq. 26): least squares of J_i θ̇ = −ẋ_{i+1}, J_i = [d(−O_i)/dθ^j]
    Eigen::Matrix<double, 3, kMaxJointsPerLink> ji = Eigen::Matrix<double, 3, kMaxJointsPerLink>::Zero();
    for (int c = 0; c < count; ++c) ji.col(c) = du[c];
    Eigen::Matrix<double, kMaxJointsPerLink, kMaxJointsPerLink> jtj = ji.transpose() * ji;
    for (int c = count; c < kMaxJointsPerLink; ++c) jtj(c, c) = 1;
    jtj.diagonal().array() += 1e-12;
    const Eigen::Matrix<double, kMaxJointsPerLink, 1> theta_c = jtj.ldlt().solve(ji.transpose() * -xdot_next);

    // eq. 30 and eq. 29
    const double gamma1 = std::clamp(closeness, 0.0, 1.0);
    const double gamma2 = 1 - std::exp(-xdot_next.norm() / p(kDelta));
    const double omega = p(kOmega);
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int c = 0; c < count; ++c) {
      const double phi_j =
          omega * (gamma1 * d123[c] +
                   (1 - gamma1) * (gamma2 / omega * p(kWConnection) * theta_c[c] + (1 - gamma2) * d4[c]));
      r += phi_j * du[c];  // r_i = J_c Φ (eq. 13)
    }
    gamma_.row(l) << g1, g2, g3, g4, gamma1, gamma2;
    return r;
  }

  static Eigen::Vector3d unit(const Eigen::Vector3d& v) {
    const double n = v.norm();
    return n > 0 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
  }

  // Eq. 15: J_C = dΩ/dθ, Ω = −[O_1; …; O_n]; joint j turns every link from its own on.
  void constraint_jacobian(const StepInput& in) {
    jc_.setZero();
    for (int l = 0; l < links_; ++l) {
      const Eigen::Vector3d o = in.kin.link_end.col(l) - in.kin.link_start.col(l);
      for (int j = 0; j <= in.model.links[l].last_joint; ++j) {
        const Eigen::Vector3d a = in.kin.axis_dirs.col(j);
        if (in.model.joints[j].type == JointType::revolute)
          jc_.block<3, 1>(3 * l, j) = -a.cross(o);
        else if (j >= first_joint_[l])
          jc_.block<3, 1>(3 * l, j) = -a;
      }
    }
  }

  void report(StepOutput& out) {
    int worst = 0;
    for (int l = links_ - 1; l >= 0; --l)
      if (gamma_(l, 4) > gamma_(worst, 4) || (l > worst && gamma_(l, 4) == gamma_(worst, 4))) worst = l;
    if (links_ == 0) return;
    for (int c = 0; c < 4; ++c) out.diag.values[d_gamma_[c]] = gamma_(worst, c);
    out.diag.values[d_weight_[0]] = gamma_(worst, 4);
    out.diag.values[d_weight_[1]] = gamma_(worst, 5);
    out.diag.values[d_link_] = worst + 1;
  }

  int n_, links_;
  RightInverse primary_;
  Eigen::MatrixXd jc_;
  Eigen::VectorXd xc_;
  Eigen::MatrixXd normal_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::VectorXd z_, rhs_, projected_;
  Eigen::VectorXi first_joint_;
  Eigen::MatrixXd gamma_;  // per link: Γ1, Γ2, Γ3, Γ4, γ1, γ2
  Eigen::VectorXd lower_, upper_;
  int d_gamma_[4], d_weight_[2], d_link_;
  Overlays* overlays_ = nullptr;
};

}  // namespace

std::vector<ParamSpec> posture_generation_params() {
  return {
      {"eta", "Safe distance η", "m", "desired link–obstacle distance; cone half-angle φ_i = atan(η/‖O_i‖)", 1.0,
       1e-6, 100.0, 0.05, {}},
      {"omega", "Gain ω", "1/s", "step along the criteria gradient (eq. 29; the paper's 0.1–0.2 per cycle)", 1.0, 0.0, 100.0, 0.01, {}},
      {"delta", "Connection scale δ", "m/s", "γ2 = 1 − exp(−‖ẋ_{i+1}‖/δ) (eq. 30)", 0.3, 1e-6, 100.0, 0.01, {}},
      {"limit_deg", "Joint limit θ^J", "deg", "virtual-obstacle limit ±θ^J on joints that have limits", 135.0,
       0.0, 360.0, 1.0, {}},
      {"influence_deg", "Limit influence φ^J", "deg", "joints within this angle of a limit are pushed back", 55.0,
       0.0, 180.0, 1.0, {}},
      {"lambda", "Damping λ", "", "damped least squares of eq. 8 and eq. 16", 0.01, 0.0, 10.0, 0.001, {}},
      {"w_collision", "Weight Γ1", "", "collision cone (eq. 18)", 1.0, 0.0, 100.0, 0.1, {}},
      {"w_adjacent", "Weight Γ2", "", "adjacent-link distance (eq. 21)", 1.0, 0.0, 100.0, 0.1, {}},
      {"w_limits", "Weight Γ3", "", "joint limits as virtual obstacles (eq. 23; the paper's criteria are unweighted, 1)", 2.0, 0.0, 100.0, 0.1, {}},
      {"w_connection", "Weight θ^C", "", "posture connection (eq. 26)", 1.0, 0.0, 100.0, 0.1, {}},
      {"w_elastic", "Weight Γ4", "", "elastic posture (eq. 28)", 1.0, 0.0, 100.0, 0.1, {}},
      {"elastic_first_link", "Γ4 on link 1", "", "the paper's simulations do not apply Γ4 to the first link", 0, 0,
       1, 1, {"off", "on"}},
      {"max_null_step", "Largest null-space step", "rad",
       "rrlab's: the null-space term of eq. 9 moves no joint more than this per step (scaled as a whole; its leak "
       "into the task grows with the square of the step); 0 = no cap", 0.02, 0.0, 1.0, 0.001, {}},
  };
}
std::unique_ptr<Method> make_posture_generation(const MethodContext& ctx) {
  return std::make_unique<PostureGeneration>(ctx);
}

}  // namespace rrlab
