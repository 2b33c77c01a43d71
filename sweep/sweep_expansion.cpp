#include <rrlab/sweep/sweep_expansion.hpp>

#include <limits>

namespace rrlab::sweep {

std::vector<SweepCase> expand_sweep(const SweepSpec& spec) {
  std::vector<std::optional<std::uint64_t>> seeds;
  if (spec.seeds.empty()) seeds.push_back(std::nullopt);
  for (std::uint64_t s : spec.seeds) seeds.push_back(s);

  std::vector<SweepCase> cases;
  for (size_t e = 0; e < spec.scenarios.size(); ++e) {
    const ScenarioEntry& entry = spec.scenarios[e];
    for (int i = 0; i < entry.count; ++i) {
      const std::string scenario_key = entry.case_key(i);
      for (size_t c = 0; c < spec.configs.size(); ++c) {
        for (const auto& seed : seeds) {
          SweepCase k;
          k.position = cases.size();
          k.entry = e;
          k.index = i;
          k.config = c;
          k.seed = seed;
          k.scenario_key = scenario_key;
          k.config_key = spec.configs[c].key;
          k.family = entry.family;
          k.key = spec.name + "/" + scenario_key + "/" + k.config_key + "/" + (seed ? std::to_string(*seed) : "own");
          cases.push_back(std::move(k));
        }
      }
    }
  }
  return cases;
}

std::uint64_t sweep_case_count(const SweepSpec& spec) {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  const auto times = [&](std::uint64_t a, std::uint64_t b) { return b != 0 && a > kMax / b ? kMax : a * b; };
  const std::uint64_t per_case = times(spec.configs.size(), spec.seeds.empty() ? 1 : spec.seeds.size());
  std::uint64_t total = 0;
  for (const ScenarioEntry& entry : spec.scenarios) {
    const std::uint64_t cases = times(std::uint64_t(entry.count), per_case);
    total = cases > kMax - total ? kMax : total + cases;
  }
  return total;
}

std::vector<SweepCase> cases_of_shard(const std::vector<SweepCase>& cases, const Shard& shard) {
  std::vector<SweepCase> out;
  for (const SweepCase& c : cases)
    if (shard.contains(c.position)) out.push_back(c);
  return out;
}

}  // namespace rrlab::sweep
