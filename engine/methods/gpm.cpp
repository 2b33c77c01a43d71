// Liégeois (1977) gradient projection: q̇ = J⁺ẋ + (I − J⁺J) z, z = ±k ∇H,
// with a selectable criterion H:
//  - joint_range: H = 1/(2n) Σ ((q_i − q̄_i)/(q_i,max − q_i,min))², minimised
//    (Liégeois' own criterion; joints without both bounds do not count);
//  - manipulability: H = √det(JJᵀ), maximised (gradient by central
//    differences of the task Jacobian, h = 1e-6 rad);
//  - distance: H = ½ Σ_links (1/d − 1/d0)² over links nearer than d0,
//    minimised; ∇d = J_pᵀ n at each link's nearest point.
#include <cmath>

#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/secondary_tasks.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {
namespace {

class Gpm final : public Method {
  // Parameters and labels by name (Method::slot).
  const ParamSlot kGradient = slot("gradient"), kGain = slot("gain"), kInfluence = slot("influence");
  const int kJointRange = label(kGradient, "joint_range"), kManipulability = label(kGradient, "manipulability");

 public:
  explicit Gpm(const MethodContext& ctx)
      : Method(gpm_params()),
        n_(ctx.model.dof()),
        space_(ctx.space),
        inverse_(task_rows(ctx.space), n_),
        conditioning_(task_rows(ctx.space), n_),
        probe_(ctx.model),
        probe_jacobian_(task_rows(ctx.space), n_),
        point_jacobian_(3, n_),
        q_probe_(n_),
        gradient_(n_),
        null_motion_(n_) {
    joint_range_centres(ctx.model.limits, centre_, inv_range_sq_);
    criterion_ = declare_diagnostic("criterion");
    null_norm_ = declare_diagnostic("null_speed");
  }

  void step(const StepInput& in, StepOutput& out) override {
    double criterion = 0;
    const int gradient = choice(kGradient);
    if (gradient == kJointRange) criterion = joint_range_gradient(in.state.q);
    else if (gradient == kManipulability) criterion = manipulability_gradient(in);
    else criterion = distance_gradient(in);  // "distance"
    inverse_.factor_pinv(in.task_jacobian);
    inverse_.apply(in.ref.xdot, out.qdot);             // J⁺ẋ
    inverse_.null_project(gradient_, null_motion_);    // (I − J⁺J) z
    out.qdot += null_motion_;
    out.diag.values[criterion_] = criterion;
    out.diag.values[null_norm_] = null_motion_.norm();
  }

 private:
  // z = −k ∇H for Liégeois' joint-range criterion; returns H.
  double joint_range_gradient(const Eigen::VectorXd& q) {
    const double scale = 1.0 / n_;
    gradient_ = -p(kGain) * scale * (q - centre_).cwiseProduct(inv_range_sq_);
    return 0.5 * scale * (q - centre_).cwiseAbs2().dot(inv_range_sq_);
  }

  // z = +k ∇w, central differences of w = √det(JJᵀ); returns w.
  double manipulability_gradient(const StepInput& in) {
    const double h = 1e-6;
    q_probe_ = in.state.q;
    for (int i = 0; i < n_; ++i) {
      q_probe_[i] = in.state.q[i] + h;
      const double up = manipulability_at(in.model);
      q_probe_[i] = in.state.q[i] - h;
      const double down = manipulability_at(in.model);
      q_probe_[i] = in.state.q[i];
      gradient_[i] = p(kGain) * (up - down) / (2 * h);
    }
    conditioning_.compute(in.task_jacobian);
    return conditioning_.manipulability();
  }

  double manipulability_at(const Model& model) {
    forward_kinematics(model, q_probe_, probe_);
    task_jacobian(model, probe_, space_, probe_jacobian_);
    conditioning_.compute(probe_jacobian_);
    return conditioning_.manipulability();
  }

  // z = −k ∇U with U = ½ Σ (1/d − 1/d0)² for each link's nearest obstacle.
  double distance_gradient(const StepInput& in) {
    gradient_.setZero();
    double potential = 0;
    const double d0 = p(kInfluence), floor = 1e-3 * d0;
    for (int link = 0; link < in.model.link_count(); ++link) {
      const int obstacle = in.distances.nearest_obstacle(link);
      if (obstacle < 0) continue;
      const LinkObstacleDistance& pair = in.distances.at(link, obstacle);
      if (pair.distance >= d0) continue;
      const double d = std::max(pair.distance, floor);
      const double excess = 1.0 / d - 1.0 / d0;
      potential += 0.5 * excess * excess;
      point_jacobian_linear(in.model, in.kin, link, pair.on_link, point_jacobian_);
      // −∇U = (1/d − 1/d0)(1/d²) ∇d, ∇d = J_pᵀ n
      const Eigen::Vector3d push = (p(kGain) * excess / (d * d)) * pair.normal;
      gradient_.noalias() += point_jacobian_.transpose() * push;
    }
    return potential;
  }

  int n_;
  TaskSpace space_;
  RightInverse inverse_;
  JacobianConditioning conditioning_;
  KinematicsData probe_;
  Eigen::MatrixXd probe_jacobian_, point_jacobian_;
  Eigen::VectorXd q_probe_, gradient_, null_motion_, centre_, inv_range_sq_;
  int criterion_, null_norm_;
};

}  // namespace

std::vector<ParamSpec> gpm_params() {
  return {{"gradient", "Criterion", "", "criterion whose gradient is projected into the null space",
           0, 0, 2, 1, {"joint_range", "manipulability", "distance"}},
          {"gain", "Gradient gain k", "", "step along the criterion gradient", 200.0, 0.0, 1e6, 0.1, {}},
          influence_distance_spec(0.3)};
}
std::unique_ptr<Method> make_gpm(const MethodContext& ctx) { return std::make_unique<Gpm>(ctx); }

}  // namespace rrlab
