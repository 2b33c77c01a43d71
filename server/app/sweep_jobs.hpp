// Sweeps started over REST (POST /api/sweeps): each runs on its own thread at
// a lower CPU priority (nice 10, inherited by its workers), counted against the
// server's active-run limit with one slot per worker, into the server's own
// database, so live runs keep their share of the cores. The routes parse the
// spec (over REST it names catalogue scenarios and generators only, never a
// file path); these limits hold for any spec.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include <rrlab/server/app/run_types.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::sweep {
struct SweepSpec;
}

namespace rrlab::server {

class RunManager;

// One stored sweep run as GET /api/sweeps/{id}/runs lists it (its summary's
// headline fields, its case's difficulty).
nlohmann::json sweep_run_json(const storage::SweepRunEntry& entry);

class SweepJobs {
 public:
  explicit SweepJobs(RunManager& runs);
  ~SweepJobs();  // stop_all()

  // Checks the spec against the limits of a sweep started over REST
  // (unprocessable beyond) and the run quotas (admission), starts it: {id,
  // name, total, status, ...}. `jobs`: worker threads, at most the cores less
  // one (one stays for live runs).
  nlohmann::json start(sweep::SweepSpec spec, int jobs);
  // The checks of start() without starting: {valid, name, total, scenario_entries, configurations}.
  nlohmann::json validate(sweep::SweepSpec spec);
  // Progress; once ended, the report of the sweep's stored runs (JSON text).
  // not_found if unknown. The report is built once when the sweep ends, off the
  // I/O threads, and kept for the last kMaxCachedReports sweeps (an older
  // one is built again when asked for).
  std::string status(std::int64_t id);
  nlohmann::json list();
  // One page of a sweep's stored runs, filtered (a report cell's runs).
  struct RunQuery {
    std::optional<std::string> family, config, failure_mode;
    std::optional<bool> success;  // passed or failed runs only
    std::int64_t limit = 100, offset = 0;
    storage::RunStore::SweepRunFilter filter() const;
  };
  nlohmann::json runs(std::int64_t id, const RunQuery& query);
  std::string name(std::int64_t id);  // the sweep's name (not_found if unknown)
  // Workers finish their current run; stored runs stay (resumable): {"id", "stopping": true}.
  nlohmann::json stop(std::int64_t id);
  // Stops every sweep and waits for their threads (server shutdown).
  void stop_all();
  // Reports (and stored counts) of ended sweeps named `name` (all: none) are
  // built again when next asked for: their stored runs changed (a delete, a resume).
  void forget_reports(const std::optional<std::string>& name);
  // Server shutdown, first step: every sweep told to stop and every report
  // build abandoned, without waiting (so that the worker pool can be joined at once).
  void interrupt();

 private:
  struct Job;
  void admit(const sweep::SweepSpec& spec);
  std::shared_ptr<Job> find(std::int64_t id);  // not_found if unknown
  std::shared_ptr<Job> prepare(sweep::SweepSpec spec);  // limited and admitted (its cost against the run quotas), not expanded
  nlohmann::json progress_of(Job& job);
  // The ended sweep's report, from the cache or built (one build at a
  // time per sweep); null when a shutdown interrupted the build.
  // `wait` false: busy when another caller is building it.
  std::shared_ptr<const std::string> report_of(const std::shared_ptr<Job>& job, bool wait);

  RunManager& runs_;
  std::mutex mutex_;
  std::map<std::int64_t, std::shared_ptr<Job>> jobs_;
  std::int64_t next_id_ = 1;
  std::mutex cache_mutex_;  // guards cached_reports_ (never held with mutex_)
  std::deque<std::shared_ptr<Job>> cached_reports_;  // newest last, at most kMaxCachedReports
  std::atomic<bool> interrupted_{false};
};

}  // namespace rrlab::server
