// How much one step of a scenario costs, relative to a step of a plain
// Jacobian method (pinv, dls) on capsule links and primitive obstacles: what
// the server admits runs by (serve --max-run-cost counts DOF x (obstacle
// equivalents + 1) x steps x this factor). The constants are fitted to
// `rrlab run` step times (scenarios 01 and 03, every method, the parameters
// that drive the cost; bench/method_cost_bench.cpp prints them) and err on
// the high side: a run is never admitted far below what it costs.
#pragma once

#include "scenario/scenario.hpp"

namespace rrlab {

// The method with its parameters (defaults where the scenario sets none):
// multi_preview ~ 12 x previews x population x generations (GA evaluations a
// step), direct_search ~ options x (1 + newton_iterations / 16) with
// 3^perturbed-joints options, the others 1 to 7.
double method_step_factor(const Scenario& scenario);

// Obstacles as primitive-obstacle equivalents: a mesh obstacle counts
// 1 + triangles / 64.
double obstacle_equivalents(const Scene& scene);

// Mesh links (URDF <mesh>): 1 + their triangles / 24 (distances go triangle
// by triangle through a BVH against every obstacle).
double link_mesh_factor(const Model& model);

}  // namespace rrlab
