#include <rrlab/server/app/run_manager.hpp>

#include <rrlab/server/app/sweep_jobs.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include <rrlab/server/app/replay_player.hpp>
#include <rrlab/storage/database.hpp>
#include <rrlab/storage/run_store.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

using nlohmann::json;

RunManager::RunManager(storage::RunStore& store, storage::FrameWriter& writer, const std::string& scenarios_dir,
                       ServerLimits limits)
    : store_(store),
      writer_(writer),
      limits_(limits),
      sweeps_(std::make_unique<SweepJobs>(*this, scenarios_dir)),
      budget_(store, writer, limits.max_total_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (scenarios_dir.empty() || !fs::is_directory(scenarios_dir, ec)) return;
  set_scenario_catalogue_dir(scenarios_dir);  // where a URDF robot's "file" is resolved
  for (const auto& entry : fs::directory_iterator(scenarios_dir, ec)) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    try {
      const Scenario scenario = parse_scenario_text(text.str());  // only valid files are served
      const std::string stem = entry.path().stem().string();
      // one name everywhere: a catalogue scenario is named by its file, in
      // the list, in its document and so in the runs stored from it; its
      // inner name still finds it
      nlohmann::json doc = scenario.json;
      doc["name"] = stem;
      catalogue_[stem] = doc;
      catalogue_.emplace(scenario.name, std::move(doc));
      catalogue_names_.push_back(stem);
    } catch (const std::exception&) {
    }
  }
  std::sort(catalogue_names_.begin(), catalogue_names_.end());
}

RunManager::~RunManager() { stop_all(); }

// Stops every run, replay and job and waits until their threads are done
// with the store, the writer and the I/O context.
void RunManager::stop_all() {
  sweeps_->stop_all();  // before stopping_: their workers' slots are jobs stop_all waits for
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

int RunManager::active_locked() const {
  int active = jobs_;
  for (const auto& g : groups_) active += g->finished() ? 0 : g->lane_count();
  return active;
}

double run_cost(const LaneEstimate& lane) {
  return double(lane.dof) * (lane.obstacles + 1) * double(lane.steps) * lane.factor;
}

void RunManager::check_writable() {
  if (!store_.write_fault() || store_.probe_write()) return;
  const auto fault = store_.write_fault();
  if (!fault) return;
  const bool full = fault->fault == storage::StorageFault::full;
  throw ApiError(503, full ? "storage_full" : "storage_readonly",
                 std::string(full ? "the database's disk is full" : "the database cannot be written") +
                     " (" + fault->message + "): no new run is started until " +
                     (full ? "space is freed (delete runs, or free the disk)" : "the file is writable again") +
                     "; stored runs can still be read",
                 "");
}

void RunManager::begin_job(std::int64_t source_run) {
  check_writable();
  std::lock_guard lock(mutex_);
  if (stopping_ || active_locked() >= limits_.max_active_runs)
    throw ApiError(503, "busy", "at most " + std::to_string(limits_.max_active_runs) +
                                    " runs and re-simulations may be active at once", "");
  if (deleting_.count(source_run))
    throw ApiError(409, "wrong_state", "run " + std::to_string(source_run) + " is being deleted", "");
  ++jobs_;
  if (source_run != 0) job_sources_.insert(source_run);
}

void RunManager::done_reading(std::int64_t source_run) {
  if (source_run == 0) return;
  std::lock_guard lock(mutex_);
  if (auto it = job_sources_.find(source_run); it != job_sources_.end()) job_sources_.erase(it);
}

void RunManager::end_job() {
  // notified under the lock: once stop_all() sees jobs_ == 0 the manager may
  // be destroyed, condition variable included (ThreadSanitizer caught a
  // notify after the unlock racing with its destruction at shutdown)
  std::lock_guard lock(mutex_);
  --jobs_;
  jobs_done_.notify_all();
}

namespace {
// A string field of a scenario, cut to `limit` bytes (whole UTF-8 characters,
// then an ellipsis): a list answers summaries, however long a field is.
std::string excerpt(const json& doc, const char* key, const std::string& otherwise, size_t limit) {
  std::string text = doc.contains(key) && doc[key].is_string() ? doc[key].get<std::string>() : otherwise;
  if (text.size() <= limit) return text;
  size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return text.substr(0, cut) + "\u2026";
}
}  // namespace

json RunManager::scenario_summary(const std::string& name, const json& doc, bool builtin) {
  json summary = {{"name", name},
                  {"title", excerpt(doc, "name", name, 128)},
                  {"description", excerpt(doc, "description", "", 200)},
                  {"source", excerpt(doc, "source", "", 200)},
                  {"builtin", builtin},
                  {"kind", nullptr},
                  {"dof", nullptr},
                  {"obstacles", nullptr},
                  {"bytes", doc.dump().size()}};
  try {
    const Scenario scenario = parse_scenario(doc);
    summary["kind"] = to_string(scenario.model.kind);
    summary["dof"] = scenario.model.dof();
    summary["obstacles"] = scenario.scene.obstacles.size();
  } catch (const std::exception&) {
    // stored under older rules: listed, with what the summary cannot say as null
  }
  return summary;
}

json RunManager::scenario_list(std::int64_t limit, std::int64_t offset) {
  const std::vector<std::string> stored = store_.scenario_names();
  const std::int64_t builtin = std::int64_t(catalogue_names_.size());
  const std::int64_t total = builtin + std::int64_t(stored.size());
  json list = json::array();
  for (std::int64_t i = offset; i < total && i < offset + limit; ++i) {
    if (i < builtin) {
      const std::string& stem = catalogue_names_[size_t(i)];
      list.push_back(scenario_summary(stem, catalogue_.at(stem), true));
      continue;
    }
    const std::string& name = stored[size_t(i - builtin)];
    {
      std::lock_guard lock(summaries_mutex_);
      if (auto it = stored_summaries_.find(name); it != stored_summaries_.end()) {
        list.push_back(it->second);
        continue;
      }
    }
    const auto text = store_.scenario(name);
    if (!text) continue;  // deleted meanwhile
    json summary = scenario_summary(name, parse_json(*text), false);
    std::lock_guard lock(summaries_mutex_);
    stored_summaries_[name] = summary;
    list.push_back(std::move(summary));
  }
  return {{"scenarios", list}, {"total", total}, {"offset", offset}, {"limit", limit}};
}

json RunManager::scenario_json(const std::string& name) {
  if (auto it = catalogue_.find(name); it != catalogue_.end()) return it->second;
  if (auto stored = store_.scenario(name)) return parse_json(*stored);
  throw ApiError(404, "not_found", "no scenario \"" + name + "\"", "scenario");
}

namespace {

// A scenario as a run would take it: parsed, and its simulator built (some
// parameters are checked against the arm only there). 422 naming the path.
Scenario checked_scenario(const json& body) {
  try {
    Scenario scenario = parse_scenario(body);
    Simulator check(scenario);
    return scenario;
  } catch (const ParamError& e) {
    const std::string path = e.param() == "method" ? "method.name" : "method.params." + e.param();
    throw ApiError(422, "invalid", path + ": " + e.what(), path);
  } catch (...) {
    rethrow_as_api_error("", 422);
  }
}

}  // namespace

json RunManager::add_scenario(const json& body) {
  if (!body.is_object()) throw ApiError(400, "invalid", "must be a scenario object", "");
  if (!body.contains("name") || !body["name"].is_string())
    throw ApiError(400, "invalid", "a stored scenario needs a string \"name\"", "name");
  const std::string name = body["name"].get<std::string>();
  static const std::regex pattern("[A-Za-z0-9_.-]{1,64}");
  if (!std::regex_match(name, pattern))
    throw ApiError(400, "invalid", "must be 1 to 64 letters, digits, '_', '-' or '.'", "name");
  checked_scenario(body);
  // never replaces: a file of scenarios/ nor one added earlier (runs name their scenario)
  const auto exists = [&] {
    return ApiError(409, "exists", "a scenario \"" + name + "\" exists already; choose another name", "name");
  };
  if (catalogue_.count(name)) throw exists();
  switch (store_.put_scenario(name, body.dump(), limits_.max_scenarios)) {
    case storage::PutScenario::added: break;
    case storage::PutScenario::exists: throw exists();
    case storage::PutScenario::full:
      throw ApiError(507, "storage_quota",
                     "max_scenarios: " + std::to_string(limits_.max_scenarios) +
                         " scenarios are stored, the most this server keeps (serve --max-scenarios); "
                         "this one is not stored",
                     "",
                     {{"limit", "max_scenarios"}, {"stored", store_.scenario_count()}, {"allowed", limits_.max_scenarios}});
  }
  return {{"name", name}};
}

json RunManager::validate_scenario(const json& body) {
  const Scenario scenario = checked_scenario(body);
  const bool exists = catalogue_.count(scenario.name) > 0 || store_.scenario(scenario.name).has_value();
  return {{"valid", true},
          {"name", scenario.name},
          {"exists", exists},
          {"kind", to_string(scenario.model.kind)},
          {"dof", scenario.model.dof()},
          {"links", scenario.model.link_count()},
          {"obstacles", scenario.scene.obstacles.size()},
          {"task", {{"space", to_string(scenario.task.space)}, {"trajectory", to_string(scenario.task.trajectory.type)}}},
          {"method", scenario.method.name},
          {"dt", scenario.dt},
          {"duration", scenario.duration},
          {"steps", scenario.steps()}};
}

Scenario RunManager::resolve_scenario(const json& value, const std::string& path) {
  json doc;
  if (value.is_string()) {
    try {
      doc = scenario_json(value.get<std::string>());
    } catch (const ApiError& e) {
      throw ApiError(404, "not_found", e.what(), path);
    }
  } else if (value.is_object()) {
    doc = value;
  } else {
    throw ApiError(400, "invalid", "must be a scenario name or a scenario object", path);
  }
  try {
    return parse_scenario(doc);
  } catch (...) {
    rethrow_as_api_error(path, 422);
  }
}

void RunManager::prune_locked() {
  // keep unfinished groups, and the newest finished ones
  int finished = 0;
  for (auto it = groups_.rbegin(); it != groups_.rend(); ++it)
    if ((*it)->finished()) ++finished;
  for (auto it = groups_.begin(); it != groups_.end() && finished > limits_.max_kept_finished;) {
    if ((*it)->finished()) {
      it = groups_.erase(it);
      --finished;
    } else {
      ++it;
    }
  }
}

namespace {
std::string mib(std::int64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
  return text;
}
}  // namespace

// The request's cost and storage against the limits, before anything is
// stored or started; reserves each lane's estimated bytes from the budget.
std::int64_t RunManager::admit_work(const std::vector<LaneEstimate>& lanes, bool frames) {
  std::lock_guard start_lock(start_mutex_);
  std::int64_t total = 0;
  for (const std::int64_t bytes : admit(lanes, frames)) total += bytes;
  return total;
}

void RunManager::release_reserved(std::int64_t bytes) { budget_.release(bytes); }

std::vector<std::int64_t> RunManager::admit(const std::vector<LaneEstimate>& lanes, bool frames,
                                            std::int64_t window) {
  double cost = 0;
  std::int64_t bytes = 0;
  std::vector<std::int64_t> reserve;
  for (const LaneEstimate& lane : lanes) {
    cost += run_cost(lane);
    if (!frames) continue;
    if (lane.steps > limits_.max_run_frames)
      throw ApiError(413, "run_too_large",
                     "max_run_frames: " + std::to_string(lane.steps) + " steps would store " +
                         std::to_string(lane.steps) + " frames; a run may store at most " +
                         std::to_string(limits_.max_run_frames) + " (serve --max-run-frames): ask for fewer steps",
                     "steps", {{"limit", "max_run_frames"}, {"requested", lane.steps}, {"allowed", limits_.max_run_frames}});
    const std::int64_t lane_bytes = lane.steps * lane.frame_bytes;
    if (lane_bytes > limits_.max_run_bytes)
      throw ApiError(413, "run_too_large",
                     "max_run_bytes: " + std::to_string(lane.steps) + " frames of " + std::to_string(lane.frame_bytes) +
                         " bytes (" + std::to_string(lane.dof) + " joints) are " + std::to_string(lane_bytes) + " bytes (" +
                         mib(lane_bytes) + "); a run may store at most " + std::to_string(limits_.max_run_bytes) +
                         " (" + mib(limits_.max_run_bytes) + ", serve --max-run-bytes): ask for fewer steps",
                     "steps",
                     {{"limit", "max_run_bytes"}, {"requested", lane_bytes}, {"allowed", limits_.max_run_bytes},
                      {"frames", lane.steps}, {"frame_bytes", lane.frame_bytes}});
    const std::int64_t reserved = window > 0 ? std::min(lane_bytes, window) : lane_bytes;
    bytes += reserved;
    reserve.push_back(reserved);
  }
  if (cost > limits_.max_run_cost) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", cost);
    std::string message = "max_run_cost: the estimate DOF x (obstacles + 1) x steps x method factor";
    const auto number = [](double v) {
      char out[32];
      std::snprintf(out, sizeof out, "%.4g", v);
      return std::string(out);
    };
    if (lanes.size() > 8) message += ", summed over " + std::to_string(lanes.size()) + " runs,";
    else
      for (const LaneEstimate& lane : lanes)
        message += (&lane == &lanes.front() ? " = " : " + ") + std::to_string(lane.dof) + " x (" +
                   number(lane.obstacles) + " + 1) x " + std::to_string(lane.steps) + " x " + number(lane.factor);
    char allowed[64];
    std::snprintf(allowed, sizeof allowed, "%.6g", limits_.max_run_cost);
    throw ApiError(413, "run_too_large",
                   message + " = " + text + " exceeds " + allowed + " (serve --max-run-cost): ask for fewer steps",
                   "steps", {{"limit", "max_run_cost"}, {"requested", cost}, {"allowed", limits_.max_run_cost}});
  }
  const std::int64_t used = budget_.used();
  if (used + bytes > budget_.max())
    throw ApiError(507, "storage_quota",
                   "max_total_bytes: the runs would reserve " + std::to_string(bytes) + " bytes of frames (" + mib(bytes) +
                       ") and the database holds " + std::to_string(used) + " (" + mib(used) +
                       ", stored, queued or reserved by running runs) of at most " + std::to_string(budget_.max()) +
                       " (" + mib(budget_.max()) + ", serve --max-total-bytes): delete runs or ask for fewer steps",
                   "",
                   {{"limit", "max_total_bytes"}, {"requested", bytes}, {"stored", used}, {"allowed", budget_.max()}});
  budget_.reserve(bytes);
  return reserve;
}

// An address's live runs beyond Quotas::max_live_per_address: its oldest
// unwatched one ends for the new one; 429 when every one is watched. Under
// start_mutex_; the one to end is returned, ended by the caller outside mutex_.
std::shared_ptr<RunGroup> RunManager::make_room_for_live_locked(const std::string& owner) {
  std::vector<std::shared_ptr<RunGroup>> own;
  for (const auto& g : groups_)  // those already ending (superseded a moment ago, abandoned, stopped) are not counted
    if (g->live() && !g->finished() && !g->ending() && g->owner() == owner) own.push_back(g);
  if (int(own.size()) < limits_.max_live_per_address) return nullptr;
  for (const auto& g : own)  // oldest first
    if (!g->watched()) return g;
  throw ApiError(429, "too_many_live_runs",
                 "this address holds " + std::to_string(own.size()) + " live runs, every one watched; at most " +
                     std::to_string(limits_.max_live_per_address) +
                     " (serve --max-live-per-address): stop one first",
                 "", {{"limit", "max_live_per_address"}, {"allowed", limits_.max_live_per_address}});
}

std::shared_ptr<RunGroup> RunManager::start_group(const std::vector<Scenario>& lanes, const GroupOptions& requested) {
  check_writable();
  GroupOptions options = requested;
  options.abandon_unwatched = std::chrono::seconds(limits_.abandon_unwatched_s);
  options.abandon_idle = std::chrono::seconds(limits_.abandon_idle_s);
  std::lock_guard start_lock(start_mutex_);  // the limit holds under concurrent starts
  std::shared_ptr<RunGroup> superseded;
  {
    std::lock_guard lock(mutex_);
    prune_locked();
    if (stopping_ || active_locked() + int(lanes.size()) > limits_.max_active_runs)
      throw ApiError(503, "busy", "at most " + std::to_string(limits_.max_active_runs) +
                                      " runs may be active at once; stop or wait for some", "");
    if (options.mode == "live") superseded = make_room_for_live_locked(options.owner);
  }
  // a live lane reserves at most a window of what it will store, not its whole duration
  const std::int64_t window = options.mode == "live" ? limits_.live_reserve_bytes : 0;
  RunServices services{store_, writer_, limits_.max_run_frames, limits_.max_run_bytes, &budget_,
                       [this, window](const std::vector<LaneEstimate>& estimates) { return admit(estimates, true, window); }};
  auto group = std::make_shared<RunGroup>(services, lanes, options);  // a refused request ends no other run
  if (superseded) superseded->supersede();
  group->start();  // registered only once its thread runs
  std::lock_guard lock(mutex_);
  groups_.push_back(group);
  return group;
}

std::shared_ptr<RunGroup> RunManager::group_of(std::int64_t id, int& lane) {
  std::lock_guard lock(mutex_);
  for (const auto& g : groups_) {
    lane = g->lane_of(id);
    if (lane < 0) continue;
    g->touch();  // every REST call and WebSocket connection for a run goes through here
    return g;
  }
  return nullptr;
}

json RunManager::delete_run(std::int64_t id) {
  const std::string run_name = "run " + std::to_string(id);
  {
    std::lock_guard lock(mutex_);
    const auto run = store_.run(id);
    if (!run) {
      if (store_.delete_run(id)) return {{"deleted", id}};  // a deletion a full disk interrupted, finished now
      throw ApiError(404, "not_found", "no " + run_name, "id");
    }
    std::shared_ptr<RunGroup> ended_group;  // dropped from memory once deleted, if it holds this run alone
    for (const auto& group : groups_) {
      if (group->lane_of(id) < 0) continue;
      if (!group->finished())
        throw ApiError(409, "wrong_state", run_name + " is live (" + run->status + "); stop it first", "id");
      if (group->lane_count() == 1) ended_group = group;
    }
    if (job_sources_.count(id))
      throw ApiError(409, "wrong_state", run_name + " is being re-simulated; delete it once that has finished", "id");
    std::vector<std::int64_t> idle_replays;
    for (const auto& [replay_id, player] : replays_) {
      if (player->run_id() != id) continue;
      if (player->playing())
        throw ApiError(409, "wrong_state",
                       run_name + " is being replayed (replay " + std::to_string(replay_id) + "); pause it first",
                       "id");
      idle_replays.push_back(replay_id);
    }
    if (run->status == "running" || run->status == "paused")
      throw ApiError(409, "wrong_state",
                     run_name + " is still being written (" + run->status +
                         "): a re-simulation or another process; a restart marks a crashed one interrupted",
                     "id");
    if (deleting_.count(id)) throw ApiError(409, "wrong_state", run_name + " is being deleted already", "id");
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
  if (!deleted) throw ApiError(404, "not_found", "no " + run_name, "id");
  sweeps_->forget_reports(std::nullopt);  // it may have been a sweep's run: reports are built again
  return {{"deleted", id}};
}

std::int64_t RunManager::add_replay(std::shared_ptr<ReplayPlayer> player, const std::string& owner) {
  std::lock_guard lock(mutex_);
  if (deleting_.count(player->run_id()))
    throw ApiError(409, "wrong_state", "run " + std::to_string(player->run_id()) + " is being deleted", "");
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
  while (owned() >= limits_.max_replays_per_client)
    if (!end_oldest_unwatched(&owner))
      throw ApiError(429, "too_many_replays",
                     "this client has " + std::to_string(limits_.max_replays_per_client) +
                         " replays with a viewer (or made in the last 10 s and not yet connected to); close one first",
                     "");
  while (int(replays_.size()) >= limits_.max_replays)
    if (!end_oldest_unwatched(nullptr))
      throw ApiError(503, "busy", "every replay slot (" + std::to_string(limits_.max_replays) + ") has a viewer", "");
  const std::int64_t id = next_replay_++;
  player->set_id(id);
  player->set_owner(owner);
  replays_[id] = std::move(player);
  return id;
}

std::shared_ptr<ReplayPlayer> RunManager::replay(std::int64_t id) {
  std::lock_guard lock(mutex_);
  auto it = replays_.find(id);
  return it == replays_.end() ? nullptr : it->second;
}

}  // namespace rrlab::server
