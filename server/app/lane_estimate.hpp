// What a lane would store and cost, known before anything is stored: the
// steps it is asked for (a live run's resets may add more; the per-run limits
// still hold then) and the bytes of one packed frame. Admission
// (app/admission.hpp) weighs runs, re-simulations and sweeps by it.
#pragma once

#include <cstdint>

#include <rrlab/scenario/scenario.hpp>

namespace rrlab::server {

struct LaneEstimate {
  int dof = 0;
  double obstacles = 0;  // primitive-obstacle equivalents (methods/step_cost.hpp)
  std::int64_t steps = 0;
  std::int64_t frame_bytes = 0;
  double factor = 1;     // the method's and the mesh links' step cost (methods/step_cost.hpp)
};

// The estimate of a scenario's run of `steps` steps, frames of `frame_bytes`.
LaneEstimate estimate_lane(const Scenario& scenario, std::int64_t steps, std::int64_t frame_bytes);

// A run's cost estimate: DOF x (obstacles + 1) x steps x the method's factor
// (the +1: a run without obstacles still costs its kinematics; obstacles and
// the factor: methods/step_cost.hpp).
double run_cost(const LaneEstimate& lane);

}  // namespace rrlab::server
