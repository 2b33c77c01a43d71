// How much one step costs, relative to a step of a plain Jacobian method
// (pinv, dls) on capsule links and primitive obstacles: what the server admits
// runs by (serve --max-run-cost counts DOF x (obstacle equivalents + 1) x steps
// x the method's factor). Each method's factor is a function in its registry
// row (methods/registry.cpp); the fitted models are here. The constants are
// fitted to `rrlab run` step times (scenarios 01 and 03, every method, the
// parameters that drive the cost; bench/method_cost_bench.cpp prints them) and
// err on the high side: a run is never admitted far below what it costs.
#pragma once

#include <functional>
#include <string_view>

#include <rrlab/collision/scene.hpp>
#include <rrlab/model/model.hpp>

namespace rrlab {

// What a method's step cost depends on: the arm and task sizes and the run's
// parameters (methods never see a scenario).
struct StepCostQuery {
  int dof = 0;        // the arm's joints
  int task_rows = 0;  // the task's rows: dof - task_rows joints are free
  // a parameter of the run: its own value, else its spec's default (0 when unknown)
  std::function<double(std::string_view)> param;
};

using StepCostFactor = double (*)(const StepCostQuery&);

// The fitted factors, one per method family.
double unit_step_cost(const StepCostQuery&);                  // pinv, dls, gpm, the witness: 1
double closest_point_step_cost(const StepCostQuery&);         // closest_point, task_priority, sr_task_priority
double constrained_step_cost(const StepCostQuery&);           // posture_generation, qp_constraints, qp_ik, hqp, diffik
double ccp_voronoi_step_cost(const StepCostQuery& query);     // four RK4 stages and their Newton iterations
double multi_preview_step_cost(const StepCostQuery& query);   // GA evaluations a step
double direct_search_step_cost(const StepCostQuery& query);   // 3^perturbed joints options

// Obstacles as primitive-obstacle equivalents: a mesh obstacle counts
// 1 + triangles / 64.
double obstacle_equivalents(const Scene& scene);

// Mesh links (URDF <mesh>): 1 + their triangles / 24 (distances go triangle
// by triangle through a BVH against every obstacle).
double link_mesh_factor(const Model& model);

}  // namespace rrlab
