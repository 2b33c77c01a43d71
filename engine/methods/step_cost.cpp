#include <rrlab/methods/step_cost.hpp>

#include <algorithm>
#include <bitset>
#include <cmath>

#include <rrlab/collision/mesh_loader.hpp>

namespace rrlab {

double unit_step_cost(const StepCostQuery&) { return 1; }

// measured 1.4-1.5 on scenarios 01 and 03
double closest_point_step_cost(const StepCostQuery&) { return 1.5; }

// qp_constraints 1.4-1.7, qp_ik 0.9-1.6, hqp 1.2-1.9 (two QPs; three when the dampers conflict), diffik
// 1.3-2.0 (bench/method_cost_bench.cpp, scenarios 01 and 03)
double constrained_step_cost(const StepCostQuery&) { return 3; }

double ccp_voronoi_step_cost(const StepCostQuery& query) {
  return 1 + 4 * (1 + query.param("newton_iterations") / 40);  // four RK4 stages
}

double multi_preview_step_cost(const StepCostQuery& query) {
  // bench/method_cost_bench.cpp, scenario 01 against pinv's 3.8 us: 320x at 3 x 20 x 1 (60 evaluations),
  // 2,500-3,800x at 3 x 100 x 1, 750-800x at 3 x 20 x 4, 90-140x at 1 x 20 x 1; on 03 (pinv 11 us) 160x and 2,700x
  const double previews = std::max(1.0, query.param("previews"));  // 0: planned offline, charged as 1
  const double evaluations =
      previews * std::max(1.0, query.param("population")) * std::max(1.0, query.param("generations"));
  return 1 + 12 * evaluations;
}

double direct_search_step_cost(const StepCostQuery& query) {
  // bench/method_cost_bench.cpp, scenario 01 against pinv: 81 options 76x, 27 options 34x, 243 options 300x
  const int free = query.dof - query.task_rows;
  const auto mask = static_cast<unsigned long long>(std::max(0.0, query.param("perturb_mask")));
  const int perturbed = std::min({int(std::bitset<64>(mask).count()), std::max(free, 0), 6});
  const double options = std::pow(3.0, perturbed);
  return 1 + options * (1 + query.param("newton_iterations") / 16);
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
