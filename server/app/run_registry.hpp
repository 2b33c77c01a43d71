// The run registry: what the server has in memory and running. The live and
// recently finished run groups, the replays, the background jobs
// (re-simulations, sweep workers) with the stored runs they read, and the
// runs being deleted. Its limits: the active runs (busy beyond), a live run
// per owner (the oldest unwatched one ends for a new one), replays per
// client and in all.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include <rrlab/server/app/run_group.hpp>
#include <rrlab/storage/quotas.hpp>

namespace rrlab::storage {
class RunStore;
}

namespace rrlab::server {

class ReplayPlayer;

class RunRegistry {
 public:
  RunRegistry(storage::RunStore& store, const Quotas& quotas);

  // Room for a new group of `lanes` lanes: busy beyond the active runs (or
  // while stopping); a live one beyond its owner's live runs returns the
  // owner's oldest unwatched one, for the caller to supersede once the new
  // group is made (too_many when all are watched).
  std::shared_ptr<RunGroup> make_room(const GroupOptions& options, int lanes);
  void add(std::shared_ptr<RunGroup> group);
  // The group holding run `id` (and its lane), or null when it is not in memory.
  std::shared_ptr<RunGroup> group_of(std::int64_t id, int& lane);

  // Deletes a stored run with its frames and events: {"deleted": id}.
  // not_found if unknown; conflict while it is live, a replay of it plays, it
  // is re-simulated (or being written as a re-simulation or by another
  // process). Its paused or ended replays are closed.
  nlohmann::json delete_run(std::int64_t id);

  // Registers a replay started by `owner` (its client name, or "@ADDRESS";
  // its id set before anyone can see it) and returns the id: beyond the
  // owner's share its own oldest unwatched replay ends, beyond the total the
  // oldest unwatched one; a replay with a WebSocket client, or made in the
  // last 10 s and not yet connected to, is never ended for another.
  // too_many / busy when nothing can end.
  std::int64_t add_replay(std::shared_ptr<ReplayPlayer> player, const std::string& owner);
  std::shared_ptr<ReplayPlayer> replay(std::int64_t id);

  // Background jobs (re-simulations of source_run): counted against the
  // active-run limit, told to stop and waited for by stop_all(); the source
  // cannot be deleted until the job calls done_reading (before it answers, so
  // that a client may delete the run once it has the answer). source_run 0:
  // a job that reads no stored run (a sweep's worker). begin_job throws busy.
  void begin_job(std::int64_t source_run);
  void done_reading(std::int64_t source_run);
  void end_job();

  bool stopping() const { return stopping_; }
  // Stops every run, replay and job and waits until their threads are done.
  void stop_all();

 private:
  void prune_locked();
  int active_locked() const;  // unfinished runs (lanes) and jobs
  std::shared_ptr<RunGroup> live_to_supersede_locked(const std::string& owner);

  storage::RunStore& store_;
  const Quotas quotas_;
  std::mutex mutex_;
  std::condition_variable jobs_done_;
  int jobs_ = 0;
  std::multiset<std::int64_t> job_sources_;  // runs that jobs are reading
  std::set<std::int64_t> deleting_;          // runs whose rows are being deleted (outside the lock)
  std::atomic<bool> stopping_{false};
  std::vector<std::shared_ptr<RunGroup>> groups_;
  std::map<std::int64_t, std::shared_ptr<ReplayPlayer>> replays_;
  std::vector<std::shared_ptr<ReplayPlayer>> retired_;  // evicted, their threads ending
  std::int64_t next_replay_ = 1;
};

}  // namespace rrlab::server
