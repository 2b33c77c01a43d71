// Zhang multi-preview control on the paper's 4-link arm (scenario 31: three
// previews, population 20, one generation per step): the cost of one control
// step in the simulator, of the GA alone (three previews re-scored and evolved
// one generation), and of one AMSIP evaluation of an imaginary manipulator.
// The GA's share of a step is BM_multi_preview_ga / BM_multi_preview_step.
#include <benchmark/benchmark.h>

#include <algorithm>

#include <rrlab/methods/multi_preview_ga.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {
namespace {

Scenario paper_scenario() {
  return load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/31_zhang_multi_preview.json");
}

void BM_multi_preview_step(benchmark::State& state) {
  Simulator sim(paper_scenario());
  sim.step();  // first step: warm-up generations of every population
  for (auto _ : state) {
    if (sim.done()) {
      state.PauseTiming();
      sim.reset();
      sim.step();
      state.ResumeTiming();
    }
    sim.step();
  }
  const auto& names = sim.diagnostic_names();
  state.counters["ga_evaluations"] = sim.frame().diagnostics[std::find(names.begin(), names.end(), "ga_evaluations") - names.begin()];
}
BENCHMARK(BM_multi_preview_step)->Unit(benchmark::kMicrosecond);

void BM_multi_preview_ga(benchmark::State& state) {
  const Scenario scenario = paper_scenario();
  const Task task(scenario.task, Eigen::Isometry3d(Eigen::Translation3d(0.1, 1.4, 0)), scenario.duration,
                  scenario.dt);
  ImaginaryManipulator arm(scenario.model, scenario.task.space);
  arm.set_potential(0.15, 10.0);
  std::vector<PreviewPopulation> populations(3, PreviewPopulation(scenario.model.dof(), 200));
  Rng rng(1);
  const GaSettings settings{20, 1, 0.1};
  PreviewTarget target;
  for (int i = 0; i < 3; ++i) {  // warm start, as the method's first step
    target.position = task.target_position(5.0 * (i + 1));
    arm.set_scene(scenario.scene, 5.0 * (i + 1));
    populations[i].evolve(arm, target, rng, settings, 40);
  }
  long step = 0;
  for (auto _ : state) {
    const double t = 0.01 * double(step++ % 5000);
    for (int i = 0; i < 3; ++i) {
      const double ahead = 5.0 * (i + 1);
      target.position = task.target_position(t + ahead);
      arm.set_scene(scenario.scene, ahead);
      populations[i].evolve(arm, target, rng, settings, 1);
    }
    benchmark::DoNotOptimize(populations[0].best().data());
  }
}
BENCHMARK(BM_multi_preview_ga)->Unit(benchmark::kMicrosecond);

void BM_multi_preview_amsip_evaluation(benchmark::State& state) {
  const Scenario scenario = paper_scenario();
  ImaginaryManipulator arm(scenario.model, scenario.task.space);
  arm.set_scene(scenario.scene, 0.0);
  PreviewTarget target;
  target.position = Eigen::Vector3d(1.6, 1.0, 0);
  Eigen::VectorXd q = scenario.q0, gene(q.size());
  long i = 0;
  for (auto _ : state) {
    gene = q;
    gene[0] += 1e-3 * double(i++ & 255);  // a gene a little off the target: Newton has work to do
    benchmark::DoNotOptimize(arm.evaluate(gene, target).fitness);
  }
}
BENCHMARK(BM_multi_preview_amsip_evaluation)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace rrlab
