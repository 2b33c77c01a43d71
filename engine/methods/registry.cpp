#include <rrlab/methods/registry.hpp>

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/witness_playback.hpp>

namespace rrlab {

const std::vector<MethodInfo>& method_registry() {
  static const std::vector<MethodInfo> table = {
      {"pinv", "Pseudoinverse, minimum-norm joint velocity (Whitney 1969)", pinv_params(), make_pinv,
       unit_step_cost, "docs/methods.md#pinv"},
      {"dls", "Damped least squares, fixed or manipulability-adaptive damping (Wampler 1986)",
       dls_params(), make_dls,
       unit_step_cost, "docs/methods.md#dls"},
      {"gpm", "Gradient projection of a criterion into the null space (Liégeois 1977)",
       gpm_params(), make_gpm,
       unit_step_cost, "docs/methods.md#gpm"},
      {"task_priority", "Task-priority resolution with a secondary task (Nakamura et al. 1987)",
       task_priority_params(), make_task_priority,
       closest_point_step_cost, "docs/methods.md#task_priority"},
      {"sr_task_priority",
       "Singularity-robust task priority, damped secondary task (Chiaverini 1997)",
       sr_task_priority_params(), make_sr_task_priority,
       closest_point_step_cost, "docs/methods.md#sr_task_priority"},
      {"closest_point", "Obstacle avoidance at the closest link point (Maciejewski & Klein 1985)",
       closest_point_params(), make_closest_point,
       closest_point_step_cost, "docs/methods.md#closest_point"},
      {"posture_generation",
       "Multi-criteria posture generation, link by link from the end-effector (Chen et al. 2002)",
       posture_generation_params(), make_posture_generation,
       constrained_step_cost, "docs/methods.md#posture_generation"},
      {"ccp_voronoi", "Configuration control points, DI / Voronoi-boundary DM criteria (Sezgin et al. 1997)",
       ccp_voronoi_params(), make_ccp_voronoi,
       ccp_voronoi_step_cost, "docs/methods.md#ccp_voronoi"},
      {"multi_preview", "Multi-preview control by avoidance manipulability and a 1-step GA (Zhang et al.)",
       multi_preview_params(), make_multi_preview,
       multi_preview_step_cost, "docs/methods.md#multi_preview"},
      {"qp_constraints",
       "QP with joint range/velocity/acceleration bounds, obstacle inequalities and singularity avoidance (Qiu, Cao & Sun)",
       qp_constraints_params(), make_qp_constraints,
       constrained_step_cost, "docs/methods.md#qp_constraints"},
      {"direct_search",
       "Direct search over perturbed self-motion options, weighted JRA/JVM/DM/clearance criteria (Kapoor, Cetin & Tesar)",
       direct_search_params(), make_direct_search,
       direct_search_step_cost, "docs/methods.md#direct_search"},
      {"qp_ik",
       "Weighted QP differential IK with joint-limit bounds and velocity dampers on obstacle and self pairs (as in "
       "mink and pink; Faverjon & Tournassoud dampers)",
       qp_ik_params(), make_qp_ik,
       constrained_step_cost, "docs/methods.md#qp_ik"},
      {"hqp",
       "Strict hierarchy as a cascade of QPs: limits and dampers, then the task, then posture (Kanoun, Lamiraux & "
       "Wieber; Escande, Mansard & Wieber)",
       hqp_params(), make_hqp,
       constrained_step_cost, "docs/methods.md#hqp"},
      {"diffik",
       "Direction-preserving differential IK: the largest scale α ≤ 1 of the task velocity under limits and dampers "
       "(Drake's DifferentialInverseKinematics)",
       diffik_params(), make_diffik,
       constrained_step_cost, "docs/methods.md#diffik"},
  };
  static const bool checked = [] {
    for (const MethodInfo& info : table)
      if (!info.make || !info.step_cost)
        throw std::logic_error("method \"" + info.name + "\" has no factory or no step cost in its registry row");
    return true;
  }();
  (void)checked;
  return table;
}

namespace {
// Registered external methods, newest last; none is ever freed.
struct ExternalMethods {
  std::mutex mutex;
  std::vector<std::unique_ptr<const MethodInfo>> entries;
};
ExternalMethods& external_methods() {
  static ExternalMethods table;
  return table;
}
const MethodInfo* find_builtin(std::string_view name) {
  for (const MethodInfo& info : method_registry())
    if (info.name == name) return &info;
  if (name == kWitnessMethod) return &witness_method_info();
  return nullptr;
}
}  // namespace

const MethodInfo* find_method(std::string_view name) {
  if (const MethodInfo* builtin = find_builtin(name)) return builtin;
  ExternalMethods& external = external_methods();
  std::lock_guard lock(external.mutex);
  for (auto it = external.entries.rbegin(); it != external.entries.rend(); ++it)
    if ((*it)->name == name) return it->get();
  return nullptr;
}

void register_external_method(MethodInfo info) {
  if (find_builtin(info.name)) throw std::invalid_argument("\"" + info.name + "\" is a built-in method's name");
  if (!info.make) throw std::invalid_argument("method \"" + info.name + "\" has no factory");
  if (!info.step_cost) throw std::invalid_argument("method \"" + info.name + "\" has no step cost");
  ExternalMethods& external = external_methods();
  std::lock_guard lock(external.mutex);
  external.entries.push_back(std::make_unique<const MethodInfo>(std::move(info)));
}

std::string method_names() {
  std::string names;
  for (const MethodInfo& info : method_registry()) names += (names.empty() ? "" : ", ") + info.name;
  ExternalMethods& external = external_methods();
  std::lock_guard lock(external.mutex);
  std::vector<std::string> listed;
  for (const auto& info : external.entries)
    if (std::find(listed.begin(), listed.end(), info->name) == listed.end()) listed.push_back(info->name);
  for (const std::string& name : listed) names += ", " + name + " (Python)";
  return names;
}

}  // namespace rrlab
