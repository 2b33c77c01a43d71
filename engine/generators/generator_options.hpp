// The options of a generated scenario family, read with errors that name
// "options.<key>": unknown keys are rejected, values outside the allowed range
// are reported with that range. A range option takes a number (a fixed
// value) or [min, max] (drawn per case).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <rrlab/util/rng.hpp>

namespace rrlab {

struct Range {
  double min = 0, max = 0;
  double draw(Rng& rng) const { return min == max ? min : rng.uniform(min, max); }
};
// `r` times `factor` (a size in reaches, in metres).
inline Range scaled(Range r, double factor) { return {r.min * factor, r.max * factor}; }

struct IntRange {
  int min = 0, max = 0;
  int draw(Rng& rng) const { return min + int(rng.below(std::uint64_t(max - min) + 1)); }
};

class GeneratorOptions {
 public:
  // `options` is an object or null (no options); `family` names the family
  // in the unknown-key error, `known` lists its keys.
  GeneratorOptions(const nlohmann::json& options, const std::string& family, std::vector<std::string> known);

  bool has(const std::string& key) const;
  // A number or [min, max] within `allowed` (inclusive).
  Range range(const std::string& key, Range def, Range allowed) const;
  IntRange int_range(const std::string& key, IntRange def, IntRange allowed) const;
  double number(const std::string& key, double def, Range allowed) const;
  bool boolean(const std::string& key, bool def) const;
  std::string choice(const std::string& key, const std::vector<std::string>& values, const std::string& def) const;
  // A non-empty array of distinct entries of `values`.
  std::vector<std::string> subset(const std::string& key, const std::vector<std::string>& values,
                                  const std::vector<std::string>& def) const;

 private:
  std::string path(const std::string& key) const { return "options." + key; }

  nlohmann::json options_;
};

}  // namespace rrlab
