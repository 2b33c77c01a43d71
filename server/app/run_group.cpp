#include <rrlab/server/app/run_group.hpp>

#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/app/stream_json.hpp>
#include <rrlab/storage/database.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/resimulation.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

using nlohmann::json;
using Clock = std::chrono::steady_clock;
// How often a live run checks whether anyone still uses it (a paused one wakes for it).
constexpr auto kIdleCheckPeriod = std::chrono::seconds(1);

// ---- construction ----

RunGroup::RunGroup(RunServices services, const std::vector<Scenario>& scenarios, const GroupOptions& options)
    : services_(services), options_(options), paused_(options.paused) {
  if (scenarios.empty()) throw DomainError(Problem::invalid, "invalid", "a run needs a scenario", "scenario");
  dt_ = scenarios.front().dt;
  lanes_.resize(scenarios.size());
  // every simulator first: a lane that fails leaves no stored run behind
  for (size_t i = 0; i < scenarios.size(); ++i) {
    try {
      lanes_[i].sim = std::make_unique<Simulator>(scenarios[i]);
      lanes_[i].geometry = std::make_unique<FrameGeometry>(scenarios[i].model, scenarios[i].scene,
                                                           scenarios[i].task.space);
    } catch (...) {
      rethrow_as_domain_error("", Problem::unprocessable);
    }
    if (options_.steps) lanes_[i].sim->set_total_steps(*options_.steps);
  }
  // the request's cost and storage, refused before anything is stored
  if (services_.admit) {
    std::vector<LaneEstimate> estimates;
    for (size_t i = 0; i < scenarios.size(); ++i)
      estimates.push_back(estimate_lane(scenarios[i], std::int64_t(lanes_[i].sim->total_steps()),
                                        std::int64_t(storage::pack_frame(lanes_[i].sim->frame()).size())));
    const std::vector<std::int64_t> reserved = services_.admit(estimates);
    for (size_t i = 0; i < scenarios.size() && i < reserved.size(); ++i) lanes_[i].reserved = reserved[i];
  }
  try {
    for (size_t i = 0; i < scenarios.size(); ++i) {
      Lane& lane = lanes_[i];
      storage::NewRun run = storage::new_run_of(scenarios[i], *lane.sim, to_string(options_.mode));
      run.source_run = options_.source_run;
      if (options_.compare && i > 0) run.compare_group = lanes_[0].run_id;
      lane.run_id = services_.store.create_run(run);
      if (options_.compare && i == 0) services_.store.set_compare_group(lane.run_id, lane.run_id);
      if (paused_) services_.store.set_status(lane.run_id, to_string(RunStatus::paused));
      publish(lane);
    }
  } catch (...) {
    release_reservations();
    throw;
  }
}

void RunGroup::release_reservations_of(Lane& lane) {
  if (services_.budget) services_.budget->release(lane.reserved);
  lane.reserved = 0;
}

void RunGroup::release_reservations() {
  for (Lane& lane : lanes_) release_reservations_of(lane);
}

std::optional<std::string> RunGroup::write_failure() {
  for (const Lane& lane : lanes_)
    if (auto error = services_.writer.run_error(lane.run_id))
      return "storing the frames of run " + std::to_string(lane.run_id) + " failed: " + *error;
  return std::nullopt;
}

RunGroup::~RunGroup() = default;

void RunGroup::start() {
  // the thread owns a reference: the group lives until its thread has finished
  try {
    std::thread([self = shared_from_this()] { self->loop(); }).detach();
  } catch (const std::exception& e) {
    release_reservations();
    for (const Lane& lane : lanes_) services_.store.finish_run(lane.run_id, to_string(RunStatus::failed), "{}");
    finished_ = true;
    {
      std::lock_guard lock(exit_mutex_);
      exited_ = true;
    }
    throw DomainError(Problem::busy, "busy", std::string("cannot start a simulation thread: ") + e.what());
  }
}

void RunGroup::wait_exited() {
  std::unique_lock lock(exit_mutex_);
  exited_cv_.wait(lock, [&] { return exited_; });
}

void RunGroup::request_stop() {
  {
    auto lock = lock_for_input();
    stop_requested_ = ending_ = true;
  }
  wake_.notify_all();
}

int RunGroup::lane_of(std::int64_t run_id) const {
  for (size_t i = 0; i < lanes_.size(); ++i)
    if (lanes_[i].run_id == run_id) return int(i);
  return -1;
}

// ---- the simulation thread ----

bool RunGroup::all_done() const {
  for (const Lane& lane : lanes_)
    if (!lane.sim->done()) return false;
  return true;
}

void RunGroup::step_lanes() {
  for (Lane& lane : lanes_) {
    if (lane.sim->done()) continue;
    timed_step(*lane.sim);
    const Frame& f = lane.sim->frame();
    if (lane.storage_stopped.empty()) {
      std::string packed = storage::pack_frame(f);
      if (store_frame(lane, std::int64_t(packed.size())))  // pushed once the lock is released
        outbox_.emplace_back(lane.run_id, storage::stored_frame(lane.seq, f, std::move(packed)));
    }
    ++lane.seq;
  }
}

// The per-run and total limits, checked frame by frame: they hold even where
// the estimate did not (a live run's resets, obstacles added, a method
// switched). A lane that reaches one stores no later frame and says why in
// its summary ("storage_stopped"); it is still simulated.
bool RunGroup::store_frame(Lane& lane, std::int64_t bytes) {
  const auto stop = [&](const std::string& why) {
    lane.storage_stopped = why + "; later steps were simulated, not stored";
    release_reservations_of(lane);
    return false;
  };
  if (lane.frames_stored >= services_.max_run_frames)
    return stop("max_run_frames: the run stored " + std::to_string(lane.frames_stored) +
                " frames, the most a run may store (serve --max-run-frames)");
  if (lane.bytes_stored + bytes > services_.max_run_bytes)
    return stop("max_run_bytes: the run stored " + std::to_string(lane.bytes_stored) + " bytes of frames and the next " +
                std::to_string(bytes) + " would pass " + std::to_string(services_.max_run_bytes) +
                " (serve --max-run-bytes)");
  if (services_.budget) {
    if (lane.reserved >= bytes) {
      lane.reserved -= bytes;
      services_.budget->release(bytes);
    } else {
      release_reservations_of(lane);
      if (!services_.budget->fits(bytes))
        return stop("max_total_bytes: the database holds " + std::to_string(services_.budget->used()) +
                    " bytes of frames (stored, queued or reserved by running runs) of at most " +
                    std::to_string(services_.budget->max()) + " (serve --max-total-bytes)");
    }
  }
  ++lane.frames_stored;
  lane.bytes_stored += bytes;
  return true;
}

RunStatus RunGroup::lane_status(const Lane& lane) const {
  if (finished_) return lane.status;
  if (stop_requested_) return RunStatus::stopping;
  return paused_ ? RunStatus::paused : RunStatus::running;
}

void RunGroup::publish(Lane& lane) {
  const auto wall = std::chrono::system_clock::now().time_since_epoch();
  const FrameContext context{lane.run_id, lane.seq, lane.scene_version, to_string(lane_status(lane)),
                             std::chrono::duration_cast<std::chrono::microseconds>(wall).count()};
  encode_frame(context, lane.sim->frame(), lane.sim->model(), lane.sim->scene(), *lane.geometry,
               lane.encode_buffer);
  auto text = std::make_shared<const std::string>(lane.encode_buffer);
  std::lock_guard lock(publish_mutex_);
  lane.published.version += 1;
  lane.published.scene_version = lane.scene_version;
  lane.published.text = std::move(text);
  lane.subscribers->notify_all();
}

void RunGroup::loop() {
  std::unique_lock lock(mutex_);
  auto anchor = Clock::now();
  long anchor_steps = 0;
  std::uint64_t generation = pacing_generation_;
  const auto publish_period = std::chrono::duration<double>(1.0 / options_.display_hz);
  while (true) {
    // a paused run wakes now and then to see whether anyone still uses it
    wake_.wait_for(lock, kIdleCheckPeriod, [&] { return stop_requested_ || !paused_ || step_requests_ > 0 || all_done(); });
    check_abandoned();
    if (stop_requested_ || all_done()) break;
    if (paused_ && step_requests_ == 0) continue;
    const bool single = paused_;
    if (single) --step_requests_;
    if (generation != pacing_generation_) {
      anchor = Clock::now();
      anchor_steps = 0;
      generation = pacing_generation_;
    }
    try {
      step_lanes();
    } catch (const std::exception& e) {
      failure_ = e.what();
      break;
    }
    if (!outbox_.empty()) {
      // storage back-pressure (a full queue) waits here, never under the lock inputs need
      lock.unlock();
      for (auto& [run, frame] : outbox_) services_.writer.push(run, std::move(frame));
      outbox_.clear();
      lock.lock();
      // a full disk or a read-only file: the run ends as failed, its reason in the summary
      if (services_.writer.failures() != writer_failures_seen_) {
        writer_failures_seen_ = services_.writer.failures();
        if (auto error = write_failure()) {
          failure_ = *error;
          break;
        }
      }
    }
    ++anchor_steps;
    // publish on a display-rate schedule (deadlines, so that steps of 10 ms
    // still give 60 publications a second on average)
    const auto now = Clock::now();
    if (single || all_done() || now >= next_publish_) {
      for (Lane& lane : lanes_) publish(lane);
      next_publish_ += std::chrono::duration_cast<Clock::duration>(publish_period);
      if (next_publish_ < now) next_publish_ = now + std::chrono::duration_cast<Clock::duration>(publish_period);
    }
    if (!step_waiters_.empty()) {  // also when the run was resumed meanwhile
      auto ready = settle_steps(false);
      lock.unlock();
      for (auto& [done, status] : ready) done->settle({{}, {}, std::move(status)});
      lock.lock();
    }
    if (!paused_ && options_.rate > 0) {
      const auto next = anchor + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(double(anchor_steps) * dt_ / options_.rate));
      wake_.wait_until(lock, next, [&] { return stop_requested_ || generation != pacing_generation_; });
    } else if (pending_inputs_ > 0) {
      // as fast as possible: let waiting REST/WebSocket inputs in between steps
      lock.unlock();
      for (int spins = 0; pending_inputs_ > 0 && spins < 10000; ++spins) std::this_thread::yield();
      lock.lock();
    }
  }
  const bool stopped = stop_requested_ && !all_done();
  lock.unlock();
  finish(!failure_.empty() ? RunStatus::failed : stopped ? RunStatus::stopped : RunStatus::completed);
}

// ---- runs nobody uses ----

void RunGroup::touch() {
  touched_ = true;
  last_activity_ = Clock::now().time_since_epoch().count();
}

bool RunGroup::watched() {
  for (Lane& lane : lanes_)
    if (lane.subscribers->size() > 0) return true;
  return false;
}

void RunGroup::check_abandoned() {
  if (options_.mode != RunMode::live || stop_requested_) return;
  const auto now = Clock::now();
  if (now < next_idle_check_) return;
  next_idle_check_ = now + kIdleCheckPeriod;
  if (watched()) {
    touch();
    return;
  }
  bool ever_watched = false;
  for (Lane& lane : lanes_) ever_watched = ever_watched || lane.subscribers->ever_added();
  const auto last = Clock::time_point(Clock::duration(last_activity_.load()));
  const bool unused_since_start = !touched_ && !ever_watched && now - started_at_ >= options_.abandon_unwatched;
  if (unused_since_start || now - last >= options_.abandon_idle) {
    ended_ = "abandoned";
    stop_requested_ = ending_ = true;
  }
}

void RunGroup::supersede() {
  {
    auto lock = lock_for_input();
    if (stop_requested_ || finished_) return;
    ended_ = "superseded";
    stop_requested_ = ending_ = true;
  }
  wake_.notify_all();
}

void RunGroup::finish(RunStatus requested_status) {
  services_.writer.flush();
  std::vector<std::function<void()>> callbacks;
  std::vector<std::pair<std::shared_ptr<storage::Completion>, json>> ended_steps;
  {
    std::lock_guard lock(mutex_);
    release_reservations();
    RunStatus status = requested_status;
    if (auto error = write_failure()) {  // the last batches may have failed after the loop
      if (failure_.empty()) failure_ = *error;
      status = RunStatus::failed;
      // frames_stored: what the store kept (a gap-free prefix), not what was pushed
      for (Lane& lane : lanes_) {
        try {
          if (auto run = services_.store.run(lane.run_id)) lane.frames_stored = run->frames;
        } catch (const std::exception&) {
        }
      }
    }
    for (Lane& lane : lanes_) {
      lane.status = status;
      try {
        services_.store.finish_run(lane.run_id, to_string(status), summary_locked(lane).dump());
      } catch (const std::exception&) {
        // no room for the summary: the status alone is a smaller write
        lane.status = RunStatus::failed;
        try {
          services_.store.set_status(lane.run_id, to_string(RunStatus::failed));
        } catch (const std::exception&) {
        }
      }
    }
    finished_ = true;
    for (Lane& lane : lanes_) publish(lane);
    ended_steps = settle_steps(true);
  }
  for (auto& [done, status] : ended_steps) done->settle({{}, {}, std::move(status)});
  {
    std::lock_guard lock(done_mutex_);
    callbacks.swap(on_finished_);
  }
  for (auto& callback : callbacks) {
    try {
      callback();
    } catch (const std::exception&) {
    }
  }
  // destroyed before exited_: a callback may own what the server tears down
  // once every run has exited (a deferred reply's HTTP session, whose socket
  // belongs to the I/O context; ASan caught its use after free at shutdown)
  callbacks.clear();
  {
    std::lock_guard lock(exit_mutex_);
    exited_ = true;
  }
  exited_cv_.notify_all();
}

void RunGroup::when_finished(std::function<void()> callback) {
  {
    std::lock_guard lock(done_mutex_);
    if (!finished_) {
      on_finished_.push_back(std::move(callback));
      return;
    }
  }
  callback();
}

std::vector<std::pair<std::shared_ptr<storage::Completion>, json>> RunGroup::settle_steps(bool all) {
  std::vector<std::pair<std::shared_ptr<storage::Completion>, json>> ready;
  std::erase_if(step_waiters_, [&](StepWaiter& w) {
    const Lane& lane = lanes_[size_t(w.lane)];
    if (!all && lane.seq < w.seq) return false;
    ready.emplace_back(std::move(w.done), status_locked(lane));
    return true;
  });
  return ready;
}

}  // namespace rrlab::server
