// A sweep spec: which scenarios, which method configurations, which seeds,
// what counts as success.
//   {"name": "NAME",
//    "scenarios": ["path/relative/to/spec.json" | "CATALOGUE_NAME" |
//                  {"generator": FAMILY, "count": N, "seed": S, ...options} |
//                  {"perturb": SCENARIO, "count": N, "seed": S, ...perturbations}],
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

#include <rrlab/generators/perturbation.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sweep/method_grid.hpp>
#include <rrlab/sweep/success_criteria.hpp>

namespace rrlab::sweep {

// One entry of "scenarios": a scenario file (one case), a generator (count
// cases) or a perturbation family of a scenario file (count cases,
// scenario/perturbation.hpp).
struct ScenarioEntry {
  std::string family;                // "file", the generator family, or "perturb:NAME"
  std::string name;                  // file, perturb: catalogue name or file stem
  std::optional<Scenario> scenario;  // file, perturb: the file's, parsed when the spec is read
  std::string dir;                   // file, perturb: the directory the file's URDF and meshes resolve in
  nlohmann::json options = nlohmann::json::object();  // generator options; perturb: the entry's perturbation keys
  PerturbationOptions perturbation;  // perturb
  PerturbationScale perturbation_scale;  // perturb: the file's reach and free gap, measured once (when the options use them)
  std::uint64_t seed = 0;            // generator and perturb seed
  int count = 1;                     // cases

  bool generated() const { return family != "file"; }
  bool perturbs() const { return family.starts_with("perturb:"); }
  // file:NAME, gen:FAMILY:SEED:INDEX, or perturb:NAME:SEED:INDEX
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
// One entry of "scenarios" (`path` names it in errors).
ScenarioEntry parse_scenario_entry(const nlohmann::json& value, const std::string& path, const SpecDirs& dirs);
SweepSpec load_sweep_spec(const std::string& file, const std::filesystem::path& scenarios_dir);

// A sweep or catalogue name: [A-Za-z0-9_.-]{1,64}.
bool is_plain_name(const std::string& name);

}  // namespace rrlab::sweep
