// Runs a sweep's cases on worker threads, each run with its own simulator,
// storing every finished run whole (run, summary, sweep row and, on request,
// frames: one transaction). Runs whose key is stored already are skipped, so
// a second invocation resumes; a stop request ends each worker's current run
// between two of its steps (unstored: a resumed sweep runs it again) and
// starts no other.
#pragma once

#include <atomic>
#include <ostream>
#include <string>
#include <vector>

#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_expansion.hpp>

namespace rrlab::sweep {

struct RunnerOptions {
  int jobs = 0;  // 0: std::thread::hardware_concurrency()
  bool frames = false;
  const std::atomic<bool>* stop = nullptr;  // set (e.g. by SIGINT) to stop within a step of each run
  std::ostream* progress = nullptr;         // progress lines (sweep_progress.hpp), none when null
  bool progress_terminal = false;           // redraw one line in place
};

struct RunnerOutcome {
  size_t cases = 0;           // given
  size_t already_stored = 0;  // skipped: stored by an earlier invocation
  size_t stored = 0;          // run and stored now
  std::vector<std::string> failures;  // "KEY: message", runs that could not be built or run
  bool interrupted = false;   // stopped before every case was stored
  // Set when a run could not be stored for lack of room ("disk full") or a
  // read-only database ("database read-only"): the sweep stopped at that run
  // (interrupted; what was stored stays, and a later invocation resumes).
  std::string storage_stopped;
};

RunnerOutcome run_sweep(const SweepSpec& spec, const std::vector<SweepCase>& cases, storage::RunStore& store,
                        const RunnerOptions& options);

// Keys of `cases` not stored yet for the sweep, in expansion order.
std::vector<SweepCase> pending_cases(const SweepSpec& spec, const std::vector<SweepCase>& cases,
                                     storage::RunStore& store);

}  // namespace rrlab::sweep
