// The server's state, as the routes see it: the scenario catalogue
// (app/scenario_catalogue.hpp), admission against the quotas
// (app/admission.hpp), the registry of live run groups, replays and jobs
// (app/run_registry.hpp) and the sweeps started over REST. RunManager owns
// them and starts run groups, which needs all three; everything else is
// theirs.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <rrlab/server/app/admission.hpp>
#include <rrlab/server/app/run_group.hpp>
#include <rrlab/server/app/run_registry.hpp>
#include <rrlab/server/app/scenario_catalogue.hpp>
#include <rrlab/storage/quotas.hpp>

namespace rrlab::storage {
class RunStore;
class FrameWriter;
}  // namespace rrlab::storage

namespace rrlab::server {

class SweepJobs;
class ReplayPlayer;

// Every limit is a `serve` option (cli/main.cpp); admission (app/admission.hpp)
// and the registry (app/run_registry.hpp) enforce them.
struct ServerLimits : Quotas {
  double default_display_hz = 60;
};

class RunManager {
 public:
  RunManager(storage::RunStore& store, storage::FrameWriter& writer, const std::string& scenarios_dir,
             ServerLimits limits = {});
  ~RunManager();  // stops every run and waits for them

  storage::RunStore& store() { return store_; }
  storage::FrameWriter& writer() { return writer_; }
  const ServerLimits& limits() const { return limits_; }
  ScenarioCatalogue& catalogue() { return catalogue_; }
  Admission& admission() { return admission_; }
  RunRegistry& registry() { return registry_; }
  // Sweeps started over REST (POST /api/sweeps).
  SweepJobs& sweeps() { return *sweeps_; }

  // A new group, registered and started. Refuses (before storing anything)
  // a write fault, more active runs than allowed, a request beyond the
  // per-run limits, the cost limit or the total bytes; a live one beyond its
  // owner's live runs ends the owner's oldest unwatched one (too_many when
  // all are watched).
  std::shared_ptr<RunGroup> start_group(const std::vector<Scenario>& lanes, const GroupOptions& options);
  // Deletes a stored run (RunRegistry::delete_run); the sweep reports that
  // may have counted it are built again.
  nlohmann::json delete_run(std::int64_t id);
  // A job's start (RunRegistry::begin_job), refused while the database cannot be written.
  void begin_job(std::int64_t source_run);

  // The registry's and admission's everyday calls.
  std::shared_ptr<RunGroup> group_of(std::int64_t id, int& lane) { return registry_.group_of(id, lane); }
  std::shared_ptr<ReplayPlayer> replay(std::int64_t id) { return registry_.replay(id); }
  std::int64_t add_replay(std::shared_ptr<ReplayPlayer> player, const std::string& owner) {
    return registry_.add_replay(std::move(player), owner);
  }
  void done_reading(std::int64_t source_run) { registry_.done_reading(source_run); }
  void end_job() { registry_.end_job(); }
  bool stopping() const { return registry_.stopping(); }
  void check_writable() { admission_.check_writable(); }
  std::int64_t admit_work(const std::vector<LaneEstimate>& lanes, bool frames) {
    return admission_.admit_work(lanes, frames);
  }
  void release_reserved(std::int64_t bytes) { admission_.release(bytes); }

  // Stops every sweep, run, replay and job and waits until their threads are
  // done with the store, the writer and the I/O context.
  void stop_all();

 private:
  storage::RunStore& store_;
  storage::FrameWriter& writer_;
  const ServerLimits limits_;
  ScenarioCatalogue catalogue_;
  Admission admission_;
  RunRegistry registry_;
  std::unique_ptr<SweepJobs> sweeps_;
};

}  // namespace rrlab::server
