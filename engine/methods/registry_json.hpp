// The method table as JSON (for `rrlab methods` and GET /api/methods).
#pragma once

#include <nlohmann/json.hpp>

#include <rrlab/methods/registry.hpp>

namespace rrlab {

nlohmann::json param_spec_json(const ParamSpec& spec);
nlohmann::json methods_json();
// A method's current parameter values, {"NAME": value, ...}.
nlohmann::json param_values_json(const Method& method);

}  // namespace rrlab
