#include <rrlab/scenario/json_reader.hpp>

#include <algorithm>
#include <cmath>

namespace rrlab {

std::string json_type_name(const nlohmann::json& value) {
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_boolean()) return "a boolean";
  if (value.is_array()) return "an array";
  if (value.is_object()) return "an object";
  return "null";
}

std::string index_path(const std::string& path, size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

double json_number(const nlohmann::json& value, const std::string& path) {
  if (!value.is_number()) throw ScenarioError(path, "must be a number, got " + json_type_name(value));
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw ScenarioError(path, "must be a finite number");
  return v;
}

std::vector<double> json_numbers(const nlohmann::json& value, const std::string& path,
                                 size_t min_size, size_t max_size) {
  if (!value.is_array()) throw ScenarioError(path, "must be an array of numbers, got " + json_type_name(value));
  if (value.size() < min_size || value.size() > max_size) {
    const std::string want = min_size == max_size
                                 ? std::to_string(min_size)
                                 : std::to_string(min_size) + " to " + std::to_string(max_size);
    throw ScenarioError(path, "must have " + want + " numbers, got " + std::to_string(value.size()));
  }
  std::vector<double> out;
  out.reserve(value.size());
  for (size_t i = 0; i < value.size(); ++i) out.push_back(json_number(value[i], index_path(path, i)));
  return out;
}

JsonObject::JsonObject(const nlohmann::json& value, std::string path)
    : value_(value), path_(std::move(path)) {
  if (!value_.is_object())
    throw ScenarioError(path_, "must be an object, got " + json_type_name(value_));
}

std::string JsonObject::child(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool JsonObject::has(const std::string& key) const { return value_.contains(key); }

const nlohmann::json& JsonObject::raw(const std::string& key) {
  if (!value_.contains(key)) throw ScenarioError(child(key), "is required");
  return value_.at(key);
}

double JsonObject::number(const std::string& key) { return json_number(raw(key), child(key)); }

double JsonObject::number(const std::string& key, double def) {
  return optional_number(key).value_or(def);
}

std::optional<double> JsonObject::optional_number(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return json_number(value_.at(key), child(key));
}

std::string JsonObject::string(const std::string& key) {
  const nlohmann::json& v = raw(key);
  if (!v.is_string()) throw ScenarioError(child(key), "must be a string, got " + json_type_name(v));
  return v.get<std::string>();
}

std::string JsonObject::string(const std::string& key, const std::string& def) {
  return has(key) ? string(key) : def;
}

bool JsonObject::boolean(const std::string& key, bool def) {
  if (!has(key)) return def;
  const nlohmann::json& v = raw(key);
  if (!v.is_boolean()) throw ScenarioError(child(key), "must be true or false, got " + json_type_name(v));
  return v.get<bool>();
}

std::string JsonObject::choice(const std::string& key, std::initializer_list<const char*> options,
                               const char* def) {
  if (!has(key) && def) return def;
  const std::string v = string(key);
  for (const char* option : options)
    if (v == option) return v;
  std::string list;
  for (const char* option : options) list += (list.empty() ? "" : ", ") + std::string(option);
  throw ScenarioError(child(key), "unknown value \"" + v + "\" (expected one of: " + list + ")");
}

std::vector<double> JsonObject::numbers(const std::string& key, size_t min_size, size_t max_size) {
  return json_numbers(raw(key), child(key), min_size, max_size);
}

JsonObject JsonObject::object(const std::string& key) { return JsonObject(raw(key), child(key)); }

const nlohmann::json& JsonObject::array(const std::string& key, size_t max_size) {
  const nlohmann::json& v = raw(key);
  if (!v.is_array()) throw ScenarioError(child(key), "must be an array, got " + json_type_name(v));
  if (v.size() > max_size)
    throw ScenarioError(child(key), "has " + std::to_string(v.size()) + " entries, at most " +
                                        std::to_string(max_size) + " allowed");
  return v;
}

void JsonObject::check_keys(std::initializer_list<const char*> allowed) const {
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    const std::string& key = it.key();
    if (std::find_if(allowed.begin(), allowed.end(), [&](const char* k) { return key == k; }) !=
        allowed.end())
      continue;
    std::string list;
    for (const char* k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
    throw ScenarioError(child(key), "unknown key (allowed here: " + list + ")");
  }
}

}  // namespace rrlab
