// Nakamura, Hanafusa & Yoshikawa (1987) task priority:
//   q̇ = J₁⁺ẋ₁ + (J₂N₁)⁺(ẋ₂ − J₂J₁⁺ẋ₁),   N₁ = I − J₁⁺J₁,
// with the secondary task either the distance of the closest link point to
// its obstacle (x₂ = d, kept at least at the influence distance) or joint
// centring (J₂ = I, ẋ₂ = −k(q − q̄), where (N₁)⁺ = N₁ reduces it to N₁ẋ₂).
#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/secondary_tasks.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {
namespace {

class TaskPriority final : public Method {
  // Parameters and labels by name (Method::slot).
  const ParamSlot kSecondary = slot("secondary"), kInfluence = slot("influence"), kGain = slot("gain"),
                  kLambda = slot("secondary_lambda");
  const int kObstacleTask = label(kSecondary, "obstacle");

 public:
  explicit TaskPriority(const MethodContext& ctx)
      : Method(task_priority_params()),
        primary_(task_rows(ctx.space), ctx.model.dof()),
        secondary_(1, ctx.model.dof()),
        scratch_(3, ctx.model.dof()),
        j2_(1, ctx.model.dof()),
        j2_tilde_(1, ctx.model.dof()),
        column_(ctx.model.dof()),
        projected_(ctx.model.dof()),
        secondary_motion_(ctx.model.dof()),
        rhs_(1) {
    joint_range_centres(ctx.model.limits, centre_, weight_);
    active_ = declare_diagnostic("secondary_active");
    distance_ = declare_diagnostic("closest_distance");
  }

  void step(const StepInput& in, StepOutput& out) override {
    primary_.factor_pinv(in.task_jacobian);
    primary_.apply(in.ref.xdot, out.qdot);  // J₁⁺ẋ₁
    bool active = false;
    if (choice(kSecondary) == kObstacleTask) {
      const DistanceTask task = distance_task(in, p(kInfluence), p(kGain), scratch_, j2_);
      out.diag.values[distance_] = task.distance;
      if (task.active) {
        // J̃₂ = J₂N₁ = (N₁J₂ᵀ)ᵀ since N₁ is symmetric
        column_ = j2_.row(0).transpose();
        primary_.null_project(column_, projected_);
        j2_tilde_.row(0) = projected_.transpose();
        // Choice made here: the restricted Jacobian J₂N₁ vanishes where the
        // distance task conflicts with the primary (an algorithmic singularity);
        // its exact pseudoinverse (λ = 0) then sends q̇ to 1e12 and the
        // integrated arm leaves the path. λ > 0 damps it (Maciejewski 1988,
        // Chiaverini 1997): (J̃₂)* = J̃₂ᵀ(J̃₂J̃₂ᵀ + λ²)⁻¹.
        if (p(kLambda) > 0)
          secondary_.factor_dls(j2_tilde_, p(kLambda));
        else
          secondary_.factor_pinv(j2_tilde_);
        rhs_[0] = task.rate - j2_.row(0).dot(out.qdot);  // ẋ₂ − J₂J₁⁺ẋ₁
        secondary_.apply(rhs_, secondary_motion_);
        out.qdot += secondary_motion_;
        active = true;
      }
    } else {
      // ẋ₂ = −k (q − q̄) on joints with both bounds; the others stay free
      column_ = -p(kGain) * (in.state.q - centre_).cwiseProduct(weight_.cwiseSign());
      primary_.null_project(column_, projected_);
      out.qdot += projected_;
      active = true;
    }
    out.diag.values[active_] = active ? 1.0 : 0.0;
  }

 private:
  RightInverse primary_, secondary_;
  Eigen::MatrixXd scratch_, j2_, j2_tilde_;
  Eigen::VectorXd column_, projected_, secondary_motion_, rhs_, centre_, weight_;
  int active_, distance_;
};

}  // namespace

std::vector<ParamSpec> task_priority_params() {
  return {secondary_task_spec(), influence_distance_spec(0.3), secondary_gain_spec(5.0),
          secondary_damping_spec(0.1)};
}
std::unique_ptr<Method> make_task_priority(const MethodContext& ctx) {
  return std::make_unique<TaskPriority>(ctx);
}

}  // namespace rrlab
