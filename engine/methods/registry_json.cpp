#include <rrlab/methods/registry_json.hpp>

namespace rrlab {

nlohmann::json param_spec_json(const ParamSpec& spec) {
  nlohmann::json j = {{"name", spec.name},   {"label", spec.label}, {"unit", spec.unit},
                      {"help", spec.help},   {"default", spec.def}, {"min", spec.min},
                      {"max", spec.max},     {"step", spec.step}};
  if (!spec.choices.empty()) j["choices"] = spec.choices;
  return j;
}

nlohmann::json methods_json() {
  nlohmann::json list = nlohmann::json::array();
  for (const MethodInfo& info : method_registry()) {
    nlohmann::json params = nlohmann::json::array();
    for (const ParamSpec& spec : info.params) params.push_back(param_spec_json(spec));
    list.push_back({{"name", info.name}, {"description", info.description}, {"params", params}});
  }
  return list;
}

nlohmann::json param_values_json(const Method& method) {
  nlohmann::json values = nlohmann::json::object();
  for (size_t i = 0; i < method.specs().size(); ++i)
    values[method.specs()[i].name] = method.param_values()[Eigen::Index(i)];
  return values;
}

}  // namespace rrlab
