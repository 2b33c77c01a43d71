#include <rrlab/generators/generator_options.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

std::string format(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string joined(const std::vector<std::string>& values) {
  std::string list;
  for (const std::string& v : values) list += (list.empty() ? "" : ", ") + v;
  return list;
}

void require_within(double v, Range allowed, const std::string& path) {
  if (v < allowed.min || v > allowed.max)
    throw ScenarioError(path, format(v) + " is outside the allowed range [" + format(allowed.min) + ", " +
                                  format(allowed.max) + "]");
}

}  // namespace

GeneratorOptions::GeneratorOptions(const nlohmann::json& options, const std::string& family,
                                   std::vector<std::string> known)
    : options_(options.is_null() ? nlohmann::json::object() : options) {
  if (!options_.is_object())
    throw ScenarioError("options", "must be an object, got " + json_type_name(options_));
  for (auto it = options_.begin(); it != options_.end(); ++it)
    if (std::find(known.begin(), known.end(), it.key()) == known.end())
      throw ScenarioError(path(it.key()), "unknown option of " + family + " (known: " + joined(known) + ")");
}

bool GeneratorOptions::has(const std::string& key) const { return options_.contains(key); }

Range GeneratorOptions::range(const std::string& key, Range def, Range allowed) const {
  if (!has(key)) return def;
  const nlohmann::json& v = options_.at(key);
  const std::string at = path(key);
  Range r;
  if (v.is_number()) {
    r.min = r.max = json_number(v, at);
    require_within(r.min, allowed, at);
    return r;
  }
  if (!v.is_array() || v.size() != 2)
    throw ScenarioError(at, "must be a number or [min, max], got " + json_type_name(v));
  r.min = json_number(v[0], index_path(at, 0));
  r.max = json_number(v[1], index_path(at, 1));
  require_within(r.min, allowed, index_path(at, 0));
  require_within(r.max, allowed, index_path(at, 1));
  if (r.min > r.max) throw ScenarioError(at, "min " + format(r.min) + " is above max " + format(r.max));
  return r;
}

IntRange GeneratorOptions::int_range(const std::string& key, IntRange def, IntRange allowed) const {
  if (!has(key)) return def;
  const Range r = range(key, {double(def.min), double(def.max)}, {double(allowed.min), double(allowed.max)});
  if (r.min != std::floor(r.min) || r.max != std::floor(r.max))
    throw ScenarioError(path(key), "must be an integer or [min, max] of integers");
  return {int(r.min), int(r.max)};
}

double GeneratorOptions::number(const std::string& key, double def, Range allowed) const {
  if (!has(key)) return def;
  const double v = json_number(options_.at(key), path(key));
  require_within(v, allowed, path(key));
  return v;
}

bool GeneratorOptions::boolean(const std::string& key, bool def) const {
  if (!has(key)) return def;
  const nlohmann::json& v = options_.at(key);
  if (!v.is_boolean()) throw ScenarioError(path(key), "must be true or false, got " + json_type_name(v));
  return v.get<bool>();
}

std::string GeneratorOptions::choice(const std::string& key, const std::vector<std::string>& values,
                                     const std::string& def) const {
  if (!has(key)) return def;
  const nlohmann::json& v = options_.at(key);
  if (v.is_string() && std::find(values.begin(), values.end(), v.get<std::string>()) != values.end())
    return v.get<std::string>();
  throw ScenarioError(path(key), "must be one of: " + joined(values) + " (got " +
                                     (v.is_string() ? "\"" + v.get<std::string>() + "\"" : json_type_name(v)) + ")");
}

std::vector<std::string> GeneratorOptions::subset(const std::string& key, const std::vector<std::string>& values,
                                                  const std::vector<std::string>& def) const {
  if (!has(key)) return def;
  const nlohmann::json& v = options_.at(key);
  const std::string at = path(key);
  if (!v.is_array() || v.empty())
    throw ScenarioError(at, "must be a non-empty array of: " + joined(values));
  std::vector<std::string> chosen;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string entry_path = index_path(at, i);
    if (!v[i].is_string() || std::find(values.begin(), values.end(), v[i].get<std::string>()) == values.end())
      throw ScenarioError(entry_path, "must be one of: " + joined(values));
    if (std::find(chosen.begin(), chosen.end(), v[i].get<std::string>()) != chosen.end())
      throw ScenarioError(entry_path, "repeats \"" + v[i].get<std::string>() + "\"");
    chosen.push_back(v[i].get<std::string>());
  }
  return chosen;
}

}  // namespace rrlab
