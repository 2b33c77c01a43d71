// The modern baselines of issue 40 (qp_ik, hqp, diffik) beside the QP method
// of the papers (qp_constraints): whole simulator steps timed one by one
// (p50/p99 counters in µs) on the planar demo (7 links, 3 obstacles), the
// 7-DOF pose scenario (2 obstacles), the iiwa14 URDF arm past a mesh hoop and
// a generated planar_clutter case (seed 5150, the tuning seed). Counters:
// `vs_qp_constraints`, the p50 over qp_constraints' p50 on the same scenario
// in the same process (the target: within 5×), and on the 7-DOF
// scenarios `vs_kdl_wdls`, the p50 over one Orocos KDL weighted-DLS velocity
// IK solve on the iiwa chain (bench/engine_bench.cpp's peer), also measured
// here.
#include <benchmark/benchmark.h>

#include <kdl/chain.hpp>
#include <kdl/chainiksolvervel_wdls.hpp>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include <rrlab/generators/generators.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

#include "step_timing.hpp"

namespace rrlab {
namespace {

Scenario modern_baseline_scenario(const std::string& name, const std::string& method) {
  Scenario sc = name == "planar_clutter_5150_0"
                    ? parse_scenario(generate_scenario("planar_clutter", nlohmann::json::object(), 5150, 0))
                    : load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/" + name + ".json");
  sc.method.name = method;
  sc.method.params.clear();
  return sc;
}

// p50 and p99 of `steps` single steps (restarting at the end of the run).
std::pair<double, double> step_percentiles(Simulator& sim, size_t steps) {
  std::vector<double> us;
  us.reserve(steps);
  while (us.size() < steps) {
    if (sim.done()) sim.reset();
    const auto start = std::chrono::steady_clock::now();
    sim.step();
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(us.begin(), us.end());
  return {us[us.size() / 2], us[std::min(us.size() - 1, us.size() * 99 / 100)]};
}

// One KDL weighted-DLS velocity IK solve on the iiwa-like chain, µs (median of 2,000).
double kdl_wdls_us() {
  const double half_pi = M_PI / 2;
  const double dh[7][3] = {{-half_pi, 0.36, 0}, {half_pi, 0, 0}, {half_pi, 0.42, 0}, {-half_pi, 0, 0},
                           {-half_pi, 0.40, 0}, {half_pi, 0, 0}, {0, 0.126, 0}};
  KDL::Chain chain;
  for (const auto& l : dh) chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::RotZ), KDL::Frame::DH(0, l[0], l[1], 0)));
  KDL::ChainIkSolverVel_wdls solver(chain);
  solver.setLambda(0.05);
  KDL::JntArray q(7), qdot(7);
  for (int i = 0; i < 7; ++i) q(i) = 0.1 + 0.2 * i;
  const KDL::Twist twist(KDL::Vector(0.1, -0.05, 0.02), KDL::Vector(0.1, 0.05, -0.1));
  std::vector<double> us;
  for (int i = 0; i < 2000; ++i) {
    q(0) = 0.1 + 1e-6 * (i & 1023);
    const auto start = std::chrono::steady_clock::now();
    solver.CartToJnt(q, twist, qdot);
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(us.begin(), us.end());
  return us[us.size() / 2];
}

void modern_baseline_step(benchmark::State& state, const std::string& scenario, const std::string& method) {
  Simulator reference(modern_baseline_scenario(scenario, "qp_constraints"));
  const double reference_p50 = step_percentiles(reference, 4000).first;
  Simulator sim(modern_baseline_scenario(scenario, method));
  timed_steps(state, sim);  // p50_us, p99_us
  state.counters["vs_qp_constraints"] = state.counters["p50_us"] / reference_p50;
  if (sim.model().dof() == 7) state.counters["vs_kdl_wdls"] = state.counters["p50_us"] / kdl_wdls_us();
}

void register_modern_baselines() {
  for (const char* scenario : {"01_planar7_obstacles", "03_dh7_pose", "43_urdf_iiwa14_mesh_obstacle", "planar_clutter_5150_0"})
    for (const char* method : {"qp_constraints", "qp_ik", "hqp", "diffik"})
      benchmark::RegisterBenchmark((std::string("BM_modern_baseline_step/") + scenario + "/" + method).c_str(),
                                   modern_baseline_step, std::string(scenario), std::string(method));
}

const bool modern_baselines_registered = (register_modern_baselines(), true);

}  // namespace
}  // namespace rrlab
