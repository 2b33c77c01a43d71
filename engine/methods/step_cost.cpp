#include "methods/step_cost.hpp"

#include <algorithm>
#include <bitset>
#include <cmath>
#include <string>

#include "collision/mesh_loader.hpp"
#include "kinematics/kinematics.hpp"
#include "methods/registry.hpp"

namespace rrlab {

namespace {

// A parameter of the scenario's method: its own value, else the spec's default.
double param(const Scenario& scenario, const std::string& name) {
  for (const auto& [key, value] : scenario.method.params)
    if (key == name) return value;
  if (const MethodInfo* info = find_method(scenario.method.name))
    for (const ParamSpec& spec : info->params)
      if (spec.name == name) return spec.def;
  return 0;
}

}  // namespace

double method_step_factor(const Scenario& scenario) {
  const std::string& name = scenario.method.name;
  if (name == "multi_preview") {
    // bench/method_cost_bench.cpp, scenario 01 against pinv's 3.8 us: 320x at 3 x 20 x 1 (60 evaluations),
    // 2,500-3,800x at 3 x 100 x 1, 750-800x at 3 x 20 x 4, 90-140x at 1 x 20 x 1; on 03 (pinv 11 us) 160x and 2,700x
    const double previews = std::max(1.0, param(scenario, "previews"));  // 0: planned offline, charged as 1
    const double evaluations = previews * std::max(1.0, param(scenario, "population")) *
                               std::max(1.0, param(scenario, "generations"));
    return 1 + 12 * evaluations;
  }
  if (name == "direct_search") {
    // bench/method_cost_bench.cpp, scenario 01 against pinv: 81 options 76x, 27 options 34x, 243 options 300x
    const int free = scenario.model.dof() - task_rows(scenario.task.space);
    const auto mask = static_cast<unsigned long long>(std::max(0.0, param(scenario, "perturb_mask")));
    const int perturbed = std::min({int(std::bitset<64>(mask).count()), std::max(free, 0), 6});
    const double options = std::pow(3.0, perturbed);
    return 1 + options * (1 + param(scenario, "newton_iterations") / 16);
  }
  if (name == "ccp_voronoi") return 1 + 4 * (1 + param(scenario, "newton_iterations") / 40);  // four RK4 stages
  if (name == "posture_generation" || name == "qp_constraints") return 3;
  if (name == "closest_point" || name == "task_priority" || name == "sr_task_priority") return 1.5;  // measured 1.4-1.5
  return 1;  // pinv, dls, gpm: the unit
}

double obstacle_equivalents(const Scene& scene) {
  double count = 0;
  for (const Obstacle& o : scene.obstacles) count += 1 + (o.mesh ? double(o.mesh->triangles.size()) / 64 : 0.0);
  return count;
}

double link_mesh_factor(const Model& model) {
  double triangles = 0;
  for (const Link& link : model.links)
    if (link.mesh) triangles += double(link.mesh->triangles.size());
  return 1 + triangles / 24;
}

}  // namespace rrlab
