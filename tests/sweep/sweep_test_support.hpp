// Shared by the sweep tests: temporary directories, spec files, the rrlab
// binary, stored summaries without their wall-clock part.
#pragma once

#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_spec.hpp>

#include "server/support/rrlab_command.hpp"

namespace rrlab::sweep::testing {

inline std::filesystem::path source_dir() { return RRLAB_SOURCE_DIR; }
inline std::filesystem::path scenarios_dir() { return source_dir() / "scenarios"; }

struct TempDir {
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "rrlab-sweep-XXXXXX").string();
    path = mkdtemp(pattern.data());
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return file(name);
  }
  std::filesystem::path path;
};

inline SweepSpec parse_spec(const nlohmann::json& doc) {
  return parse_sweep_spec(doc, {scenarios_dir(), scenarios_dir()});
}

// A small spec: 2 catalogue scenarios × 3 configurations × 2 seeds, 60 steps.
inline nlohmann::json small_spec(const std::string& name = "small") {
  nlohmann::json spec = nlohmann::json::parse(R"({
    "scenarios": ["01_planar7_obstacles", "11_sezgin_ex1_box"],
    "methods": ["pinv", {"name": "dls", "params": {"lambda": [0.02, 0.1]}}],
    "seeds": [1, 2],
    "success": {"max_tracking_error": 0.01, "collision": false, "joint_limits": true},
    "steps": 60})");
  spec["name"] = name;
  return spec;
}

// key -> stored summary without step_us (wall clock), with the verdict and record.
inline std::map<std::string, nlohmann::json> stored_runs(storage::RunStore& store, const std::string& sweep) {
  std::map<std::string, nlohmann::json> out;
  for (const storage::SweepRunEntry& e : store.sweep_runs(sweep)) {
    nlohmann::json summary = nlohmann::json::parse(e.summary_json.value_or("null"));
    summary.erase("step_us");
    const auto run = store.run(e.run_id);
    out[e.row.key] = {{"summary", summary},     {"success", e.row.success}, {"family", e.row.family},
                      {"config", e.row.config_key}, {"scenario_key", e.row.scenario_key}, {"seed", e.seed},
                      {"scenario", run->scenario_json}, {"method", run->method}, {"params", run->params_json}};
  }
  return out;
}

using CommandResult = rrlab::testing::CliRun;
// Runs `rrlab ARGS`, capturing stdout and stderr.
inline CommandResult rrlab(const std::string& args) { return rrlab::testing::run_cli(args); }

}  // namespace rrlab::sweep::testing
