// Dispatch of generated scenario families, and what they share: the case's
// random stream and the document around the drawn parts. The families and
// their options: docs/generators.md, and the table at the top of each
// generator_<family>.cpp.
#include <rrlab/generators/generators.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <rrlab/generators/generator_case.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

// FNV-1a: the family name into the case key.
std::uint64_t name_hash(const std::string& name) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char ch : name) h = (h ^ ch) * 0x100000001b3ULL;
  return h;
}

std::uint64_t case_key(const std::string& family, std::uint64_t seed, int index) {
  SplitMix64 by_seed(seed ^ name_hash(family));
  SplitMix64 by_index(by_seed.next() + std::uint64_t(index) * 0x9e3779b97f4a7c15ULL);
  return by_index.next();
}

}  // namespace

GeneratorCase::GeneratorCase(std::string family_name, nlohmann::json case_options, std::uint64_t case_seed,
                             int case_index)
    : family(std::move(family_name)),
      options(std::move(case_options)),
      seed(case_seed),
      index(case_index),
      key(case_key(family, seed, index)),
      rng(key) {}

double rounded(double value, double step) {
  // dividing by the whole number 1/step gives the double nearest the decimal
  // (0.3263, not 0.32630000000000003), which JSON then writes as such
  const double per_unit = std::round(1.0 / step);
  return std::round(value * per_unit) / per_unit;
}

std::string fixed_digits(double value, int digits) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(digits);
  out << value;
  return out.str();
}

std::string case_title(const GeneratorCase& c) {
  return c.family + " case " + std::to_string(c.index) + " (seed " + std::to_string(c.seed) + ")";
}

nlohmann::json case_document(const GeneratorCase& c, const std::string& description, double dt, double duration,
                             const nlohmann::json& robot, const nlohmann::json& obstacles,
                             const nlohmann::json& task) {
  nlohmann::json doc;
  doc["name"] = c.family + "-" + std::to_string(c.index);
  doc["description"] = description;
  const nlohmann::json options = c.options.is_null() ? nlohmann::json::object() : c.options;
  doc["source"] = "rrlab generator: family " + c.family + ", seed " + std::to_string(c.seed) + ", index " +
                  std::to_string(c.index) + ", options " + options.dump();
  doc["dt"] = dt;
  doc["duration"] = duration;
  doc["seed"] = c.key >> 11;  // 53 bits: exact in any JSON reader
  doc["robot"] = robot;
  if (!obstacles.empty()) doc["obstacles"] = obstacles;
  doc["task"] = task;
  return doc;
}

void no_case_found(const GeneratorCase& c, const std::string& what_to_loosen) {
  throw ScenarioError("generator", c.family + ": no case met the family's conditions in " +
                                       std::to_string(kCaseAttempts) + " attempts (seed " +
                                       std::to_string(c.seed) + ", index " + std::to_string(c.index) +
                                       "); loosen " + what_to_loosen);
}

const std::vector<GeneratorFamily>& generator_family_table() {
  static const std::vector<GeneratorFamily> table = [] {
    std::vector<GeneratorFamily> rows = {
        {"planar_clutter", "a planar arm among static obstacles of mixed shapes", generate_planar_clutter},
        {"planar_limits", "a planar arm with joint limits, on a path that drives pinv past one", generate_planar_limits},
        {"narrow_passage", "a planar arm whose hand threads a gap between two walls", generate_narrow_passage},
        {"spatial_clutter", "a 7-DOF spatial DH arm among static obstacles", generate_spatial_clutter},
        {"moving_obstacles", "a planar arm and obstacles crossing its path at constant velocity",
         generate_moving_obstacles},
        {"urdf_tabletop", "a shipped URDF arm with a pose task over a cluttered table", generate_urdf_tabletop},
        {"urdf_shelf", "a shipped URDF arm with a pose task reaching into a shelf", generate_urdf_shelf},
    };
    // each obstacle family's cases without the obstacles placed on pinv's arm:
    // what blocking adds is the difference between the two
    for (const char* name : {"planar_clutter", "narrow_passage", "spatial_clutter", "moving_obstacles", "urdf_tabletop",
                             "urdf_shelf"}) {
      const GeneratorFamily base = *std::find_if(rows.begin(), rows.end(), [&](const GeneratorFamily& f) { return f.name == name; });
      rows.push_back({base.name + "_open", base.summary + ", without obstacles placed to block the minimum-norm solution",
                      base.generate, true});
    }
    return rows;
  }();
  return table;
}

const std::vector<std::string>& generator_families() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const GeneratorFamily& family : generator_family_table()) list.push_back(family.name);
    return list;
  }();
  return names;
}

namespace {

nlohmann::json generate(GeneratorCase& c) {
  for (const GeneratorFamily& family : generator_family_table())
    if (family.name == c.family) {
      c.open = family.open;
      return family.generate(c);
    }
  std::string known;
  for (const std::string& f : generator_families()) known += (known.empty() ? "" : ", ") + f;
  throw ScenarioError("generator", "unknown family \"" + c.family + "\" (known: " + known + ")");
}

}  // namespace

nlohmann::json generate_scenario(const std::string& family, const nlohmann::json& options, std::uint64_t seed,
                                 int index) {
  if (index < 0) throw ScenarioError("index", "must be >= 0, got " + std::to_string(index));
  GeneratorCase c(family, options, seed, index);
  return generate(c);
}

void check_generator_options(const std::string& family, const nlohmann::json& options) {
  GeneratorCase c(family, options, 0, 0);
  c.options_only = true;
  generate(c);
}

}  // namespace rrlab
