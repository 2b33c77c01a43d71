// A redundancy-resolution method written outside rrlab: damped least squares
// with a gain on the commanded task velocity, q̇ = k Jᵀ(J Jᵀ + λ²I)⁻¹ ẋ.
// Registered by name, it is found by scenarios and runs in the simulator like
// a built-in method.
//   own_method SCENARIO
#include <rrlab/rrlab.hpp>

#include <Eigen/Cholesky>
#include <exception>
#include <iostream>
#include <memory>

namespace {

class ScaledDls final : public rrlab::Method {
 public:
  explicit ScaledDls(const rrlab::MethodContext&) : rrlab::Method(specs()) {
    gain_ = slot("gain");
    damping_ = slot("damping");
  }

  static std::vector<rrlab::ParamSpec> specs() {
    return {{"gain", "Gain k", "", "scale of the commanded task velocity", 1.0, 0.0, 2.0, 0.05, {}},
            {"damping", "Damping λ", "", "damping of the least-squares inverse", 0.01, 0.0, 1.0, 0.001, {}}};
  }

  void step(const rrlab::StepInput& in, rrlab::StepOutput& out) override {
    const Eigen::MatrixXd& J = in.task_jacobian;
    const double lambda = p(damping_);
    Eigen::MatrixXd JJt = J * J.transpose();
    JJt.diagonal().array() += lambda * lambda;
    out.qdot = p(gain_) * J.transpose() * JJt.ldlt().solve(in.ref.xdot);
  }

 private:
  rrlab::ParamSlot gain_, damping_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: own_method SCENARIO\n";
    return 2;
  }
  try {
    rrlab::MethodInfo info;
    info.name = "scaled_dls";
    info.description = "Damped least squares with a gain (an example of a method outside rrlab)";
    info.params = ScaledDls::specs();
    info.make = [](const rrlab::MethodContext& ctx) { return std::make_unique<ScaledDls>(ctx); };
    info.step_cost = rrlab::unit_step_cost;  // as dls: one factorization a step
    rrlab::register_external_method(info);

    const rrlab::Scenario scenario = rrlab::load_scenario_file(argv[1]);
    rrlab::Simulator sim(scenario, "scaled_dls");
    sim.set_param("gain", 1.0);
    while (!sim.done()) sim.step();
    std::cout << rrlab::summary_to_json(sim.summary()).dump(2) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "own_method: " << e.what() << "\n";
    return 1;
  }
}
