// A sweep spec: which scenarios, which method configurations, which seeds,
// what counts as success.
//   {"name": "NAME",
//    "scenarios": ["path/relative/to/spec.json" | "CATALOGUE_NAME" |
//                  {"generator": FAMILY, "count": N, "seed": S, ...options}],
//    "methods": ["NAME" | {"name": "NAME", "params": {PARAM: value | [values]}}],
//    "seeds": [S, ...],            optional: default each scenario's own seed
//    "success": {...},             success_criteria.hpp
//    "steps": N}                   optional: steps per run (default duration / dt)
// Errors are ScenarioError naming the JSON path (methods[2].params.lambda[1]).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sweep/method_grid.hpp"
#include "scenario/scenario.hpp"
#include "sweep/success_criteria.hpp"

namespace rrlab::sweep {

// One entry of "scenarios": a scenario file (one case) or a generator (count cases).
struct ScenarioEntry {
  std::string family;                // "file", or the generator family
  std::string name;                  // file: catalogue name or file stem
  std::optional<Scenario> scenario;  // file: parsed when the spec is read
  nlohmann::json options = nlohmann::json::object();  // generator options
  std::uint64_t seed = 0;            // generator seed
  int count = 1;                     // cases

  bool generated() const { return family != "file"; }
  // file:NAME, or gen:FAMILY:SEED:INDEX
  std::string case_key(int index) const;
};

struct SweepSpec {
  std::string name;
  std::vector<ScenarioEntry> scenarios;
  std::vector<MethodConfig> configs;  // every grid point of "methods", in spec order
  std::vector<std::uint64_t> seeds;   // empty: each scenario's own
  SuccessCriteria success;
  std::optional<long> steps;
};

// Where relative scenario paths and catalogue names are looked up.
struct SpecDirs {
  std::filesystem::path spec_dir;       // scenario paths are relative to the spec file
  std::filesystem::path scenarios_dir;  // catalogue: scenarios_dir/NAME.json
};

SweepSpec parse_sweep_spec(const nlohmann::json& doc, const SpecDirs& dirs);
SweepSpec load_sweep_spec(const std::string& file, const std::filesystem::path& scenarios_dir);

// A sweep or catalogue name: [A-Za-z0-9_.-]{1,64}.
bool is_plain_name(const std::string& name);

}  // namespace rrlab::sweep
