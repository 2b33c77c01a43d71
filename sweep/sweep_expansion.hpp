// A sweep spec expanded into its runs, in one fixed order: for each scenario
// entry, each of its cases, each method configuration, each seed. The same
// spec always gives the same runs in the same order (jobs and shards only
// choose which of them a process runs), each with a stable key:
//   SWEEP/SCENARIO_KEY/CONFIG_KEY/SEED
// SCENARIO_KEY is file:NAME or gen:FAMILY:SEED:INDEX, CONFIG_KEY is
// method{param=value,...} (method_grid.hpp) and SEED the run's seed, or "own"
// when the spec gives no seeds (each scenario's own).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/sweep/sweep_spec.hpp>

namespace rrlab::sweep {

struct SweepCase {
  size_t position = 0;                // in the expansion
  size_t entry = 0;                   // spec.scenarios index
  int index = 0;                      // case within the entry
  size_t config = 0;                  // spec.configs index
  std::optional<std::uint64_t> seed;  // none: the scenario's own
  std::string key, scenario_key, config_key, family;
};

// Which part of the expansion a process runs: position mod count == index.
struct Shard {
  int index = 0, count = 1;
  bool contains(size_t position) const { return position % size_t(count) == size_t(index); }
};

std::vector<SweepCase> expand_sweep(const SweepSpec& spec);
// How many cases expand_sweep(spec) makes, without making them (a size limit
// is checked before the expansion can take the memory); saturates at the
// largest std::uint64_t.
std::uint64_t sweep_case_count(const SweepSpec& spec);
std::vector<SweepCase> cases_of_shard(const std::vector<SweepCase>& cases, const Shard& shard);

}  // namespace rrlab::sweep
