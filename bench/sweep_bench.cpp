// Sweep throughput, runs per second, with 1 and 2 jobs: 01_planar7_obstacles
// (800 steps) with pinv, dls and closest_point × 8 seeds = 24 runs stored
// (summaries, no frames) into a fresh database per iteration.
#include <benchmark/benchmark.h>
#include <stdlib.h>

#include <filesystem>

#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_runner.hpp>
#include <rrlab/sweep/sweep_spec.hpp>

namespace rrlab::sweep {
namespace {

SweepSpec planar_suite() {
  const std::filesystem::path scenarios = std::filesystem::path(RRLAB_SOURCE_DIR) / "scenarios";
  const nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "bench", "scenarios": ["01_planar7_obstacles"], "methods": ["pinv", "dls", "closest_point"],
    "seeds": [1, 2, 3, 4, 5, 6, 7, 8], "success": {"max_tracking_error": 0.01}})");
  return parse_sweep_spec(doc, {scenarios, scenarios});
}

void BM_SweepPlanar7(benchmark::State& state) {
  const SweepSpec spec = planar_suite();
  const std::vector<SweepCase> cases = expand_sweep(spec);
  std::string pattern = "/tmp/rrlab-sweep-bench-XXXXXX";
  const std::string dir = mkdtemp(pattern.data());
  RunnerOptions options;
  options.jobs = int(state.range(0));
  int round = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto store = std::make_unique<storage::RunStore>(dir + "/sweep" + std::to_string(round++) + ".db");
    state.ResumeTiming();
    const RunnerOutcome outcome = run_sweep(spec, cases, *store, options);
    benchmark::DoNotOptimize(outcome.stored);
    state.PauseTiming();
    store.reset();
    state.ResumeTiming();
  }
  std::filesystem::remove_all(dir);
  state.SetItemsProcessed(state.iterations() * std::int64_t(cases.size()));
  state.counters["runs"] = double(cases.size());
}
BENCHMARK(BM_SweepPlanar7)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rrlab::sweep
