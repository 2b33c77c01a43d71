// Whole simulator steps timed one by one: p50/p99 counters in µs next to
// Google Benchmark's mean (the issues' budgets are on the tail).
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include <rrlab/sim/simulator.hpp>

namespace rrlab {

inline void timed_steps(benchmark::State& state, Simulator& sim) {
  std::vector<double> us;
  us.reserve(1 << 18);
  for (auto _ : state) {
    if (sim.done()) sim.reset();
    const auto start = std::chrono::steady_clock::now();
    sim.step();
    const auto stop = std::chrono::steady_clock::now();
    if (us.size() < us.capacity()) us.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
  }
  if (us.empty()) return;
  std::sort(us.begin(), us.end());
  state.counters["p50_us"] = us[us.size() / 2];
  state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
}

}  // namespace rrlab
