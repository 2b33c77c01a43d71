// Not a redundancy-resolution method: plays the scenario's witness back (a
// reference lane, and the check that a generated case is solvable). Each step
// commands the velocity that reaches the witness at the next step time, so an
// Euler step lands on it.
#include <rrlab/methods/witness_playback.hpp>

namespace rrlab {
namespace {

class WitnessPlayback final : public Method {
 public:
  explicit WitnessPlayback(std::shared_ptr<const WitnessTrajectory> witness)
      : Method({}), witness_(std::move(witness)) {}

  void step(const StepInput& in, StepOutput& out) override {
    witness_->at(double(in.state.step + 1) * in.dt, next_);
    out.qdot = (next_ - in.state.q) / in.dt;
  }

 private:
  std::shared_ptr<const WitnessTrajectory> witness_;
  Eigen::VectorXd next_;
};

std::unique_ptr<Method> make_witness_playback(const MethodContext& ctx) {
  if (!ctx.witness)
    throw ParamError("method", std::string(kWitnessMethod) +
                                   ": this scenario has no witness (generated cases carry one: rrlab generate)");
  if (ctx.witness->q.empty() || ctx.witness->q[0].size() != ctx.model.dof())
    throw ParamError("method", std::string(kWitnessMethod) + ": the witness does not fit this robot");
  return std::make_unique<WitnessPlayback>(ctx.witness);
}

}  // namespace

const MethodInfo& witness_method_info() {
  static const MethodInfo info{kWitnessMethod,
                               "Plays back the scenario's witness, a joint trajectory known to solve it (generated "
                               "cases); a reference, not a redundancy-resolution method",
                               {},
                               make_witness_playback,
                               unit_step_cost};
  return info;
}

}  // namespace rrlab
