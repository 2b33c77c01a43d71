// Inputs to a running simulation (parameter changes, obstacle edits, joystick
// commands, method switches, reset). The server applies them live and stores
// each as an event {step, kind, payload}; re-simulation applies the same
// events before the same steps, so both paths share this one function.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

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
void apply_input(Simulator& sim, const std::string& kind, const nlohmann::json& payload);

// Live inputs are bounded by PhysicalBounds (scenario/physical_bounds.hpp),
// the same set that scenario files are checked against.

// The obstacle as scenario-syntax JSON at its current position (radians), for
// snapshots and for clients that edit it.
nlohmann::json obstacle_to_json(const Obstacle& obstacle);

}  // namespace rrlab
