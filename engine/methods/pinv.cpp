// Whitney (1969): minimum-norm joint velocity q̇ = J⁺ ẋ.
#include <rrlab/methods/factories.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {
namespace {

class Pinv final : public Method {
 public:
  explicit Pinv(const MethodContext& ctx)
      : Method(pinv_params()), inverse_(task_rows(ctx.space), ctx.model.dof()) {
    sigma_min_ = declare_diagnostic("sigma_min");
  }

  void step(const StepInput& in, StepOutput& out) override {
    inverse_.factor_pinv(in.task_jacobian);
    inverse_.apply(in.ref.xdot, out.qdot);  // q̇ = J⁺ ẋ
    out.diag.values[sigma_min_] = inverse_.sigma_min();
  }

 private:
  RightInverse inverse_;
  int sigma_min_;
};

}  // namespace

std::vector<ParamSpec> pinv_params() { return {}; }
std::unique_ptr<Method> make_pinv(const MethodContext& ctx) { return std::make_unique<Pinv>(ctx); }

}  // namespace rrlab
