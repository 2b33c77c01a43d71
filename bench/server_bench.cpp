// WebSocket frame encoding: size and time of one 7-DOF planar frame.
#include <benchmark/benchmark.h>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/server/app/stream_json.hpp>

namespace rrlab::server {
namespace {

void BM_EncodeFrame7Dof(benchmark::State& state) {
  Simulator sim(load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/01_planar7_obstacles.json"));
  for (int i = 0; i < 10; ++i) sim.step();
  std::string out;
  const FrameContext context{1, 10, 1, "running"};
  FrameGeometry geometry(sim.model(), sim.scene(), sim.scenario().task.space);
  for (auto _ : state) {
    encode_frame(context, sim.frame(), sim.model(), sim.scene(), geometry, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["bytes"] = double(out.size());
}
BENCHMARK(BM_EncodeFrame7Dof);

}  // namespace
}  // namespace rrlab::server
