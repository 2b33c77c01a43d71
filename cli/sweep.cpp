// rrlab sweep SPEC.json --db OUT.db: runs a sweep (or its shard), resumable.
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/summaries_csv.hpp>
#include <rrlab/sweep/sweep_runner.hpp>
#include <rrlab/sweep/sweep_shard.hpp>
#include <rrlab/sweep/sweep_spec.hpp>

#include "cli.hpp"

namespace rrlab::cli {

namespace {

std::atomic<bool> stop_requested{false};

extern "C" void request_stop(int) { stop_requested.store(true); }

// SIGINT/SIGTERM ask the workers to stop after their current runs; the
// previous handlers come back when the sweep ends.
class StopOnSignal {
 public:
  StopOnSignal() {
    struct sigaction action {};
    action.sa_handler = request_stop;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~StopOnSignal() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

}  // namespace

int sweep(const SweepOptions& options) {
  using namespace rrlab::sweep;
  try {
    const SweepSpec spec = load_sweep_spec(options.spec_file, find_dir(options.scenarios_dir, "scenarios"));
    const Shard shard = resolve_shard(options.shard, options.shards, [](const char* name) { return std::getenv(name); });
    const std::vector<SweepCase> cases = cases_of_shard(expand_sweep(spec), shard);

    const std::filesystem::path db(options.db);
    if (db.has_parent_path()) std::filesystem::create_directories(db.parent_path());
    storage::RunStore store(options.db);

    RunnerOptions runner;
    runner.jobs = options.jobs;
    runner.frames = options.frames;
    runner.stop = &stop_requested;
    runner.progress = &std::cerr;
    runner.progress_terminal = ::isatty(STDERR_FILENO) == 1;
    RunnerOutcome outcome;
    {
      StopOnSignal signals;
      outcome = run_sweep(spec, cases, store, runner);
    }

    if (options.out_csv) {
      std::ofstream out(*options.out_csv);
      if (!out) throw ScenarioError("--out", "cannot write '" + *options.out_csv + "'");
      write_summaries_csv(out, cases, store.sweep_runs(spec.name));
    }
    const nlohmann::json result = {{"sweep", spec.name},
                                   {"shard", std::to_string(shard.index) + "/" + std::to_string(shard.count)},
                                   {"runs", outcome.cases},
                                   {"already_stored", outcome.already_stored},
                                   {"stored", outcome.stored},
                                   {"failed", outcome.failures.size()},
                                   {"interrupted", outcome.interrupted}};
    nlohmann::json shown = result;
    if (!outcome.storage_stopped.empty()) shown["stopped"] = outcome.storage_stopped;
    std::cout << shown.dump() << '\n';
    for (const std::string& failure : outcome.failures) std::cerr << "rrlab: sweep: run failed: " << failure << '\n';
    if (!outcome.storage_stopped.empty()) {
      std::cerr << "rrlab: sweep stopped: " << outcome.storage_stopped << " (" << outcome.already_stored + outcome.stored
                << " of " << outcome.cases << " runs stored); free room, then run the same command again to resume\n";
      return 1;
    }
    if (outcome.interrupted) {
      std::cerr << "rrlab: sweep interrupted: " << outcome.already_stored + outcome.stored << " of " << outcome.cases
                << " runs stored; run the same command again to resume\n";
      return 130;
    }
    return outcome.failures.empty() ? 0 : 1;
  } catch (const ScenarioError& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace rrlab::cli
