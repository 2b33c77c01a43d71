// qp_constraints (Qiu): a whole simulator step (kinematics, distances, task
// reference, obstacle rows, QP, metrics) on the Qiu circle and on a 7-DOF arm
// among 10 obstacles. Each step is also timed on its own: p50/p99 counters in µs
// (the issue's budget: p99 ≤ 100 µs).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

#include "step_timing.hpp"

namespace rrlab {
namespace {

void BM_qp_constraints_step_qiu_circle(benchmark::State& state) {
  Simulator sim(load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/20_qiu_circle.json"));
  timed_steps(state, sim);
}
BENCHMARK(BM_qp_constraints_step_qiu_circle);

// 7-DOF iiwa-like arm, 6-D pose circle, 10 obstacles around the path with
// several inside d_s + σ of some link most of the time.
void BM_qp_constraints_step_dh7_10_obstacles(benchmark::State& state) {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "dt": 0.005, "duration": 6.0, "angle_unit": "deg",
    "robot": {"kind": "dh", "links": [
      {"a": 0, "alpha": -90, "d": 0.36, "radius": 0.06}, {"a": 0, "alpha": 90, "d": 0, "radius": 0.06},
      {"a": 0, "alpha": 90, "d": 0.42, "radius": 0.06}, {"a": 0, "alpha": -90, "d": 0, "radius": 0.06},
      {"a": 0, "alpha": -90, "d": 0.40, "radius": 0.05}, {"a": 0, "alpha": 90, "d": 0, "radius": 0.05},
      {"a": 0, "alpha": 0, "d": 0.126, "radius": 0.04}],
      "q0": [0, 40, 0, -70, 0, 60, 0],
      "limits": {"lower": [-170, -120, -170, -120, -170, -120, -175], "upper": [170, 120, 170, 120, 170, 120, 175],
                 "velocity": [85, 85, 100, 75, 130, 135, 135], "acceleration": [500, 500, 500, 500, 500, 500, 500]}},
    "obstacles": [
      {"shape": "sphere", "center": [0.35, 0.35, 0.7], "radius": 0.08},
      {"shape": "box", "center": [0.7, 0, 0.1], "size": [0.4, 0.8, 0.2]},
      {"shape": "sphere", "center": [0.3, -0.4, 0.6], "radius": 0.06},
      {"shape": "sphere", "center": [0.2, 0.3, 1.0], "radius": 0.05},
      {"shape": "point", "position": [0.45, 0.0, 0.85]},
      {"shape": "point", "position": [0.5, -0.35, 0.3]},
      {"shape": "box", "center": [-0.3, 0.0, 0.5], "size": [0.1, 0.6, 0.6]},
      {"shape": "sphere", "center": [0.0, 0.45, 0.4], "radius": 0.1},
      {"shape": "wall", "point": [0, 0, -0.1], "normal": [0, 0, 1]},
      {"shape": "polygon", "points": [[0.8, 0.4], [1.0, 0.4], [0.9, 0.6]], "z": [0, 0.9]}],
    "task": {"space": "pose", "trajectory": {"type": "circle", "center": [0.6677, -0.1500, 0.4208],
             "radius": 0.15, "normal": [1, 0, 0]}},
    "method": {"name": "qp_constraints"}})");
  Simulator sim(parse_scenario(doc));
  timed_steps(state, sim);
}
BENCHMARK(BM_qp_constraints_step_dh7_10_obstacles);

}  // namespace
}  // namespace rrlab
