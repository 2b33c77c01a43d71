// One sweep case run to the end and described for storage: the scenario as
// run (generated if need be, with the case's seed and method configuration
// written into its JSON so the stored record reproduces it), its summary,
// the success verdict and, on request, its frames.
#pragma once

#include <atomic>
#include <memory>

#include <rrlab/sim/frame.hpp>
#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_expansion.hpp>

namespace rrlab::sweep {

struct CaseResult {
  storage::FinishedRun run;
  storage::SweepRunRow row;
  Summary summary;
};

// Case `index` of a generated entry. The last 16 made are kept (process-wide,
// thread-safe), so the runs of one case do not generate it again.
std::shared_ptr<const Scenario> generated_case(const ScenarioEntry& entry, int index);

// The scenario of a case: the file's or the generated one, with the case's
// seed and method configuration (parameters not set keep the method's
// defaults; the scenario's own method parameters do not carry over).
Scenario scenario_of_case(const SweepSpec& spec, const SweepCase& c);
// The configuration's method and the parameters it sets (the others keep
// their defaults) on `scenario`; its JSON record is left as it is.
void use_method_config(Scenario& scenario, const MethodConfig& config);

// Throws what the engine throws (ScenarioError, ParamError) for a case it
// cannot run, and RunInterrupted once `stop` (may be null) is set.
CaseResult run_case(const SweepSpec& spec, const SweepCase& c, bool with_frames,
                    const std::atomic<bool>* stop = nullptr);

}  // namespace rrlab::sweep
