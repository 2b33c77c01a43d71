// Wampler (1986): damped least squares q̇ = Jᵀ(JJᵀ + λ²I)⁻¹ ẋ. With adaptive
// damping λ grows as the manipulability w = √det(JJᵀ) falls below w0
// (Nakamura & Hanafusa 1986): λ = λ0 (1 − w/w0) for w < w0, else 0.
#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/secondary_tasks.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {
namespace {

class Dls final : public Method {
  // Parameters and labels by name (Method::slot).
  const ParamSlot kLambda = slot("lambda"), kDamping = slot("damping"), kW0 = slot("w0");
  const int kAdaptive = label(kDamping, "adaptive");

 public:
  explicit Dls(const MethodContext& ctx)
      : Method(dls_params()),
        inverse_(task_rows(ctx.space), ctx.model.dof()),
        conditioning_(task_rows(ctx.space), ctx.model.dof()) {
    lambda_used_ = declare_diagnostic("lambda");
  }

  void step(const StepInput& in, StepOutput& out) override {
    double lambda = p(kLambda);
    if (choice(kDamping) == kAdaptive) {
      conditioning_.compute(in.task_jacobian);
      const double w = conditioning_.manipulability();
      lambda = w < p(kW0) ? p(kLambda) * (1.0 - w / p(kW0)) : 0.0;
    }
    inverse_.factor_dls(in.task_jacobian, lambda);
    inverse_.apply(in.ref.xdot, out.qdot);
    out.diag.values[lambda_used_] = lambda;
  }

 private:
  RightInverse inverse_;
  JacobianConditioning conditioning_;
  int lambda_used_;
};

}  // namespace

std::vector<ParamSpec> dls_params() {
  return {damping_spec(0.05),
          {"damping", "Damping", "", "fixed λ, or λ0·(1 − w/w0) below the manipulability w0", 0, 0,
           1, 1, {"fixed", "adaptive"}},
          {"w0", "Manipulability threshold w0", "", "adaptive damping acts below this w", 0.01, 1e-9,
           1e3, 0.001, {}}};
}
std::unique_ptr<Method> make_dls(const MethodContext& ctx) { return std::make_unique<Dls>(ctx); }

}  // namespace rrlab
