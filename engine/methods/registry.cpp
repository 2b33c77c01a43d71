#include "methods/registry.hpp"

#include "methods/factories.hpp"
#include "methods/witness_playback.hpp"

namespace rrlab {

const std::vector<MethodInfo>& method_registry() {
  static const std::vector<MethodInfo> table = {
      {"pinv", "Pseudoinverse, minimum-norm joint velocity (Whitney 1969)", pinv_params(), make_pinv},
      {"dls", "Damped least squares, fixed or manipulability-adaptive damping (Wampler 1986)",
       dls_params(), make_dls},
      {"gpm", "Gradient projection of a criterion into the null space (Liégeois 1977)",
       gpm_params(), make_gpm},
      {"task_priority", "Task-priority resolution with a secondary task (Nakamura et al. 1987)",
       task_priority_params(), make_task_priority},
      {"sr_task_priority",
       "Singularity-robust task priority, damped secondary task (Chiaverini 1997)",
       sr_task_priority_params(), make_sr_task_priority},
      {"closest_point", "Obstacle avoidance at the closest link point (Maciejewski & Klein 1985)",
       closest_point_params(), make_closest_point},
      {"posture_generation",
       "Multi-criteria posture generation, link by link from the end-effector (Chen et al. 2002)",
       posture_generation_params(), make_posture_generation},
      {"ccp_voronoi", "Configuration control points, DI / Voronoi-boundary DM criteria (Sezgin et al. 1997)",
       ccp_voronoi_params(), make_ccp_voronoi},
      {"multi_preview", "Multi-preview control by avoidance manipulability and a 1-step GA (Zhang et al.)",
       multi_preview_params(), make_multi_preview},
      {"qp_constraints",
       "QP with joint range/velocity/acceleration bounds, obstacle inequalities and singularity avoidance (Qiu, Cao & Sun)",
       qp_constraints_params(), make_qp_constraints},
      {"direct_search",
       "Direct search over perturbed self-motion options, weighted JRA/JVM/DM/clearance criteria (Kapoor, Cetin & Tesar)",
       direct_search_params(), make_direct_search},
  };
  return table;
}

const MethodInfo* find_method(std::string_view name) {
  for (const MethodInfo& info : method_registry())
    if (info.name == name) return &info;
  if (name == kWitnessMethod) return &witness_method_info();
  return nullptr;
}

std::string method_names() {
  std::string names;
  for (const MethodInfo& info : method_registry()) names += (names.empty() ? "" : ", ") + info.name;
  return names;
}

}  // namespace rrlab
