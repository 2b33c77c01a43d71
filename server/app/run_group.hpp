// One or more simulations stepped in lockstep on their own thread (a single
// run is a group of one; /api/compare makes a group of several methods on one
// scenario). Inputs are applied under the group's lock between steps and
// their events queued to the FrameWriter ahead of the frames they take effect
// in (answered once stored: Accepted); frames go to the FrameWriter; the
// latest frame of each lane is published for WebSocket clients at the
// display rate.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/server/app/controller.hpp>
#include <rrlab/server/app/frame_geometry.hpp>
#include <rrlab/server/app/frame_source.hpp>
#include <rrlab/server/app/lane_estimate.hpp>
#include <rrlab/server/app/run_types.hpp>
#include <rrlab/server/app/storage_budget.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/completion.hpp>
#include <rrlab/storage/quotas.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::storage {
class RunStore;
class FrameWriter;
}  // namespace rrlab::storage

namespace rrlab::server {

struct RunServices {
  storage::RunStore& store;
  storage::FrameWriter& writer;
  long max_run_frames = Quotas{}.max_run_frames;       // per run (serve --max-run-frames)
  std::int64_t max_run_bytes = Quotas{}.max_run_bytes;    // per run (serve --max-run-bytes)
  StorageBudget* budget = nullptr;             // total (serve --max-total-bytes); null: none
  // Called with every lane's estimate once the simulators are built and
  // before any run is stored: throws DomainError to refuse the request; returns
  // each lane's bytes to reserve from the budget (reserved by the caller).
  std::function<std::vector<std::int64_t>(const std::vector<LaneEstimate>&)> admit;
};

class LaneSource;

// A real-time factor: 0 (as fast as possible) or in [0.001, 1000].
inline bool valid_rate(double rate) { return rate == 0 || (rate >= 1e-3 && rate <= 1000); }
inline constexpr const char* kRateRule = "must be 0 (as fast as possible) or in [0.001, 1000]";

struct GroupOptions {
  RunMode mode = RunMode::live;
  double rate = 1.0;           // real-time factor; 0: as fast as possible
  double display_hz = 60.0;    // publication rate for WebSocket clients
  bool paused = false;         // live runs: start paused
  std::optional<long> steps;   // default: the scenario's duration / dt
  std::optional<std::int64_t> source_run;
  bool compare = false;
  std::string owner;  // the address that started it (live runs per address: Quotas::max_live_per_address)
  // a live run nobody watches or calls ends as abandoned (Quotas::abandon_unwatched_s, abandon_idle_s)
  std::chrono::seconds abandon_unwatched{Quotas{}.abandon_unwatched_s};
  std::chrono::seconds abandon_idle{Quotas{}.abandon_idle_s};
};

// What an input or a control request answers: the lane's status now, and
// the work the answer still waits for (an input's event being stored, a
// single step being taken), which settles with the status to answer then.
// Nothing blocks meanwhile: REST answers later, a WebSocket acks later.
struct Accepted {
  nlohmann::json status;
  std::shared_ptr<storage::Completion> pending;  // null: answer `status` now
};

class RunGroup : public std::enable_shared_from_this<RunGroup> {
 public:
  // Creates the stored runs (one per scenario); throws DomainError on bad input.
  RunGroup(RunServices services, const std::vector<Scenario>& lanes, const GroupOptions& options);
  ~RunGroup();
  void start();
  void request_stop();  // the run ends as "stopped" after the current step
  void wait_exited();   // returns once the thread has finished everything (callbacks included)

  int lane_count() const { return int(lanes_.size()); }
  std::int64_t run_id(int lane) const { return lanes_[size_t(lane)].run_id; }
  int lane_of(std::int64_t run_id) const;  // -1 if not in this group

  // A control command; the lane's status (a step: once the step is taken; a
  // reset: once stored). Throws DomainError (conflict in the wrong state).
  Accepted control(int lane, const ControlCommand& command);
  // An input event (sim/run_inputs.hpp kinds); params and method go to this
  // lane, scene, joystick and reset inputs to every lane. Applied at once
  // (it takes effect in the next step); pending settles once its events are
  // stored, with an error if they could not be. Throws DomainError (paths
  // relative to the payload).
  Accepted input(int lane, InputKind kind, const nlohmann::json& payload);
  nlohmann::json status_json(int lane);
  bool finished() const { return finished_; }
  // Called once when the group has ended (at once if it has).
  void when_finished(std::function<void()> callback);
  nlohmann::json summary_json(int lane);  // the lane's run summary so far

  std::shared_ptr<FrameSource> source(int lane);  // a LaneSource (app/lane_source.hpp)
  Controller& controller() { return controller_; }  // one for every lane

  // Activity: a REST call for the group, or a WebSocket message to it. A live
  // run with neither, nor a WebSocket client, for GroupOptions::abandon_*
  // ends as "stopped" with "ended": "abandoned" in its summary.
  void touch();
  bool watched();  // some lane has a WebSocket client
  bool live() const { return options_.mode == RunMode::live; }
  bool ending() const { return ending_; }  // asked to stop (by a client, or as abandoned or superseded)
  const std::string& owner() const { return options_.owner; }
  // Ends the run to make room for a newer one of its owner ("ended": "superseded").
  void supersede();

 private:
  struct Lane {
    std::int64_t run_id = 0;
    std::unique_ptr<Simulator> sim;
    std::unique_ptr<FrameGeometry> geometry;  // what frames draw beyond the simulator's record
    std::int64_t seq = 0;  // steps taken in this run (over resets)
    std::int64_t frames_stored = 0, bytes_stored = 0;  // pushed to the writer
    std::int64_t reserved = 0;  // bytes of the budget reserved for this lane, not yet pushed
    std::string storage_stopped;  // why later frames are not stored ("": all stored)
    std::uint64_t scene_version = 1;  // raised by every input but a joystick's
    // the scene_version of the last change that needs a whole snapshot (a
    // method switch, a reset, an obstacle added or removed), and of the last
    // parameter change and obstacle edit (sent as params and scene messages)
    std::uint64_t snapshot_version = 1, params_version = 0, obstacles_version = 0;
    RunStatus status = RunStatus::running;  // once finished: how it ended
    // published for clients (guarded by publish_mutex_)
    PublishedFrame published;
    std::string encode_buffer;
    std::shared_ptr<Subscribers> subscribers = std::make_shared<Subscribers>();
  };
  friend class LaneSource;

  void loop();
  std::unique_lock<std::mutex> lock_for_input();  // ahead of the simulation thread
  nlohmann::json summary_locked(Lane& lane);
  nlohmann::json status_locked(const Lane& lane) const;
  bool all_done() const;
  void step_lanes();
  void publish(Lane& lane);                 // holds mutex_
  bool store_frame(Lane& lane, std::int64_t bytes);  // false: a limit stops this lane's storage
  void release_reservations();
  void release_reservations_of(Lane& lane);
  std::optional<std::string> write_failure();  // a lane's frames could not be written
  void finish(RunStatus status);  // holds no lock
  void check_abandoned();  // holds mutex_: ends a live run nobody uses (touch())
  RunStatus lane_status(const Lane& lane) const;

  RunServices services_;
  GroupOptions options_;
  double dt_ = 0.01;
  std::vector<Lane> lanes_;

  mutable std::mutex mutex_;  // the simulations and everything below
  std::condition_variable wake_;
  std::atomic<int> pending_inputs_{0};
  bool paused_ = false, stop_requested_ = false;
  int step_requests_ = 0;
  std::uint64_t pacing_generation_ = 0;  // bumped on pause/rate changes
  std::chrono::steady_clock::time_point next_publish_{};

  std::mutex publish_mutex_;
  std::atomic<bool> finished_{false};
  std::mutex done_mutex_;
  std::vector<std::function<void()>> on_finished_;
  std::string failure_;  // an exception from a step ends the run as "failed"
  std::uint64_t writer_failures_seen_ = 0;
  std::vector<std::pair<std::int64_t, storage::StoredFrame>> outbox_;  // this step's frames
  struct StepWaiter {
    int lane;
    std::int64_t seq;  // settled once the lane has taken this many steps, or the run ended
    std::shared_ptr<storage::Completion> done;
  };
  std::vector<StepWaiter> step_waiters_;
  // the waiters settled now, with their statuses (taken under mutex_, settled without it)
  std::vector<std::pair<std::shared_ptr<storage::Completion>, nlohmann::json>> settle_steps(bool all);
  std::mutex exit_mutex_;
  std::condition_variable exited_cv_;
  bool exited_ = false;
  Controller controller_;
  // activity (touch()): steady-clock ticks, and whether any came since the start
  const std::chrono::steady_clock::time_point started_at_ = std::chrono::steady_clock::now();
  std::atomic<std::chrono::steady_clock::rep> last_activity_{started_at_.time_since_epoch().count()};
  std::atomic<bool> touched_{false};
  std::atomic<bool> ending_{false};  // stop_requested_, readable without the lock
  std::chrono::steady_clock::time_point next_idle_check_{};
  std::string ended_;  // why it ended on its own ("abandoned", "superseded"); "" otherwise (under mutex_)
};

}  // namespace rrlab::server
