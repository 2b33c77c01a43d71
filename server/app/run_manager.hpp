// The server's state: the scenario catalogue (files of scenarios/ plus those
// added over REST, stored in the database), the live run groups and replays.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <rrlab/server/app/run_group.hpp>
#include <rrlab/server/routes/api.hpp>
#include <rrlab/storage/quotas.hpp>

namespace rrlab::storage {
class RunStore;
class FrameWriter;
}  // namespace rrlab::storage

namespace rrlab::server {

class SweepJobs;

class ReplayPlayer;

// Every limit is a `serve` option (cli/main.cpp). A request beyond a
// per-run limit is 413 "run_too_large", beyond a total 507 "storage_quota";
// the error names the limit ("limit") and the numbers ("requested",
// "allowed", and what is stored).
struct ServerLimits : Quotas {
  double default_display_hz = 60;
};

// A run's cost estimate: DOF x (obstacles + 1) x steps x the method's factor
// (the +1: a run without obstacles still costs its kinematics; obstacles and
// the factor: methods/step_cost.hpp).
double run_cost(const LaneEstimate& lane);

class RunManager {
 public:
  RunManager(storage::RunStore& store, storage::FrameWriter& writer, const std::string& scenarios_dir,
             ServerLimits limits = {});
  ~RunManager();  // stops every run and waits for them

  storage::RunStore& store() { return store_; }
  storage::FrameWriter& writer() { return writer_; }
  const ServerLimits& limits() const { return limits_; }

  // Scenarios: by catalogue name (file stem or its "name"), or inline JSON.
  // The list: {"scenarios": [summary...], "total", "offset", "limit"}, files
  // of scenarios/ first (by stem), then stored ones (by name); a summary is
  // {name, title, description (at most 200 characters), source, builtin,
  // kind, dof, obstacles, bytes} (bytes: the scenario's JSON text).
  nlohmann::json scenario_list(std::int64_t limit, std::int64_t offset);
  nlohmann::json scenario_json(const std::string& name);      // 404 if unknown
  nlohmann::json add_scenario(const nlohmann::json& body);    // 201 body; 409 if it exists
  // {"valid": true, name, dof, ...} for a scenario a run would accept (422 naming the path otherwise).
  nlohmann::json validate_scenario(const nlohmann::json& body);
  Scenario resolve_scenario(const nlohmann::json& value, const std::string& path);

  // 503 storage_full/storage_readonly while a write fault lasts (a probe
  // write decides whether it still does).
  void check_writable();
  // A new group, registered and started. Refuses (before storing anything)
  // a request beyond the per-run limits, the cost limit or the total bytes;
  // a live one beyond its owner's live runs ends the owner's oldest unwatched
  // one (429 when all are watched).
  std::shared_ptr<RunGroup> start_group(const std::vector<Scenario>& lanes, const GroupOptions& options);
  // The group holding run `id` (and its lane), or null when it is not in memory.
  std::shared_ptr<RunGroup> group_of(std::int64_t id, int& lane);

  // Deletes a stored run with its frames and events: {"deleted": id}. 404 if
  // unknown; 409 while it is live, a replay of it plays, it is re-simulated
  // (or being written as a re-simulation or by another process). Its paused
  // or ended replays are closed.
  nlohmann::json delete_run(std::int64_t id);

  // Admits work that is not a run group (a re-simulation, a sweep) against
  // the same quotas as runs: 413 / 507 as for runs. Returns the frame bytes it
  // reserved of --max-total-bytes, for release_reserved() as its frames are stored.
  std::int64_t admit_work(const std::vector<LaneEstimate>& lanes, bool frames);
  void release_reserved(std::int64_t bytes);

  // Registers a replay started by `owner` (its client name, or "@ADDRESS";
  // its id set before anyone can see it) and returns the id: beyond the
  // owner's share its own oldest unwatched replay ends, beyond the total the
  // oldest unwatched one; a replay with a WebSocket client, or made in the
  // last 10 s and not yet connected to, is never ended for another. 429 / 503
  // when nothing can end.
  std::int64_t add_replay(std::shared_ptr<ReplayPlayer> player, const std::string& owner);
  // Background jobs (re-simulations of source_run): counted against the
  // active-run limit, told to stop and waited for by stop_all(); the source
  // cannot be deleted until the job calls done_reading (before it answers, so
  // that a client may delete the run once it has the answer). source_run 0:
  // a job that reads no stored run (a sweep). begin_job throws ApiError 503.
  void begin_job(std::int64_t source_run);
  void done_reading(std::int64_t source_run);
  void end_job();
  bool stopping() const { return stopping_; }
  std::shared_ptr<ReplayPlayer> replay(std::int64_t id);

  void stop_all();

  // Sweeps started over REST (POST /api/sweeps).
  SweepJobs& sweeps() { return *sweeps_; }

 private:
  void prune_locked();
  // Checks `lanes` against the quotas and reserves their frame bytes; `frames`
  // false: they store summaries only (no per-run frame limits apply).
  // `window` > 0: each lane reserves at most that many bytes (a live lane's window ahead).
  std::vector<std::int64_t> admit(const std::vector<LaneEstimate>& lanes, bool frames = true,
                                  std::int64_t window = 0);  // under start_mutex_
  std::shared_ptr<RunGroup> make_room_for_live_locked(const std::string& owner);
  nlohmann::json scenario_summary(const std::string& name, const nlohmann::json& doc, bool builtin);
  int active_locked() const;  // unfinished runs (lanes) and jobs

  storage::RunStore& store_;
  storage::FrameWriter& writer_;
  ServerLimits limits_;
  std::map<std::string, nlohmann::json> catalogue_;  // file scenarios by stem and by name
  std::vector<std::string> catalogue_names_;         // file stems, sorted
  std::mutex mutex_, start_mutex_;
  std::condition_variable jobs_done_;
  int jobs_ = 0;
  std::multiset<std::int64_t> job_sources_;  // runs that jobs are reading
  std::set<std::int64_t> deleting_;          // runs whose rows are being deleted (outside the lock)
  std::atomic<bool> stopping_{false};
  std::vector<std::shared_ptr<RunGroup>> groups_;
  std::map<std::int64_t, std::shared_ptr<ReplayPlayer>> replays_;
  std::vector<std::shared_ptr<ReplayPlayer>> retired_;  // evicted, their threads ending
  std::int64_t next_replay_ = 1;
  std::unique_ptr<SweepJobs> sweeps_;
  StorageBudget budget_;
  std::mutex summaries_mutex_;
  std::map<std::string, nlohmann::json> stored_summaries_;  // stored scenarios never change: computed once
};

}  // namespace rrlab::server
