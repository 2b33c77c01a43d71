// direct_search (Kapoor): a whole simulator step with 81 options on the
// 10-DOF torso + arm of scenario 22 (options, Newton compensation, criteria
// and selection), and the same with the largest-determinant block search on
// every step (block_switch = 1), and with the method's default parameters
// (/2: Δ = 0.02, w_dm = 0, block_switch = 0.02). Each step is also
// timed on its own: p50/p99 counters in µs (the budget: ≤ 1 ms per step).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include <rrlab/methods/registry.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

#include "step_timing.hpp"

namespace rrlab {
namespace {

void BM_direct_search_step_10dof_81_options(benchmark::State& state) {
  Simulator sim(load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/22_kapoor_square_circle.json"));
  if (state.range(0) == 1) sim.set_param("block_switch", 1.0);
  if (state.range(0) == 2)  // the method's defaults, as the benchmark suite runs it (w_dm = 0: no DM per option)
    for (const ParamSpec& spec : find_method("direct_search")->params) sim.set_param(spec.name, spec.def);
  timed_steps(state, sim);
}
BENCHMARK(BM_direct_search_step_10dof_81_options)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace rrlab
