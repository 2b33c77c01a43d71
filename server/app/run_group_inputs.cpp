// A run group's side that clients call: its status and summary, control
// commands (start, pause, step, reset, stop, rate) and input events, taken
// under the group's lock between two steps (RunGroup::lock_for_input).
#include <rrlab/server/app/run_group.hpp>

#include <rrlab/methods/registry_json.hpp>
#include <rrlab/server/api/errors.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

using nlohmann::json;

json RunGroup::summary_locked(Lane& lane) {
  json s = summary_to_json(lane.sim->summary());
  s["run"] = lane.run_id;
  s["frames_stored"] = lane.frames_stored;
  if (!lane.storage_stopped.empty()) s["storage_stopped"] = lane.storage_stopped;
  if (!ended_.empty()) s["ended"] = ended_;
  if (!failure_.empty()) s["failure"] = failure_;
  return s;
}

json RunGroup::summary_json(int lane) {
  auto lock = lock_for_input();
  return summary_locked(lanes_[size_t(lane)]);
}

json RunGroup::status_locked(const Lane& lane) const {
  const State& state = lane.sim->state();
  return {{"id", lane.run_id},
          {"mode", to_string(options_.mode)},
          {"status", to_string(lane_status(lane))},
          {"method", lane.sim->method_name()},
          {"params", param_values_json(lane.sim->method())},
          {"step", state.step},
          {"t", state.t},
          {"frames", lane.seq},
          {"total_steps", lane.sim->total_steps()},
          {"rate", options_.rate}};
}

json RunGroup::status_json(int lane) {
  auto lock = lock_for_input();
  return status_locked(lanes_[size_t(lane)]);
}

// Every lock taken from outside the simulation thread goes through here: an
// as-fast-as-possible run yields between steps while someone is waiting.
std::unique_lock<std::mutex> RunGroup::lock_for_input() {
  ++pending_inputs_;
  std::unique_lock lock(mutex_);
  --pending_inputs_;
  return lock;
}

Accepted RunGroup::control(int lane_index, const ControlCommand& command) {
  const std::optional<ControlAction> action = command.action;
  if (!action && !command.rate)
    throw DomainError(Problem::invalid, "invalid", "give an action, a rate or both", "action");
  if (command.rate && !valid_rate(*command.rate)) throw DomainError(Problem::invalid, "invalid", kRateRule, "rate");
  if (options_.mode != RunMode::live && action != ControlAction::stop)
    throw DomainError(Problem::conflict, "wrong_state",
                      std::string("a ") + to_string(options_.mode) + " run can only be stopped", "action");
  if (action == ControlAction::reset) return input(lane_index, InputKind::reset, json::object());
  auto lock = lock_for_input();
  Lane& lane = lanes_[size_t(lane_index)];
  if (finished_ || stop_requested_)
    throw DomainError(Problem::conflict, "wrong_state",
                      std::string("the run has ended (") + to_string(lane_status(lane)) + ")", "action");
  if (command.rate) {
    options_.rate = *command.rate;
    ++pacing_generation_;
  }
  Accepted accepted;
  if (action == ControlAction::start || action == ControlAction::pause) {
    paused_ = action == ControlAction::pause;
    ++pacing_generation_;
    const RunStatus status = paused_ ? RunStatus::paused : RunStatus::running;
    for (const Lane& l : lanes_) services_.store.set_status(l.run_id, to_string(status));
    for (Lane& l : lanes_) publish(l);
  } else if (action == ControlAction::step) {
    if (!paused_)
      throw DomainError(Problem::conflict, "wrong_state", "pause the run before single-stepping", "action");
    // answered once the simulation thread has taken the step (or the run ended)
    // (steps asked for before it and not yet taken come first)
    accepted.pending = std::make_shared<storage::Completion>();
    ++step_requests_;
    step_waiters_.push_back({lane_index, lane.seq + step_requests_, accepted.pending});
  } else if (action == ControlAction::stop) {
    stop_requested_ = ending_ = true;  // the REST route answers once the run has ended (deferred)
  }
  wake_.notify_all();
  accepted.status = status_locked(lane);
  return accepted;
}

Accepted RunGroup::input(int lane_index, InputKind kind, const json& payload) {
  if (options_.mode != RunMode::live)
    throw DomainError(Problem::conflict, "wrong_state",
                      std::string("a ") + to_string(options_.mode) + " run takes no inputs; start a live run");
  auto lock = lock_for_input();
  if (finished_ || stop_requested_) throw DomainError(Problem::conflict, "wrong_state", "the run has ended");
  // a run whose writes failed could no longer be re-simulated: it takes no more inputs
  if (auto error = write_failure()) throw DomainError(Problem::unavailable, "storage", *error);
  const bool own_lane = kind == InputKind::params || kind == InputKind::method;
  Accepted accepted;
  accepted.pending = std::make_shared<storage::Completion>();
  const size_t last = own_lane ? size_t(lane_index) : lanes_.size() - 1;
  for (size_t i = 0; i < lanes_.size(); ++i) {
    if (own_lane && int(i) != lane_index) continue;
    Lane& lane = lanes_[i];
    try {
      apply_input(*lane.sim, kind, payload);
    } catch (...) {
      rethrow_as_domain_error("");  // lanes before this one keep the input, and its event
    }
    // Stored by the frame writer, queued ahead of the frames it takes effect
    // in (the mutex keeps the next step out until then); the last lane's
    // event committed means every one's (one queue, written in order).
    services_.writer.push_event(lane.run_id, {lane.seq, lane.sim->state().step, to_string(kind), payload.dump()},
                                i == last ? accepted.pending : nullptr);
    if (kind != InputKind::joystick) {
      ++lane.scene_version;
      (kind == InputKind::params     ? lane.params_version
       : kind == InputKind::obstacle ? lane.obstacles_version
                                     : lane.snapshot_version) = lane.scene_version;
    }
    if (paused_) publish(lane);
  }
  wake_.notify_all();
  accepted.status = status_locked(lanes_[size_t(lane_index)]);
  return accepted;
}

}  // namespace rrlab::server
