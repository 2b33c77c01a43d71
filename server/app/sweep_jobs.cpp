#include "app/sweep_jobs.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "routes/api.hpp"
#include "app/run_manager.hpp"
#include "app/thread_priority.hpp"
#include "scenario/scenario.hpp"
#include "sweep/sweep_case.hpp"
#include "sweep/sweep_expansion.hpp"
#include "sweep/sweep_report.hpp"
#include "sweep/sweep_report_json.hpp"
#include "sweep/sweep_runner.hpp"
#include "sweep/sweep_spec.hpp"
#include "storage/run_store.hpp"

namespace rrlab::server {

using nlohmann::json;

namespace {

// Stored JSON text as JSON; null when absent or not JSON (an unquoted string
// from json_extract, a row written by an older rrlab): never a discarded value.
json parsed_or_null(const std::optional<std::string>& text) {
  if (!text) return json();
  json value = json::parse(*text, nullptr, false);
  return value.is_discarded() ? json() : value;
}

constexpr size_t kMaxRunsPerSweep = 100'000;
constexpr size_t kMaxGeneratorEntries = 64;
constexpr int kMaxRunningSweeps = 4;
constexpr size_t kMaxKeptSweeps = 64;  // finished ones beyond this are forgotten (their runs stay stored)

// Over REST a scenario entry is a catalogue name or a generator: never a path.
void refuse_paths(const json& spec) {
  if (!spec.is_object() || !spec.contains("scenarios") || !spec["scenarios"].is_array()) return;
  const json& list = spec["scenarios"];
  for (size_t i = 0; i < list.size(); ++i) {
    // a scenario entry, or the scenario a perturbation family perturbs
    const bool perturbs = list[i].is_object() && list[i].contains("perturb") && list[i]["perturb"].is_string();
    if (!list[i].is_string() && !perturbs) continue;
    const std::string name = perturbs ? list[i]["perturb"].get<std::string>() : list[i].get<std::string>();
    if (!sweep::is_plain_name(name) || name.ends_with(".json"))
      throw ApiError(422, "invalid",
                     "over REST a sweep names catalogue scenarios or generators, not files: '" + name + "'",
                     "scenarios[" + std::to_string(i) + "]" + (perturbs ? ".perturb" : ""));
  }
}

}  // namespace

struct SweepJobs::Job {
  std::int64_t id = 0;
  sweep::SweepSpec spec;
  std::vector<sweep::SweepCase> cases;
  int jobs = 1;
  std::atomic<bool> stop{false};
  std::thread thread;
  std::mutex mutex;  // guards the fields below
  std::string status = "running", error;
  sweep::RunnerOutcome outcome;
};

SweepJobs::SweepJobs(RunManager& runs, std::string scenarios_dir) : runs_(runs), scenarios_dir_(std::move(scenarios_dir)) {}

// A sweep is admitted like the runs it makes (summaries only: no frame
// limits): its cost estimate, summed over every run, against
// --max-run-cost. Runs of one scenario entry and method configuration cost
// alike: the entry's case 0 stands for the others (generated once: the
// last cases made are kept, sweep_case.hpp).
void SweepJobs::admit(const Job& job) {
  std::map<std::pair<size_t, size_t>, LaneEstimate> by_kind;
  std::vector<LaneEstimate> lanes;
  lanes.reserve(job.cases.size());
  for (const sweep::SweepCase& c : job.cases) {
    auto it = by_kind.find({c.entry, c.config});
    if (it == by_kind.end()) {
      LaneEstimate estimate;
      try {
        // the entry's first case: generated once for all its configurations
        sweep::SweepCase first = c;
        first.index = 0;
        const Scenario scenario = sweep::scenario_of_case(job.spec, first);
        const std::int64_t steps = job.spec.steps ? *job.spec.steps : std::llround(scenario.duration / scenario.dt);
        estimate = estimate_lane(scenario, steps, 0);
      } catch (const std::exception&) {
        // a case that cannot be built fails when it runs, at no cost
      }
      it = by_kind.emplace(std::make_pair(c.entry, c.config), estimate).first;
    }
    lanes.push_back(it->second);
  }
  runs_.admit_work(lanes, false);
}

SweepJobs::~SweepJobs() { stop_all(); }

// A spec checked as a start would check it (422 naming the path, the REST
// limits, the run quotas), expanded into its cases; nothing is started.
std::shared_ptr<SweepJobs::Job> SweepJobs::prepare(const json& body) {
  refuse_paths(body);
  auto job = std::make_shared<Job>();
  try {
    job->spec = sweep::parse_sweep_spec(body, {scenarios_dir_, scenarios_dir_});
  } catch (...) {
    rethrow_as_api_error("", 422);
  }
  // counted before expanding: a short spec can name billions of runs (memory)
  const std::uint64_t runs = sweep::sweep_case_count(job->spec);
  if (runs > kMaxRunsPerSweep)
    throw ApiError(422, "invalid",
                   "this spec expands to " + std::to_string(runs) + " runs; over REST at most " +
                       std::to_string(kMaxRunsPerSweep) + " (the command line has no limit)",
                   "scenarios");
  // admitting generates each generator entry's first case (tens of ms each)
  const auto generated = size_t(std::count_if(job->spec.scenarios.begin(), job->spec.scenarios.end(),
                                              [](const sweep::ScenarioEntry& e) { return e.generated(); }));
  if (generated > kMaxGeneratorEntries)
    throw ApiError(422, "invalid",
                   "this spec has " + std::to_string(generated) + " generator entries; over REST at most " +
                       std::to_string(kMaxGeneratorEntries) + " (the command line has no limit)",
                   "scenarios");
  job->cases = sweep::expand_sweep(job->spec);
  admit(*job);
  return job;
}

json SweepJobs::validate(const json& body) {
  const std::shared_ptr<Job> job = prepare(body);
  return {{"valid", true},
          {"name", job->spec.name},
          {"total", job->cases.size()},
          {"scenario_entries", job->spec.scenarios.size()},
          {"configurations", job->spec.configs.size()}};
}

json SweepJobs::start(const json& body, int jobs) {
  const std::shared_ptr<Job> job = prepare(body);
  // one core stays for live runs
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  job->jobs = std::clamp(jobs, 1, std::max(1, cores - 1));

  std::lock_guard lock(mutex_);
  int running = 0;
  for (const auto& [id, other] : jobs_) {
    std::lock_guard other_lock(other->mutex);
    if (other->status != "running") continue;
    ++running;
    if (other->spec.name == job->spec.name)
      throw ApiError(409, "wrong_state", "sweep '" + job->spec.name + "' is running already (id " + std::to_string(id) + ")",
                     "name");
  }
  if (running >= kMaxRunningSweeps)
    throw ApiError(503, "busy", "at most " + std::to_string(kMaxRunningSweeps) + " sweeps may run at once", "");
  int begun = 0;
  try {
    for (; begun < job->jobs; ++begun) runs_.begin_job(0);  // 0: it reads no stored run
  } catch (...) {
    for (int i = 0; i < begun; ++i) runs_.end_job();
    throw;
  }
  // forget the oldest finished sweeps beyond the limit
  for (auto it = jobs_.begin(); jobs_.size() >= kMaxKeptSweeps && it != jobs_.end();) {
    bool ended;
    {
      std::lock_guard other_lock(it->second->mutex);
      ended = it->second->status != "running";
    }
    if (!ended) { ++it; continue; }
    if (it->second->thread.joinable()) it->second->thread.join();
    it = jobs_.erase(it);
  }
  job->id = next_id_++;
  jobs_[job->id] = job;
  job->thread = std::thread([this, job] {
    lower_thread_priority(10);  // inherited by the workers it starts
    sweep::RunnerOptions options;
    options.jobs = job->jobs;
    options.stop = &job->stop;
    std::string status = "completed", error;
    sweep::RunnerOutcome outcome;
    try {
      outcome = sweep::run_sweep(job->spec, job->cases, runs_.store(), options);
      if (outcome.interrupted) status = "stopped";
    } catch (const std::exception& e) {
      status = "failed";
      error = e.what();
    }
    {
      std::lock_guard job_lock(job->mutex);
      job->status = status;
      job->error = error;
      job->outcome = std::move(outcome);
    }
    for (int i = 0; i < job->jobs; ++i) runs_.end_job();
  });
  return status_of(*job);
}

json SweepJobs::status_of(Job& job) {
  std::string status, error;
  sweep::RunnerOutcome outcome;
  {
    std::lock_guard lock(job.mutex);
    status = job.status;
    error = job.error;
    outcome = job.outcome;
  }
  const size_t total = job.cases.size();
  const size_t pending = sweep::pending_cases(job.spec, job.cases, runs_.store()).size();
  json body = {{"id", job.id},       {"name", job.spec.name}, {"status", status},
               {"total", total},     {"done", total - pending}, {"jobs", job.jobs}};
  if (!error.empty()) body["error"] = error;
  if (status == "running") return body;
  json failures = json::array();
  for (size_t i = 0; i < outcome.failures.size() && i < 20; ++i) failures.push_back(outcome.failures[i]);
  body["failed"] = outcome.failures.size();
  body["failures"] = failures;
  body["report"] = sweep::report_json(sweep::build_report(runs_.store().sweep_runs(job.spec.name)));
  return body;
}

std::shared_ptr<SweepJobs::Job> SweepJobs::find(std::int64_t id) {
  std::lock_guard lock(mutex_);
  auto it = jobs_.find(id);
  if (it == jobs_.end()) throw ApiError(404, "not_found", "no sweep " + std::to_string(id), "id");
  return it->second;
}

json SweepJobs::status(std::int64_t id) { return status_of(*find(id)); }

json SweepJobs::runs(std::int64_t id, const RunQuery& query) {
  const std::shared_ptr<Job> job = find(id);
  std::vector<storage::SweepRunEntry> matching;
  for (storage::SweepRunEntry& e : runs_.store().sweep_runs(job->spec.name)) {
    if (query.family && sweep::report_family(e.row) != *query.family) continue;
    if (query.config && e.row.config_key != *query.config) continue;
    if (query.outcome && (e.row.success != (*query.outcome == "pass"))) continue;
    if (query.failure_mode && e.row.failure_mode != query.failure_mode) continue;
    matching.push_back(std::move(e));
  }
  json page = json::array();
  for (size_t i = size_t(query.offset); i < matching.size() && i < size_t(query.offset + query.limit); ++i) {
    const storage::SweepRunEntry& e = matching[i];
    json summary = parsed_or_null(e.summary_json);
    const auto field = [&](const char* key) { return summary.is_object() && summary.contains(key) ? summary[key] : json(); };
    page.push_back({{"run", e.run_id},
                    {"key", e.row.key},
                    {"case", e.row.scenario_key},
                    {"config", e.row.config_key},
                    {"family", sweep::report_family(e.row)},
                    {"success", e.row.success},
                    {"failure_mode", e.row.failure_mode ? json(*e.row.failure_mode) : json()},
                    {"failure_t", e.row.failure_t ? json(*e.row.failure_t) : json()},
                    {"frames", e.frames},
                    {"steps", field("steps")},
                    {"collided", field("collided")},
                    {"min_distance", field("min_distance")},
                    {"max_tracking_error", field("max_tracking_error")},
                    {"difficulty", parsed_or_null(e.difficulty_json)}});
  }
  return {{"id", id}, {"sweep", job->spec.name}, {"total", matching.size()}, {"offset", query.offset},
          {"limit", query.limit}, {"runs", page}};
}

json SweepJobs::list() {
  std::vector<std::shared_ptr<Job>> jobs;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, job] : jobs_) jobs.push_back(job);
  }
  json list = json::array();
  for (const auto& job : jobs) {
    std::lock_guard lock(job->mutex);
    list.push_back({{"id", job->id}, {"name", job->spec.name}, {"status", job->status}, {"total", job->cases.size()},
                    {"failed", job->outcome.failures.size()}});
  }
  return list;
}

json SweepJobs::control(std::int64_t id, const json& body) {
  if (!body.is_object() || body.size() != 1 || !body.contains("action") || body["action"] != "stop")
    throw ApiError(400, "invalid", "a sweep takes {\"action\": \"stop\"}", "action");
  find(id)->stop = true;
  return {{"id", id}, {"stopping", true}};
}

void SweepJobs::stop_all() {
  std::vector<std::shared_ptr<Job>> jobs;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, job] : jobs_) jobs.push_back(job);
  }
  for (const auto& job : jobs) job->stop = true;
  for (const auto& job : jobs)
    if (job->thread.joinable()) job->thread.join();
}

}  // namespace rrlab::server
