// Maciejewski & Klein (1985) obstacle avoidance at the closest point:
//   q̇ = J_e⁺ẋ_e + [J_o(I − J_e⁺J_e)]⁺ (α_o ẋ_o − J_o J_e⁺ ẋ_e),
// J_o the linear Jacobian of the link point nearest to an obstacle, ẋ_o the
// unit vector from the obstacle to it, α_o = k·(d0 − d) its escape speed
// (homogeneous term α_h φ left at zero). Choice made here: the avoidance
// term is blended in by h(d), a smoothstep from 0 at d0 to 1 at d0/2, so that
// joint velocities stay continuous when an obstacle enters the influence zone.
#include <algorithm>

#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/secondary_tasks.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {
namespace {

class ClosestPoint final : public Method {
  // Parameters by name (Method::slot).
  const ParamSlot kInfluence = slot("influence"), kGain = slot("gain"), kLambda = slot("secondary_lambda");

 public:
  explicit ClosestPoint(const MethodContext& ctx)
      : Method(closest_point_params()),
        rows_(point_rows(ctx.model)),
        primary_(task_rows(ctx.space), ctx.model.dof()),
        avoidance_(rows_, ctx.model.dof()),
        scratch_(3, ctx.model.dof()),
        jo_(rows_, ctx.model.dof()),
        jo_tilde_(rows_, ctx.model.dof()),
        column_(ctx.model.dof()),
        projected_(ctx.model.dof()),
        motion_(ctx.model.dof()),
        rhs_(rows_) {
    blend_ = declare_diagnostic("blend");
    distance_ = declare_diagnostic("closest_distance");
  }

  void step(const StepInput& in, StepOutput& out) override {
    primary_.factor_pinv(in.task_jacobian);
    primary_.apply(in.ref.xdot, out.qdot);  // J_e⁺ẋ_e
    const ClosestObstaclePoint cp = closest_obstacle_point(in.distances);
    const double d0 = p(kInfluence);
    double blend = 0;
    if (cp.found && cp.distance < d0) {
      const double s = std::clamp((d0 - cp.distance) / (0.5 * d0), 0.0, 1.0);
      blend = s * s * (3 - 2 * s);
      closest_point_jacobian(in.model, in.kin, cp, scratch_, jo_);
      for (int r = 0; r < rows_; ++r) {  // J̃_o = J_o N, row by row (N symmetric)
        column_ = jo_.row(r).transpose();
        primary_.null_project(column_, projected_);
        jo_tilde_.row(r) = projected_.transpose();
      }
      // Choice made here: J̃_o = J_oN loses rank where avoidance conflicts with
      // the end-effector task; its exact pseudoinverse (λ = 0) then gives
      // unbounded q̇ and the integrated arm leaves the path. λ > 0 damps it
      // (Maciejewski 1988): J̃_o* = J̃_oᵀ(J̃_oJ̃_oᵀ + λ²I)⁻¹.
      if (p(kLambda) > 0)
        avoidance_.factor_dls(jo_tilde_, p(kLambda));
      else
        avoidance_.factor_pinv(jo_tilde_, 1e-10);
      const double alpha = p(kGain) * (d0 - cp.distance);
      rhs_ = alpha * cp.normal.head(rows_);
      rhs_.noalias() -= jo_ * out.qdot;  // α_o ẋ_o − J_o J_e⁺ ẋ_e
      avoidance_.apply(rhs_, motion_);
      out.qdot += blend * motion_;
    }
    out.diag.values[blend_] = blend;
    out.diag.values[distance_] = cp.found ? cp.distance : 0.0;
  }

 private:
  int rows_;
  RightInverse primary_, avoidance_;
  Eigen::MatrixXd scratch_, jo_, jo_tilde_;
  Eigen::VectorXd column_, projected_, motion_, rhs_;
  int blend_, distance_;
};

}  // namespace

std::vector<ParamSpec> closest_point_params() {
  return {influence_distance_spec(0.3), secondary_gain_spec(5.0), secondary_damping_spec(0.1)};
}
std::unique_ptr<Method> make_closest_point(const MethodContext& ctx) {
  return std::make_unique<ClosestPoint>(ctx);
}

}  // namespace rrlab
