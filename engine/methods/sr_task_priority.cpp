// Chiaverini (1997) singularity-robust task priority, as Chen et al. eq. (9):
//   q̇ = J_E* ẋ_E + (I − J_E^# J_E) J_C* ẋ_C,   J* = Jᵀ(JJᵀ + λ²I)⁻¹ (eq. 8).
// The projector uses the exact pseudoinverse (Chiaverini) or, with
// projector = damped, J_E* as Chen's eq. (9) prints it. The secondary task is
// the closest-point distance (J_C = nᵀJ_p, ẋ_C = k(d0 − d) inside d0, which
// vanishes at d0 so the switch is smooth) or joint centring (J_C = I).
#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/secondary_tasks.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {
namespace {

class SrTaskPriority final : public Method {
  // Parameters and labels by name (Method::slot).
  const ParamSlot kLambda = slot("lambda"), kSecondary = slot("secondary"), kInfluence = slot("influence"),
                  kGain = slot("gain"), kProjector = slot("projector");
  const int kObstacleTask = label(kSecondary, "obstacle"), kExactProjector = label(kProjector, "exact");

 public:
  explicit SrTaskPriority(const MethodContext& ctx)
      : Method(sr_task_priority_params()),
        primary_(task_rows(ctx.space), ctx.model.dof()),
        projector_(task_rows(ctx.space), ctx.model.dof()),
        secondary_(1, ctx.model.dof()),
        scratch_(3, ctx.model.dof()),
        j2_(1, ctx.model.dof()),
        constraint_motion_(ctx.model.dof()),
        projected_(ctx.model.dof()),
        rhs_(1) {
    joint_range_centres(ctx.model.limits, centre_, weight_);
    active_ = declare_diagnostic("secondary_active");
    distance_ = declare_diagnostic("closest_distance");
  }

  void step(const StepInput& in, StepOutput& out) override {
    const double lambda = p(kLambda);
    primary_.factor_dls(in.task_jacobian, lambda);
    primary_.apply(in.ref.xdot, out.qdot);  // J_E* ẋ_E, eq. (8)
    RightInverse& projector = choice(kProjector) == kExactProjector ? projector_ : primary_;
    if (choice(kProjector) == kExactProjector) projector_.factor_pinv(in.task_jacobian);

    bool active = false;
    if (choice(kSecondary) == kObstacleTask) {
      const DistanceTask task = distance_task(in, p(kInfluence), p(kGain), scratch_, j2_);
      out.diag.values[distance_] = task.distance;
      if (task.active) {
        secondary_.factor_dls(j2_, lambda);
        rhs_[0] = task.rate;
        secondary_.apply(rhs_, constraint_motion_);  // J_C* ẋ_C
        active = true;
      }
    } else {
      // J_C = I: J_C* = I/(1 + λ²)
      constraint_motion_ = (-p(kGain) / (1.0 + lambda * lambda)) *
                           (in.state.q - centre_).cwiseProduct(weight_.cwiseSign());
      active = true;
    }
    if (active) {
      projector.null_project(constraint_motion_, projected_);  // (I − J_E^# J_E) J_C* ẋ_C
      out.qdot += projected_;
    }
    out.diag.values[active_] = active ? 1.0 : 0.0;
  }

 private:
  RightInverse primary_, projector_, secondary_;
  Eigen::MatrixXd scratch_, j2_;
  Eigen::VectorXd constraint_motion_, projected_, rhs_, centre_, weight_;
  int active_, distance_;
};

}  // namespace

std::vector<ParamSpec> sr_task_priority_params() {
  return {damping_spec(0.01), secondary_task_spec(), influence_distance_spec(0.3),
          secondary_gain_spec(50.0),
          {"projector", "Null-space projector", "",
           "exact: I − J⁺J (Chiaverini); damped: I − J*J (Chen eq. 9 as printed)", 0, 0, 1, 1,
           {"exact", "damped"}}};
}
std::unique_ptr<Method> make_sr_task_priority(const MethodContext& ctx) {
  return std::make_unique<SrTaskPriority>(ctx);
}

}  // namespace rrlab
