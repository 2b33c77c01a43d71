// Merges a shard's database into another: every sweep run (run, frames,
// events, sweep_runs row) whose (sweep, key) the target lacks is copied under
// a new run id; the others are left alone, so merging twice, or shards that
// overlap, adds nothing twice. Runs that belong to no sweep are not copied.
#pragma once

#include <cstddef>

#include <rrlab/storage/run_store.hpp>

namespace rrlab::sweep {

struct MergeOutcome {
  size_t copied = 0, already_present = 0;
};

MergeOutcome merge_sweep_runs(storage::RunStore& into, storage::RunStore& from);

}  // namespace rrlab::sweep
