#include <rrlab/sweep/method_grid.hpp>

#include <cstdio>
#include <map>

#include <rrlab/methods/registry.hpp>
#include <rrlab/scenario/json_reader.hpp>

namespace rrlab::sweep {

namespace {

constexpr size_t kMaxConfigs = 100000;

// One parameter's values, resolved against the method's spec.
struct ParamAxis {
  std::vector<ParamValue> values;
};

ParamValue resolve(const std::string& method, const ParamSpec& spec, const nlohmann::json& value,
                   const std::string& path) {
  const auto [name, v] = resolve_method_param(method, spec.name, value, path);
  ParamValue out{name, v, spec.choices.empty() ? exact_number(v) : spec.choices[size_t(v)]};
  return out;
}

std::vector<MethodConfig> configs_of_entry(const nlohmann::json& entry, const std::string& path) {
  std::string method;
  std::vector<ParamAxis> axes;
  if (entry.is_string()) {
    method = entry.get<std::string>();
    require_method(method, path);
  } else {
    JsonObject object(entry, path);
    object.check_keys({"name", "params"});
    method = object.string("name");
    require_method(method, object.child("name"));
    if (object.has("params")) {
      const JsonObject params = object.object("params");
      const nlohmann::json& raw = object.raw("params");
      const std::vector<ParamSpec>& specs = find_method(method)->params;
      for (auto it = raw.begin(); it != raw.end(); ++it)
        if (find_param(specs, it.key()) < 0)  // names the known ones
          resolve_method_param(method, it.key(), it.value(), params.child(it.key()));
      for (const ParamSpec& spec : specs) {
        if (!raw.contains(spec.name)) continue;
        const nlohmann::json& value = raw.at(spec.name);
        const std::string value_path = params.child(spec.name);
        ParamAxis axis;
        if (value.is_array()) {
          if (value.empty()) throw ScenarioError(value_path, "must list at least one value");
          for (size_t i = 0; i < value.size(); ++i)
            axis.values.push_back(resolve(method, spec, value[i], index_path(value_path, i)));
        } else {
          axis.values.push_back(resolve(method, spec, value, value_path));
        }
        axes.push_back(std::move(axis));
      }
    }
  }
  // cartesian product, the first parameter outermost
  size_t total = 1;
  for (const ParamAxis& axis : axes) {
    total *= axis.values.size();
    if (total > kMaxConfigs)
      throw ScenarioError(path, "spans more than " + std::to_string(kMaxConfigs) + " configurations");
  }
  std::vector<MethodConfig> out;
  for (size_t n = 0; n < total; ++n) {
    MethodConfig config{method, {}, ""};
    size_t rest = n, stride = total;
    for (const ParamAxis& axis : axes) {
      stride /= axis.values.size();
      config.params.push_back(axis.values[rest / stride]);
      rest %= stride;
    }
    config.key = method_config_key(method, config.params);
    out.push_back(std::move(config));
  }
  return out;
}

}  // namespace

std::string exact_number(double value) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return buf;
}

std::string method_config_key(const std::string& method, const std::vector<ParamValue>& params) {
  if (params.empty()) return method;
  std::string key = method + "{";
  for (size_t i = 0; i < params.size(); ++i) key += (i ? "," : "") + params[i].name + "=" + params[i].text;
  return key + "}";
}

std::vector<MethodConfig> parse_method_configs(const nlohmann::json& methods, const std::string& path) {
  if (!methods.is_array()) throw ScenarioError(path, "must be an array, got " + json_type_name(methods));
  if (methods.empty()) throw ScenarioError(path, "must list at least one method");
  std::vector<MethodConfig> out;
  std::map<std::string, size_t> seen;  // key -> methods[] index
  for (size_t i = 0; i < methods.size(); ++i) {
    const std::string entry_path = index_path(path, i);
    for (MethodConfig& config : configs_of_entry(methods[i], entry_path)) {
      config.entry = i;
      const auto [it, fresh] = seen.emplace(config.key, i);
      if (!fresh)
        throw ScenarioError(entry_path, "repeats the configuration " + config.key + " of " +
                                            index_path(path, it->second));
      out.push_back(std::move(config));
      if (out.size() > kMaxConfigs)
        throw ScenarioError(path, "spans more than " + std::to_string(kMaxConfigs) + " configurations");
    }
  }
  return out;
}

}  // namespace rrlab::sweep
