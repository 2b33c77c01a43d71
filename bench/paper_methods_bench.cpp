// Step time of the paper methods of issue 4 on their seed scenarios: the
// method's step() alone, at a state reached by simulating part of the run
// (kinematics, distances and the reference already computed, as the
// simulator hands them over). Targets: posture_generation on the 12-DOF
// planar arm <= 30 µs, ccp_voronoi RK4 on Sezgin Ex1 <= 20 µs.
#include <benchmark/benchmark.h>

#include <rrlab/methods/registry.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {
namespace {

void method_step(benchmark::State& state, const char* file, long warm_steps,
                 std::vector<std::pair<const char*, double>> params) {
  const Scenario scenario = load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/" + file);
  Simulator sim(scenario);
  for (long i = 0; i < warm_steps && !sim.done(); ++i) sim.step();
  // the simulator's own evaluation at the current state: one more step's inputs
  auto method = find_method(scenario.method.name)
                    ->make({scenario.model, scenario.task.space, int(scenario.scene.obstacles.size()), scenario.seed});
  for (const auto& [name, value] : scenario.method.params) method->set_param(name, value);
  for (const auto& [name, value] : params) method->set_param(name, value);
  StepOutput out;
  const int n = scenario.model.dof();
  out.qdot = Eigen::VectorXd::Zero(n);
  out.q_next = Eigen::VectorXd::Zero(n);
  out.diag.names = method->diagnostic_names();
  out.diag.values = Eigen::VectorXd::Zero(Eigen::Index(out.diag.names.size()));
  const StepInput in{sim.model(),     sim.state(),         sim.reference(),
                     sim.scene(),     scenario.dt,         sim.kinematics(),
                     sim.task_jacobian(), sim.distances(), sim.task(), sim.self_distances()};
  for (auto _ : state) {
    method->step(in, out);
    benchmark::DoNotOptimize(out.qdot.data());
  }
}

void BM_posture_generation_chen_planar12(benchmark::State& s) {
  method_step(s, "16_chen_sim1_planar12.json", 400, {});
}
void BM_posture_generation_chen_spatial16(benchmark::State& s) {
  method_step(s, "17_chen_sim2_spatial16_window.json", 400, {});
}
void BM_posture_generation_chen_spatial8(benchmark::State& s) {
  method_step(s, "18_chen_sim3_joint_limits.json", 400, {});
}
void BM_ccp_voronoi_rk4_ex1_one_ccp(benchmark::State& s) { method_step(s, "10_sezgin_ex1_lshape.json", 40, {}); }
void BM_ccp_voronoi_rk4_ex1_two_ccp(benchmark::State& s) {
  method_step(s, "10_sezgin_ex1_lshape.json", 40, {{"ccp2_link", 2}, {"ccp2_at", 0.5}});
}
void BM_ccp_voronoi_lagrangian_ex1_one_ccp(benchmark::State& s) {
  method_step(s, "10_sezgin_ex1_lshape.json", 40, {{"integrator", 1}});
}
void BM_ccp_voronoi_rk4_ex2_dm_moving(benchmark::State& s) {
  method_step(s, "12_sezgin_ex2_moving_triangle.json", 40, {});
}
void BM_ccp_voronoi_rk4_ex3_hybrid(benchmark::State& s) { method_step(s, "13_sezgin_ex3_narrow_gap.json", 60, {}); }

BENCHMARK(BM_posture_generation_chen_planar12);
BENCHMARK(BM_posture_generation_chen_spatial16);
BENCHMARK(BM_posture_generation_chen_spatial8);
BENCHMARK(BM_ccp_voronoi_rk4_ex1_one_ccp);
BENCHMARK(BM_ccp_voronoi_rk4_ex1_two_ccp);
BENCHMARK(BM_ccp_voronoi_lagrangian_ex1_one_ccp);
BENCHMARK(BM_ccp_voronoi_rk4_ex2_dm_moving);
BENCHMARK(BM_ccp_voronoi_rk4_ex3_hybrid);

}  // namespace
}  // namespace rrlab
