// A scenario's step cost: its method's factor (the registry row's
// step_cost, methods/step_cost.hpp) for the scenario's arm, task and parameters.
#pragma once

#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

// The method with its parameters (defaults where the scenario sets none):
// multi_preview ~ 12 x previews x population x generations (GA evaluations a
// step), direct_search ~ options x (1 + newton_iterations / 16) with
// 3^perturbed-joints options, the others 1 to 7. Throws std::invalid_argument
// for a method the registry does not know.
double method_step_factor(const Scenario& scenario);

}  // namespace rrlab
