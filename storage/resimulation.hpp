// Re-simulation of a stored run: a fresh simulator from the run's scenario,
// method, parameters and seed, with the recorded events applied before the
// same steps; every frame is compared byte for byte with the stored one.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/frame.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::storage {

// The scenario a stored run started from (its method and parameters included).
Scenario scenario_of_run(const RunRecord& run);
// The stored-run description of a simulator about to run `scenario` (the
// inverse of scenario_of_run: its method and parameters as they start).
NewRun new_run_of(const Scenario& scenario, const Simulator& sim, const std::string& mode);

struct ResimulationResult {
  std::int64_t frames_compared = 0;
  std::optional<std::int64_t> first_mismatch;  // seq of the first differing frame
  std::string mismatch;                         // what differed there
  Summary summary;
  // A run that stored no frames but completed steps (a sweep's) is stepped as
  // far as its summary says, and its summary compared instead: every result
  // field (not the step times) must be the same, bit for bit.
  bool summary_compared = false;
  std::string summary_mismatch;  // the first differing field, empty when none
  // A verdict only when frames or a summary were compared: a run that stored
  // nothing to compare is neither identical nor different.
  bool compared() const { return frames_compared > 0 || summary_compared; }
  bool identical() const { return compared() && !first_mismatch && summary_mismatch.empty(); }
};

constexpr const char* kNothingCompared = "the run stored no frames: nothing to compare";

// {identical (null when nothing was compared), compared, frames_compared,
// first_mismatch, mismatch, reason (only when nothing was compared)}: the
// verdict as the CLI and REST report it.
nlohmann::json verification_json(const ResimulationResult& result);

// The steps a run's summary says it completed (0 without a summary or steps;
// at most ScenarioLimits::max_steps × 16, as a re-simulation steps).
std::int64_t summary_steps(const RunRecord& run);

// on_frame (may be empty) sees each re-simulated frame with its seq and packed blob.
ResimulationResult resimulate(RunStore& store, const RunRecord& run,
                              const std::function<void(std::int64_t, const Frame&, const std::string&)>& on_frame);

}  // namespace rrlab::storage
