#include <rrlab/server/app/lane_estimate.hpp>

#include <rrlab/methods/step_cost.hpp>
#include <rrlab/scenario/scenario_step_cost.hpp>

namespace rrlab::server {

LaneEstimate estimate_lane(const Scenario& scenario, std::int64_t steps, std::int64_t frame_bytes) {
  return {scenario.model.dof(), obstacle_equivalents(scenario.scene), steps, frame_bytes,
          method_step_factor(scenario) * link_mesh_factor(scenario.model)};
}

double run_cost(const LaneEstimate& lane) {
  return double(lane.dof) * (lane.obstacles + 1) * double(lane.steps) * lane.factor;
}

}  // namespace rrlab::server
