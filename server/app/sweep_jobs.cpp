#include <rrlab/server/app/sweep_jobs.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/server/app/free_memory.hpp>
#include <rrlab/server/app/run_manager.hpp>
#include <rrlab/server/app/thread_priority.hpp>
#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/api/response.hpp>
#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_case.hpp>
#include <rrlab/sweep/sweep_expansion.hpp>
#include <rrlab/sweep/sweep_report.hpp>
#include <rrlab/sweep/sweep_report_json.hpp>
#include <rrlab/sweep/sweep_runner.hpp>
#include <rrlab/sweep/sweep_spec.hpp>

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
constexpr size_t kMaxCachedReports = 8;  // built reports kept (each at most a few MB: sweep_report_json.hpp)

}  // namespace

struct SweepJobs::Job {
  std::int64_t id = 0;
  sweep::SweepSpec spec;
  std::vector<sweep::SweepCase> cases;
  int jobs = 1;
  std::atomic<bool> stop{false};
  std::thread thread;
  std::mutex mutex;  // guards the fields below
  SweepStatus status = SweepStatus::running;
  std::string error;
  sweep::RunnerOutcome outcome;
  std::optional<size_t> done_at_end;  // stored cases, counted once the sweep has ended
  std::shared_ptr<const std::string> report;  // the ended sweep's report (null: not built, or dropped)
  std::mutex build_mutex;  // held while the report is built
  std::atomic<bool> exited{false};  // the thread has finished (the report built)
};

SweepJobs::SweepJobs(RunManager& runs) : runs_(runs) {}

// A sweep is admitted like the runs it makes (summaries only: no frame
// limits): its cost estimate, summed over every run, against
// --max-run-cost. A scenario entry's cases cost alike (its case 0 stands for
// the others): each entry's first case is built once, and only the method
// changes from one configuration to the next, so admission is linear in the
// configurations with a small constant (no scenario built per configuration).
void SweepJobs::admit(const sweep::SweepSpec& spec) {
  std::vector<LaneEstimate> lanes;
  lanes.reserve(size_t(std::min<std::uint64_t>(sweep::sweep_case_count(spec), kMaxRunsPerSweep)));
  const size_t seeds = std::max<size_t>(1, spec.seeds.size());
  for (size_t e = 0; e < spec.scenarios.size() && !spec.configs.empty(); ++e) {
    std::optional<Scenario> first;
    try {
      sweep::SweepCase c;
      c.entry = e;
      first = sweep::scenario_of_case(spec, c);
    } catch (const std::exception&) {
      // a case that cannot be built fails when it runs, at no cost
    }
    for (const sweep::MethodConfig& config : spec.configs) {
      LaneEstimate estimate;
      if (first) {
        sweep::use_method_config(*first, config);
        const std::int64_t steps = spec.steps ? *spec.steps : std::llround(first->duration / first->dt);
        estimate = estimate_lane(*first, steps, 0);
      }
      lanes.insert(lanes.end(), size_t(spec.scenarios[e].count) * seeds, estimate);
    }
  }
  runs_.admit_work(lanes, false);
}

SweepJobs::~SweepJobs() { stop_all(); }

// A spec checked as a start would check it (unprocessable naming the path, the REST
// limits, the run quotas), not yet expanded into its cases; nothing is started.
std::shared_ptr<SweepJobs::Job> SweepJobs::prepare(sweep::SweepSpec spec) {
  auto job = std::make_shared<Job>();
  job->spec = std::move(spec);
  // counted before expanding: a short spec can name billions of runs (memory)
  const std::uint64_t runs = sweep::sweep_case_count(job->spec);
  if (runs > kMaxRunsPerSweep)
    throw DomainError(Problem::unprocessable, "invalid",
                      "this spec expands to " + std::to_string(runs) + " runs; over REST at most " +
                          std::to_string(kMaxRunsPerSweep) + " (the command line has no limit)",
                      "scenarios");
  // admitting generates each generator entry's first case (tens of ms each)
  const auto generated = size_t(std::count_if(job->spec.scenarios.begin(), job->spec.scenarios.end(),
                                              [](const sweep::ScenarioEntry& e) { return e.generated(); }));
  if (generated > kMaxGeneratorEntries)
    throw DomainError(Problem::unprocessable, "invalid",
                      "this spec has " + std::to_string(generated) + " generator entries; over REST at most " +
                          std::to_string(kMaxGeneratorEntries) + " (the command line has no limit)",
                      "scenarios");
  admit(job->spec);
  return job;
}

json SweepJobs::validate(sweep::SweepSpec spec) {
  json answer;
  {
    const std::shared_ptr<Job> job = prepare(std::move(spec));  // not expanded: counted
    answer = {{"valid", true},
              {"name", job->spec.name},
              {"total", sweep::sweep_case_count(job->spec)},
              {"scenario_entries", job->spec.scenarios.size()},
              {"configurations", job->spec.configs.size()}};
  }
  release_free_memory();  // a large grid's spec is gone: its pages go back to the system
  return answer;
}

json SweepJobs::start(sweep::SweepSpec spec, int jobs) {
  runs_.check_writable();  // storage_full on a full disk: a sweep would store nothing
  const std::shared_ptr<Job> job = prepare(std::move(spec));
  forget_reports(job->spec.name);  // an earlier run of this sweep: its runs are about to change
  job->cases = sweep::expand_sweep(job->spec);
  // one core stays for live runs
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  job->jobs = std::clamp(jobs, 1, std::max(1, cores - 1));

  std::lock_guard lock(mutex_);
  int running = 0;
  for (const auto& [id, other] : jobs_) {
    std::lock_guard other_lock(other->mutex);
    if (other->status != SweepStatus::running) continue;
    ++running;
    if (other->spec.name == job->spec.name)
      throw DomainError(Problem::conflict, "wrong_state",
                        "sweep '" + job->spec.name + "' is running already (id " + std::to_string(id) + ")", "name");
  }
  if (running >= kMaxRunningSweeps)
    throw DomainError(Problem::busy, "busy", "at most " + std::to_string(kMaxRunningSweeps) + " sweeps may run at once");
  int begun = 0;
  try {
    for (; begun < job->jobs; ++begun) runs_.begin_job(0);  // 0: it reads no stored run
  } catch (...) {
    for (int i = 0; i < begun; ++i) runs_.end_job();
    throw;
  }
  // forget the oldest finished sweeps beyond the limit
  for (auto it = jobs_.begin(); jobs_.size() >= kMaxKeptSweeps && it != jobs_.end();) {
    if (!it->second->exited) { ++it; continue; }  // running, or building its report
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
    SweepStatus status = SweepStatus::completed;
    std::string error;
    sweep::RunnerOutcome outcome;
    try {
      outcome = sweep::run_sweep(job->spec, job->cases, runs_.store(), options);
      if (outcome.interrupted) status = SweepStatus::stopped;
    } catch (const std::exception& e) {
      status = SweepStatus::failed;
      error = e.what();
    }
    for (int i = 0; i < job->jobs; ++i) runs_.end_job();
    // the report is built before the sweep shows as ended, on this low-priority
    // thread: a client that sees it ended gets the report at once, and no GET
    // waits on a worker for it
    try {
      report_of(job, true);
    } catch (const std::exception&) {
      // a stored summary that is not JSON: GET /api/sweeps/{id} tries again and answers the error
    }
    {
      std::lock_guard job_lock(job->mutex);
      job->status = status;
      job->error = error;
      job->outcome = std::move(outcome);
    }
    job->exited = true;
  });
  return progress_of(*job);
}

json SweepJobs::progress_of(Job& job) {
  SweepStatus status = SweepStatus::running;
  std::string error, storage_stopped;
  json failures = json::array();  // the first 20
  size_t failed = 0;
  std::optional<size_t> done;
  {
    std::lock_guard lock(job.mutex);
    status = job.status;
    error = job.error;
    storage_stopped = job.outcome.storage_stopped;
    failed = job.outcome.failures.size();
    for (size_t i = 0; i < failed && i < 20; ++i) failures.push_back(job.outcome.failures[i]);
    done = job.done_at_end;
  }
  const size_t total = job.cases.size();
  const bool ended = status != SweepStatus::running;
  if (!done) {
    done = total - sweep::pending_cases(job.spec, job.cases, runs_.store()).size();
    if (ended) {
      std::lock_guard lock(job.mutex);
      job.done_at_end = done;
    }
  }
  json body = {{"id", job.id},       {"name", job.spec.name}, {"status", to_string(status)},
               {"total", total},     {"done", *done},         {"jobs", job.jobs}};
  if (!error.empty()) body["error"] = error;
  // why it stopped on its own: "disk full" or "database read-only" (what was stored stays; resumable)
  if (!storage_stopped.empty()) body["reason"] = storage_stopped;
  if (!ended) return body;
  body["failed"] = failed;
  body["failures"] = failures;
  return body;
}

std::shared_ptr<const std::string> SweepJobs::report_of(const std::shared_ptr<Job>& kept, bool wait) {
  Job& job = *kept;
  {
    std::lock_guard lock(job.mutex);
    if (job.report) return job.report;
  }
  std::unique_lock build(job.build_mutex, std::defer_lock);
  if (wait)
    build.lock();
  else if (!build.try_lock())  // another request builds it: no second worker held waiting for it
    throw DomainError(Problem::busy, "busy", "this sweep's report is being built; ask again in a moment");
  {
    std::lock_guard lock(job.mutex);  // built by another caller meanwhile
    if (job.report) return job.report;
  }
  const std::vector<storage::SweepRunEntry> runs = runs_.store().sweep_runs(job.spec.name, &interrupted_);
  const sweep::SweepReport report = sweep::build_report(runs, &interrupted_);
  if (interrupted_) return nullptr;
  auto text = std::make_shared<const std::string>(safe_dump(sweep::report_json(report)));
  release_free_memory();  // the runs read and the report's tables are gone: only its text stays
  {
    std::lock_guard lock(job.mutex);
    job.report = text;
  }
  // the newest reports are kept; the oldest beyond the limit dropped
  std::shared_ptr<Job> dropped;
  {
    std::lock_guard lock(cache_mutex_);
    std::erase_if(cached_reports_, [&](const std::shared_ptr<Job>& other) { return other == kept; });
    cached_reports_.push_back(kept);
    if (cached_reports_.size() > kMaxCachedReports) {
      dropped = cached_reports_.front();
      cached_reports_.pop_front();
    }
  }
  if (dropped) {
    std::lock_guard lock(dropped->mutex);
    dropped->report.reset();
  }
  return text;
}

std::shared_ptr<SweepJobs::Job> SweepJobs::find(std::int64_t id) {
  std::lock_guard lock(mutex_);
  auto it = jobs_.find(id);
  if (it == jobs_.end()) throw DomainError(Problem::not_found, "not_found", "no sweep " + std::to_string(id), "id");
  return it->second;
}

std::string SweepJobs::status(std::int64_t id) {
  const std::shared_ptr<Job> job = find(id);
  const json progress = progress_of(*job);
  std::string body = safe_dump(progress);
  if (progress["status"] == to_string(SweepStatus::running)) return body;  // no report yet
  const std::shared_ptr<const std::string> report = report_of(job, false);
  if (!report) throw DomainError(Problem::busy, "busy", "the server is shutting down");
  body.pop_back();  // the report spliced in as text: built once, never parsed again
  body += ",\"report\":";
  body += *report;
  body += '}';
  return body;
}

json sweep_run_json(const storage::SweepRunEntry& e) {
  const json summary = parsed_or_null(e.summary_json);
  const auto field = [&](const char* key) { return summary.is_object() && summary.contains(key) ? summary[key] : json(); };
  return {{"run", e.run_id},
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
          {"difficulty", parsed_or_null(e.difficulty_json)}};
}

storage::RunStore::SweepRunFilter SweepJobs::RunQuery::filter() const {
  return {family, config, failure_mode, success};
}

std::string SweepJobs::name(std::int64_t id) { return find(id)->spec.name; }

json SweepJobs::runs(std::int64_t id, const RunQuery& query) {
  const std::shared_ptr<Job> job = find(id);
  std::int64_t total = 0;
  const std::vector<storage::SweepRunEntry> matching =
      runs_.store().sweep_runs_page(job->spec.name, query.filter(), query.limit, query.offset, total);
  json page = json::array();
  for (const storage::SweepRunEntry& e : matching) page.push_back(sweep_run_json(e));
  return {{"id", id}, {"sweep", job->spec.name}, {"total", total}, {"offset", query.offset},
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
    list.push_back({{"id", job->id}, {"name", job->spec.name}, {"status", to_string(job->status)}, {"total", job->cases.size()},
                    {"failed", job->outcome.failures.size()}});
  }
  return list;
}

json SweepJobs::stop(std::int64_t id) {
  find(id)->stop = true;
  return {{"id", id}, {"stopping", true}};
}

void SweepJobs::forget_reports(const std::optional<std::string>& name) {
  std::vector<std::shared_ptr<Job>> jobs;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, job] : jobs_)
      if (!name || job->spec.name == *name) jobs.push_back(job);
  }
  for (const auto& job : jobs) {
    std::lock_guard lock(job->mutex);
    if (job->status == SweepStatus::running) continue;
    job->report.reset();
    job->done_at_end.reset();
  }
  std::lock_guard lock(cache_mutex_);
  std::erase_if(cached_reports_, [&](const std::shared_ptr<Job>& kept) { return !name || kept->spec.name == *name; });
}

void SweepJobs::interrupt() {
  interrupted_ = true;
  std::lock_guard lock(mutex_);
  for (const auto& [id, job] : jobs_) job->stop = true;
}

void SweepJobs::stop_all() {
  interrupted_ = true;
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
