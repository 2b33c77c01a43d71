// Inputs to a running simulation (parameter changes, obstacle edits, joystick
// commands, method switches, reset). The server applies them live and stores
// each as an event {step, kind, payload}; re-simulation applies the same
// events before the same steps, so both paths share this one function.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

class Simulator;

// An input that is valid JSON but not allowed in the run's state (e.g. a
// joystick command on a run whose task is not a joystick): HTTP 409.
class InputStateError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Event kinds, with their payloads (angles in radians, SI units):
//   params           {"NAME": number | label, ...}           (the current method's)
//   obstacle         {"id", "position"?, "velocity"?, "size"?, "radius"?, "points"?, "normal"?}
//   obstacle_add     an obstacle in scenario syntax, placed at the current time
//   obstacle_remove  {"id"}
//   joystick         {"linear": [vx, vy(, vz)], "angular"?: [wx, wy, wz]}
//   method           {"name", "params"?: {...}}
//   reset            {}
// Validates the whole payload first and changes nothing when it throws
// ScenarioError (path relative to the payload) or InputStateError.
enum class InputKind { params, obstacle, obstacle_add, obstacle_remove, joystick, method, reset };
const char* to_string(InputKind kind);
std::optional<InputKind> parse_input_kind(std::string_view text);
void apply_input(Simulator& sim, InputKind kind, const nlohmann::json& payload);
// The same, the kind by its name (a stored event's): ScenarioError at "kind" for an unknown one.
void apply_input(Simulator& sim, const std::string& kind, const nlohmann::json& payload);
// The ScenarioError apply_input throws for a kind it does not know.
ScenarioError unknown_input_kind(const std::string& kind);

// Live inputs are bounded by PhysicalBounds (scenario/physical_bounds.hpp),
// the same set that scenario files are checked against.

// The obstacle as scenario-syntax JSON at its current position (radians), for
// snapshots and for clients that edit it.
nlohmann::json obstacle_to_json(const Obstacle& obstacle);

}  // namespace rrlab
