// The "methods" of a sweep spec expanded into method configurations: each
// entry is a method name, or {"name", "params": {NAME: value | [values]}}
// whose value lists span a grid (cartesian product). Parameters are ordered
// as the method declares them (`rrlab methods`), so a configuration's key
// does not depend on how the spec orders its object; lists keep their order.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rrlab::sweep {

struct ParamValue {
  std::string name;
  double value = 0;  // an enumeration's index for choice parameters
  std::string text;  // as printed in keys: the label, or %.17g
};

struct MethodConfig {
  std::string method;
  std::vector<ParamValue> params;  // those the spec sets; the others keep the method's defaults
  std::string key;                 // method{param=value,...}, or the method alone without params
  size_t entry = 0;                // index in the spec's "methods"
};

// %.17g: the exact double, as printed in keys.
std::string exact_number(double value);
std::string method_config_key(const std::string& method, const std::vector<ParamValue>& params);

// Throws ScenarioError naming the path (methods[2].params.lambda[1]); rejects
// duplicate configurations.
std::vector<MethodConfig> parse_method_configs(const nlohmann::json& methods, const std::string& path);

}  // namespace rrlab::sweep
