#include <rrlab/sweep/sweep_runner.hpp>

#include <algorithm>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_set>

#include <rrlab/methods/method.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/database.hpp>
#include <rrlab/sweep/sweep_case.hpp>
#include <rrlab/sweep/sweep_progress.hpp>

namespace rrlab::sweep {

std::vector<SweepCase> pending_cases(const SweepSpec& spec, const std::vector<SweepCase>& cases,
                                     storage::RunStore& store) {
  const std::vector<std::string> keys = store.sweep_keys(spec.name);
  const std::unordered_set<std::string> stored(keys.begin(), keys.end());
  std::vector<SweepCase> out;
  for (const SweepCase& c : cases)
    if (!stored.count(c.key)) out.push_back(c);
  return out;
}

RunnerOutcome run_sweep(const SweepSpec& spec, const std::vector<SweepCase>& cases, storage::RunStore& store,
                        const RunnerOptions& options) {
  RunnerOutcome outcome;
  outcome.cases = cases.size();
  const std::vector<SweepCase> todo = pending_cases(spec, cases, store);
  outcome.already_stored = cases.size() - todo.size();

  int jobs = options.jobs > 0 ? options.jobs : int(std::max(1u, std::thread::hardware_concurrency()));
  jobs = int(std::min<size_t>(size_t(jobs), std::max<size_t>(todo.size(), 1)));

  std::optional<SweepProgress> progress;
  if (options.progress) progress.emplace(*options.progress, options.progress_terminal, cases.size(), outcome.already_stored);

  std::atomic<size_t> next{0}, stored{0};
  std::atomic<bool> storage_failed{false};
  std::mutex failures_mutex;
  const auto stopping = [&] { return storage_failed || (options.stop && options.stop->load()); };
  const auto worker = [&] {
    while (!stopping()) {
      const size_t i = next++;
      if (i >= todo.size()) return;
      try {
        const CaseResult result = run_case(spec, todo[i], options.frames, options.stop);
        if (store.add_sweep_run(result.run, result.row)) ++stored;
      } catch (const RunInterrupted&) {
        return;  // not stored: a resumed sweep runs it again
      } catch (const storage::StorageError& e) {
        // a full disk or a read-only file: every later run would fail the same way, so the
        // sweep stops here (not a failure of this run: a resumed sweep runs it again)
        std::lock_guard lock(failures_mutex);
        if (!e.write_fault()) {
          outcome.failures.push_back(todo[i].key + ": " + e.what());
        } else {
          if (!storage_failed.exchange(true))
            outcome.storage_stopped = e.fault() == storage::StorageFault::full ? "disk full" : "database read-only";
          return;
        }
      } catch (const ParamError& e) {
        std::lock_guard lock(failures_mutex);
        outcome.failures.push_back(todo[i].key + ": method.params." + e.what());
      } catch (const std::exception& e) {
        std::lock_guard lock(failures_mutex);
        outcome.failures.push_back(todo[i].key + ": " + e.what());
      }
      if (progress) progress->run_done();
    }
  };
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();

  if (progress) progress->finish();
  outcome.stored = stored;
  outcome.interrupted = outcome.already_stored + outcome.stored + outcome.failures.size() < cases.size();
  std::sort(outcome.failures.begin(), outcome.failures.end());
  return outcome;
}

}  // namespace rrlab::sweep
