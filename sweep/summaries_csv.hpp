// `rrlab sweep --out FILE`: one CSV row per stored run of the given cases, in
// expansion order: key, scenario_key, config, family, seed, success, run id
// and the summary's numbers (step_us last: wall clock, not deterministic).
#pragma once

#include <ostream>
#include <vector>

#include "storage/run_store.hpp"
#include "sweep/sweep_expansion.hpp"

namespace rrlab::sweep {

void write_summaries_csv(std::ostream& out, const std::vector<SweepCase>& cases,
                         const std::vector<storage::SweepRunEntry>& stored);

}  // namespace rrlab::sweep
