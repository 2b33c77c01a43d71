#include <rrlab/scenario/scenario_step_cost.hpp>

#include <stdexcept>
#include <string>

#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/methods/registry.hpp>

namespace rrlab {

double method_step_factor(const Scenario& scenario) {
  const MethodInfo* info = find_method(scenario.method.name);
  if (!info) throw std::invalid_argument("unknown method \"" + scenario.method.name + "\"");
  StepCostQuery query;
  query.dof = scenario.model.dof();
  query.task_rows = task_rows(scenario.task.space);
  query.param = [&](std::string_view name) {
    for (const auto& [key, value] : scenario.method.params)
      if (key == name) return value;
    const int spec = find_param(info->params, name);
    return spec >= 0 ? info->params[size_t(spec)].def : 0.0;
  };
  return info->step_cost(query);
}

}  // namespace rrlab
