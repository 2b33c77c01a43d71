#include <rrlab/server/app/run_manager.hpp>

#include <chrono>

#include <rrlab/server/app/replay_player.hpp>
#include <rrlab/server/app/sweep_jobs.hpp>

namespace rrlab::server {

RunManager::RunManager(storage::RunStore& store, storage::FrameWriter& writer, const std::string& scenarios_dir,
                       ServerLimits limits)
    : store_(store),
      writer_(writer),
      limits_(limits),
      catalogue_(store, scenarios_dir, limits.max_scenarios),
      admission_(store, writer, limits),
      registry_(store, limits),
      sweeps_(std::make_unique<SweepJobs>(*this)) {}

RunManager::~RunManager() { stop_all(); }

void RunManager::stop_all() {
  sweeps_->stop_all();  // before the registry stops: their workers' slots are jobs it waits for
  registry_.stop_all();
}

void RunManager::begin_job(std::int64_t source_run) {
  admission_.check_writable();
  registry_.begin_job(source_run);
}

std::shared_ptr<RunGroup> RunManager::start_group(const std::vector<Scenario>& lanes, const GroupOptions& requested) {
  admission_.check_writable();
  GroupOptions options = requested;
  options.abandon_unwatched = std::chrono::seconds(limits_.abandon_unwatched_s);
  options.abandon_idle = std::chrono::seconds(limits_.abandon_idle_s);
  auto admitting = admission_.hold();  // the limits hold under concurrent starts
  const std::shared_ptr<RunGroup> superseded = registry_.make_room(options, int(lanes.size()));
  // a live lane reserves at most a window of what it will store, not its whole duration
  const std::int64_t window = options.mode == RunMode::live ? limits_.live_reserve_bytes : 0;
  RunServices services{store_, writer_, limits_.max_run_frames, limits_.max_run_bytes, &admission_.budget(),
                       [this, window](const std::vector<LaneEstimate>& estimates) {
                         return admission_.admit_held(estimates, true, window);
                       }};
  auto group = std::make_shared<RunGroup>(services, lanes, options);  // a refused request ends no other run
  if (superseded) superseded->supersede();
  group->start();  // registered only once its thread runs
  registry_.add(group);
  return group;
}

nlohmann::json RunManager::delete_run(std::int64_t id) {
  nlohmann::json deleted = registry_.delete_run(id);
  sweeps_->forget_reports(std::nullopt);  // it may have been a sweep's run: reports are built again
  return deleted;
}

}  // namespace rrlab::server
