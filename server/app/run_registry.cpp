#include <rrlab/server/app/run_registry.hpp>

#include <algorithm>
#include <chrono>

#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/app/replay_player.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

using nlohmann::json;

RunRegistry::RunRegistry(storage::RunStore& store, const Quotas& quotas) : store_(store), quotas_(quotas) {}

// Every run, replay and job told to stop, then waited for: once this returns
// no thread of theirs uses the store, the writer or the I/O context.
void RunRegistry::stop_all() {
  stopping_ = true;
  std::vector<std::shared_ptr<RunGroup>> groups;
  std::vector<std::shared_ptr<ReplayPlayer>> players;
  {
    std::lock_guard lock(mutex_);
    groups = groups_;
    for (auto& [id, player] : replays_) players.push_back(player);
    players.insert(players.end(), retired_.begin(), retired_.end());
  }
  for (auto& g : groups) g->request_stop();
  for (auto& p : players) p->stop();
  for (auto& g : groups) g->wait_exited();
  for (auto& p : players) p->wait_exited();
  std::unique_lock lock(mutex_);
  jobs_done_.wait(lock, [&] { return jobs_ == 0; });
}

int RunRegistry::active_locked() const {
  int active = jobs_;
  for (const auto& g : groups_) active += g->finished() ? 0 : g->lane_count();
  return active;
}

void RunRegistry::begin_job(std::int64_t source_run) {
  std::lock_guard lock(mutex_);
  if (stopping_ || active_locked() >= quotas_.max_active_runs)
    throw DomainError(Problem::busy, "busy",
                      "at most " + std::to_string(quotas_.max_active_runs) +
                          " runs and re-simulations may be active at once");
  if (deleting_.count(source_run))
    throw DomainError(Problem::conflict, "wrong_state", "run " + std::to_string(source_run) + " is being deleted");
  ++jobs_;
  if (source_run != 0) job_sources_.insert(source_run);
}

void RunRegistry::done_reading(std::int64_t source_run) {
  if (source_run == 0) return;
  std::lock_guard lock(mutex_);
  if (auto it = job_sources_.find(source_run); it != job_sources_.end()) job_sources_.erase(it);
}

void RunRegistry::end_job() {
  // notified under the lock: once stop_all() sees jobs_ == 0 the registry may
  // be destroyed, condition variable included (ThreadSanitizer caught a
  // notify after the unlock racing with its destruction at shutdown)
  std::lock_guard lock(mutex_);
  --jobs_;
  jobs_done_.notify_all();
}

void RunRegistry::prune_locked() {
  // keep unfinished groups, and the newest finished ones
  int finished = 0;
  for (auto it = groups_.rbegin(); it != groups_.rend(); ++it)
    if ((*it)->finished()) ++finished;
  for (auto it = groups_.begin(); it != groups_.end() && finished > quotas_.max_kept_finished;) {
    if ((*it)->finished()) {
      it = groups_.erase(it);
      --finished;
    } else {
      ++it;
    }
  }
}

// An address's live runs beyond Quotas::max_live_per_address: its oldest
// unwatched one ends for the new one; too_many when every one is watched.
std::shared_ptr<RunGroup> RunRegistry::live_to_supersede_locked(const std::string& owner) {
  std::vector<std::shared_ptr<RunGroup>> own;
  for (const auto& g : groups_)  // those already ending (superseded a moment ago, abandoned, stopped) are not counted
    if (g->live() && !g->finished() && !g->ending() && g->owner() == owner) own.push_back(g);
  if (int(own.size()) < quotas_.max_live_per_address) return nullptr;
  for (const auto& g : own)  // oldest first
    if (!g->watched()) return g;
  throw DomainError(Problem::too_many, "too_many_live_runs",
                    "this address holds " + std::to_string(own.size()) + " live runs, every one watched; at most " +
                        std::to_string(quotas_.max_live_per_address) +
                        " (serve --max-live-per-address): stop one first",
                    "", {{"limit", "max_live_per_address"}, {"allowed", quotas_.max_live_per_address}});
}

std::shared_ptr<RunGroup> RunRegistry::make_room(const GroupOptions& options, int lanes) {
  std::lock_guard lock(mutex_);
  prune_locked();
  if (stopping_ || active_locked() + lanes > quotas_.max_active_runs)
    throw DomainError(Problem::busy, "busy",
                      "at most " + std::to_string(quotas_.max_active_runs) +
                          " runs may be active at once; stop or wait for some");
  return options.mode == RunMode::live ? live_to_supersede_locked(options.owner) : nullptr;
}

void RunRegistry::add(std::shared_ptr<RunGroup> group) {
  std::lock_guard lock(mutex_);
  groups_.push_back(std::move(group));
}

std::shared_ptr<RunGroup> RunRegistry::group_of(std::int64_t id, int& lane) {
  std::lock_guard lock(mutex_);
  for (const auto& g : groups_) {
    lane = g->lane_of(id);
    if (lane < 0) continue;
    g->touch();  // every REST call and WebSocket connection for a run goes through here
    return g;
  }
  return nullptr;
}

json RunRegistry::delete_run(std::int64_t id) {
  const std::string run_name = "run " + std::to_string(id);
  {
    std::lock_guard lock(mutex_);
    const auto run = store_.run(id);
    if (!run) {
      if (store_.delete_run(id)) return {{"deleted", id}};  // a deletion a full disk interrupted, finished now
      throw DomainError(Problem::not_found, "not_found", "no " + run_name, "id");
    }
    std::shared_ptr<RunGroup> ended_group;  // dropped from memory once deleted, if it holds this run alone
    for (const auto& group : groups_) {
      if (group->lane_of(id) < 0) continue;
      if (!group->finished())
        throw DomainError(Problem::conflict, "wrong_state", run_name + " is live (" + run->status + "); stop it first",
                          "id");
      if (group->lane_count() == 1) ended_group = group;
    }
    if (job_sources_.count(id))
      throw DomainError(Problem::conflict, "wrong_state",
                        run_name + " is being re-simulated; delete it once that has finished", "id");
    std::vector<std::int64_t> idle_replays;
    for (const auto& [replay_id, player] : replays_) {
      if (player->run_id() != id) continue;
      if (player->playing())
        throw DomainError(Problem::conflict, "wrong_state",
                          run_name + " is being replayed (replay " + std::to_string(replay_id) + "); pause it first",
                          "id");
      idle_replays.push_back(replay_id);
    }
    const std::optional<RunStatus> status = parse_run_status(run->status);
    if (status == RunStatus::running || status == RunStatus::paused)
      throw DomainError(Problem::conflict, "wrong_state",
                        run_name + " is still being written (" + run->status +
                            "): a re-simulation or another process; a restart marks a crashed one interrupted",
                        "id");
    if (deleting_.count(id))
      throw DomainError(Problem::conflict, "wrong_state", run_name + " is being deleted already", "id");
    if (ended_group) std::erase(groups_, ended_group);
    // paused or ended replays of it close: their seeks would find no frames
    for (const std::int64_t replay_id : idle_replays) {
      replays_[replay_id]->stop();
      retired_.push_back(replays_[replay_id]);
      replays_.erase(replay_id);
    }
    // from here until the rows are gone, replays and re-simulations of it are refused
    deleting_.insert(id);
  }
  bool deleted = false;
  try {
    deleted = store_.delete_run(id);
  } catch (...) {
    std::lock_guard lock(mutex_);
    deleting_.erase(id);
    throw;
  }
  {
    std::lock_guard lock(mutex_);
    deleting_.erase(id);
  }
  if (!deleted) throw DomainError(Problem::not_found, "not_found", "no " + run_name, "id");
  return {{"deleted", id}};
}

std::int64_t RunRegistry::add_replay(std::shared_ptr<ReplayPlayer> player, const std::string& owner) {
  std::lock_guard lock(mutex_);
  if (deleting_.count(player->run_id()))
    throw DomainError(Problem::conflict, "wrong_state", "run " + std::to_string(player->run_id()) + " is being deleted");
  std::erase_if(retired_, [](const auto& p) { return p->exited(); });
  constexpr auto kConnecting = std::chrono::seconds(10);  // a new replay's client gets this long to connect
  // Ends the oldest replay (of `only` when given) that nobody watches; false when there is none.
  const auto end_oldest_unwatched = [&](const std::string* only) {
    for (auto it = replays_.begin(); it != replays_.end(); ++it) {  // ids grow: oldest first
      if ((only && it->second->owner() != *only) || it->second->in_use(kConnecting)) continue;
      it->second->stop();
      retired_.push_back(it->second);
      replays_.erase(it);
      return true;
    }
    return false;
  };
  const auto owned = [&] {
    return std::count_if(replays_.begin(), replays_.end(), [&](const auto& r) { return r.second->owner() == owner; });
  };
  while (owned() >= quotas_.max_replays_per_client)
    if (!end_oldest_unwatched(&owner))
      throw DomainError(Problem::too_many, "too_many_replays",
                        "this client has " + std::to_string(quotas_.max_replays_per_client) +
                            " replays with a viewer (or made in the last 10 s and not yet connected to); close one first");
  while (int(replays_.size()) >= quotas_.max_replays)
    if (!end_oldest_unwatched(nullptr))
      throw DomainError(Problem::busy, "busy",
                        "every replay slot (" + std::to_string(quotas_.max_replays) + ") has a viewer");
  const std::int64_t id = next_replay_++;
  player->set_id(id);
  player->set_owner(owner);
  replays_[id] = std::move(player);
  return id;
}

std::shared_ptr<ReplayPlayer> RunRegistry::replay(std::int64_t id) {
  std::lock_guard lock(mutex_);
  auto it = replays_.find(id);
  return it == replays_.end() ? nullptr : it->second;
}

}  // namespace rrlab::server
