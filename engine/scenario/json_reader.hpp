// Typed reading of JSON with paths in every error, and unknown keys rejected.
#pragma once

#include <Eigen/Core>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

std::string json_type_name(const nlohmann::json& value);
std::string index_path(const std::string& path, size_t index);

// One JSON object being read: check_keys() first rejects unknown keys (so a
// typo is reported as such), then fields are read by name.
class JsonObject {
 public:
  JsonObject(const nlohmann::json& value, std::string path);

  const std::string& path() const { return path_; }
  std::string child(const std::string& key) const;
  bool has(const std::string& key) const;
  const nlohmann::json& raw(const std::string& key);  // must exist

  double number(const std::string& key);
  double number(const std::string& key, double def);
  std::optional<double> optional_number(const std::string& key);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& def);
  bool boolean(const std::string& key, bool def);
  std::string choice(const std::string& key, std::initializer_list<const char*> options,
                     const char* def = nullptr);
  // A fixed-length or bounded-length array of numbers.
  std::vector<double> numbers(const std::string& key, size_t min_size, size_t max_size);
  JsonObject object(const std::string& key);
  const nlohmann::json& array(const std::string& key, size_t max_size);

  // Throws on the first key not in `allowed`, listing the allowed ones.
  void check_keys(std::initializer_list<const char*> allowed) const;

 private:
  const nlohmann::json& value_;
  std::string path_;
};

double json_number(const nlohmann::json& value, const std::string& path);
std::vector<double> json_numbers(const nlohmann::json& value, const std::string& path,
                                 size_t min_size, size_t max_size);

}  // namespace rrlab
