// The explicit table of every method: name, description, parameter specs
// and a factory. CLI, REST and scenarios look methods up here by name.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <rrlab/methods/method.hpp>
#include <rrlab/methods/step_cost.hpp>

namespace rrlab {

// One row per method: everything rrlab needs to know of it. A row without a
// factory or a step cost does not register (std::logic_error for a built-in
// row, std::invalid_argument from register_external_method).
struct MethodInfo {
  std::string name, description;
  std::vector<ParamSpec> params;
  std::function<std::unique_ptr<Method>(const MethodContext&)> make;
  StepCostFactor step_cost = nullptr;  // a step's cost relative to pinv's (methods/step_cost.hpp)
  std::string docs;                    // its section of docs/methods.md ("docs/methods.md#anchor"), "" if none
  bool python = false;                 // registered by the Python package (a method written in Python)
};

// The built-in methods.
const std::vector<MethodInfo>& method_registry();
// nullptr when unknown; also finds "witness" (methods/witness_playback.hpp),
// which the registry does not list, and registered external methods
const MethodInfo* find_method(std::string_view name);
std::string method_names();  // "pinv, dls, ..." for error messages

// A method defined outside rrlab's code (one written in Python), found by
// name like a built-in one from now on in this process (scenarios, sweeps).
// Registering a name again replaces its factory for the runs that start
// later; an entry is never freed (a run may be building from it). Throws
// std::invalid_argument for a built-in method's name. Thread-safe.
void register_external_method(MethodInfo info);

}  // namespace rrlab
