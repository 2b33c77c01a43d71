// The server's enums: how a run was started, where it is, and the actions a
// client steers a run or a replay with. Inside the server they are enums;
// their names appear only where JSON is written or read and where the store
// keeps them (one to_string and one parse per enum).
#pragma once

#include <optional>
#include <string_view>

namespace rrlab::server {

// How a run was started: steered live (inputs, pacing), a batch run (as fast
// as possible, no inputs), or a re-simulation of a stored run.
enum class RunMode { live, batch, resimulation };
const char* to_string(RunMode mode);
std::optional<RunMode> parse_run_mode(std::string_view text);

// Where a run is. A live run is running or paused, stopping once asked to
// stop, then stopped, completed or failed; a run a crash cut short is marked
// interrupted by the next start (storage).
enum class RunStatus { running, paused, stopping, stopped, completed, failed, interrupted };
const char* to_string(RunStatus status);
std::optional<RunStatus> parse_run_status(std::string_view text);

// POST /api/runs/{id}/control and {"type": "control"} on a live run's WebSocket.
enum class ControlAction { start, pause, step, reset, stop };
const char* to_string(ControlAction action);
std::optional<ControlAction> parse_control_action(std::string_view text);

// A live run's control command: an action, a new real-time factor, or both.
struct ControlCommand {
  std::optional<ControlAction> action;
  std::optional<double> rate;  // valid_rate (app/run_group.hpp)
};

// POST /api/replays/{id}/control and {"type": "control"} on a replay's WebSocket.
enum class ReplayAction { play, pause, seek };
const char* to_string(ReplayAction action);
std::optional<ReplayAction> parse_replay_action(std::string_view text);

// A replay's control command: an action, a speed, a frame to show, or several.
struct ReplayCommand {
  std::optional<ReplayAction> action;
  std::optional<double> speed;  // in (0, 1000]
  std::optional<double> seq;    // a seek's frame (checked against the run's frames by the player)
};

// A sweep started over REST: running until it completes, is stopped or fails.
enum class SweepStatus { running, completed, stopped, failed };
const char* to_string(SweepStatus status);

}  // namespace rrlab::server
