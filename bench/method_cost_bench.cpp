// The step cost model the server admits runs by (engine/methods/step_cost.hpp)
// next to what a step really costs: every method on scenarios 01 (planar, 3
// obstacles) and 03 (7-DOF pose), and the parameters that drive the costly
// ones. Counters: `modeled` (the model's factor x the pinv step of the same
// scenario, in µs) beside the measured time per step; the model should
// never be far below the measurement.
#include <benchmark/benchmark.h>

#include <string>
#include <utility>
#include <vector>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/scenario/scenario_step_cost.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {
namespace {

Scenario with_method(const std::string& file, const std::string& method,
                     const std::vector<std::pair<std::string, double>>& params) {
  Scenario scenario = load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/" + file);
  scenario.method.name = method;
  scenario.method.params = params;
  return scenario;
}

// Mean step time (µs) of a few hundred steps, restarting at the end.
double step_us(const Scenario& scenario, int steps) {
  Simulator sim(scenario);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    if (sim.done()) sim.reset();
    sim.step();
  }
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / steps;
}

void costed_method_step(benchmark::State& state, const std::string& file, const std::string& method,
                 std::vector<std::pair<std::string, double>> params) {
  const Scenario scenario = with_method(file, method, params);
  const double pinv_us = step_us(with_method(file, "pinv", {}), 400);
  Simulator sim(scenario);
  for (auto _ : state) {
    if (sim.done()) sim.reset();
    sim.step();
  }
  state.counters["modeled_us"] = pinv_us * method_step_factor(scenario) * link_mesh_factor(scenario.model);
  state.counters["factor"] = method_step_factor(scenario);
}

void register_all() {
  for (const char* file : {"01_planar7_obstacles.json", "03_dh7_pose.json"}) {
    for (const char* method : {"pinv", "dls", "gpm", "task_priority", "sr_task_priority", "closest_point",
                               "posture_generation", "qp_constraints", "ccp_voronoi", "direct_search", "multi_preview",
                               "qp_ik", "hqp", "diffik"})
      benchmark::RegisterBenchmark((std::string("BM_method_step/") + file + "/" + method).c_str(), costed_method_step, file,
                                   method, std::vector<std::pair<std::string, double>>{});
    const std::vector<std::pair<std::string, std::vector<std::pair<std::string, double>>>> variants = {
        {"multi_preview", {{"population", 100}}},  {"multi_preview", {{"generations", 4}}},
        {"multi_preview", {{"previews", 1}}},       {"direct_search", {{"perturb_mask", 7}}},
        {"direct_search", {{"perturb_mask", 127}}}, {"direct_search", {{"newton_iterations", 30}}}};
    for (const auto& [method, params] : variants)
      benchmark::RegisterBenchmark((std::string("BM_method_step/") + file + "/" + method + "/" + params[0].first + "=" +
                                    std::to_string(int(params[0].second)))
                                       .c_str(),
                                   costed_method_step, file, method, params);
  }
}

const bool registered = (register_all(), true);

}  // namespace
}  // namespace rrlab
