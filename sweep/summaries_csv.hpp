// `rrlab sweep --out FILE`: one CSV row per stored run of the given cases, in
// expansion order: key, scenario_key, config, family, seed, success, the
// first failure's mode and time, run id, the summary's numbers (smoothness
// included: empty where the run was too short for it), the case's
// difficulty (generated cases) and step_us last (wall clock, not deterministic).
#pragma once

#include <ostream>
#include <vector>

#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_expansion.hpp>

namespace rrlab::sweep {

void write_summaries_csv(std::ostream& out, const std::vector<SweepCase>& cases,
                         const std::vector<storage::SweepRunEntry>& stored);

}  // namespace rrlab::sweep
