// rrlab generate FAMILY --seed S --count N [--first I] [--option KEY=VALUE ...] --out DIR:
// the cases a sweep entry {"generator": FAMILY, "seed": S, "count": N, KEY: VALUE}
// runs, as scenario files DIR/FAMILY-INDEX.json (witness included); with
// --cases I,J,... exactly those indices (the unsolved cases a report lists).
// rrlab generate --perturb SCENARIO ... likewise writes the cases of a sweep
// entry {"perturb": SCENARIO, ...} as DIR/NAME-pINDEX.json; a dotted KEY
// (obstacles.shift=0.03) sets a key of an object option.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

#include <rrlab/generators/generators.hpp>
#include <rrlab/generators/perturbation.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sweep/sweep_spec.hpp>
#include <rrlab/util/nesting_depth.hpp>

#include "cli.hpp"

namespace rrlab::cli {

namespace {

constexpr size_t kMaxCases = 1'000'000;  // as --count

// KEY=VALUE: VALUE as JSON (numbers, [min, max], arrays of names), else as a
// string; KEY may be dotted (a.b: key b of object option a).
void add_option(nlohmann::json& options, const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ScenarioError("--option", "expects KEY=VALUE, got '" + text + "'");
  const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  nlohmann::json* at = &options;
  size_t from = 0;
  for (size_t dot; (dot = key.find('.', from)) != std::string::npos; from = dot + 1) {
    nlohmann::json& next = (*at)[key.substr(from, dot - from)];
    if (next.is_null()) next = nlohmann::json::object();
    if (!next.is_object()) throw ScenarioError("--option", "'" + key + "': " + key.substr(0, dot) + " is not an object");
    at = &next;
  }
  try {
    (*at)[key.substr(from)] = parse_json(value);
  } catch (const std::exception&) {
    (*at)[key.substr(from)] = value;
  }
}

// The perturbation entry the options describe, read as a sweep reads it.
sweep::ScenarioEntry perturbation_entry(const GenerateOptions& options, const nlohmann::json& keys) {
  nlohmann::json entry = keys;
  entry["perturb"] = options.perturb;
  entry["count"] = options.count;
  entry["seed"] = options.seed;
  const std::string scenarios = find_dir(options.scenarios_dir, "scenarios");
  return sweep::parse_scenario_entry(entry, "--perturb", {".", scenarios});
}

// The indices to write: --cases as given (each once), else --first onwards.
std::vector<int> case_indices(const GenerateOptions& options) {
  if (options.cases.empty()) {
    std::vector<int> indices(size_t(options.count));
    for (int i = 0; i < options.count; ++i) indices[size_t(i)] = options.first + i;
    return indices;
  }
  if (options.cases.size() > kMaxCases)
    throw ScenarioError("--cases", "at most " + std::to_string(kMaxCases) + " indices, got " + std::to_string(options.cases.size()));
  std::set<int> seen;
  for (int index : options.cases)
    if (!seen.insert(index).second) throw ScenarioError("--cases", "index " + std::to_string(index) + " is given twice");
  return options.cases;
}

}  // namespace

int generate(const GenerateOptions& options) {
  try {
    if (options.list) {  // the generator registry, for scripts (scripts/benchmark-table)
      for (const GeneratorFamily& family : generator_family_table()) std::cout << family.name << '\t' << family.summary << '\n';
      return 0;
    }
    if (options.out_dir.empty()) {
      std::cerr << "rrlab: error: generate needs --out DIR\n";
      return 2;
    }
    nlohmann::json family_options = nlohmann::json::object();
    for (const std::string& text : options.options) add_option(family_options, text);
    if (options.family.empty() == options.perturb.empty()) {
      std::cerr << "rrlab: error: generate needs a FAMILY or --perturb SCENARIO (one of them)\n";
      return 2;
    }
    const std::vector<int> indices = case_indices(options);
    std::optional<sweep::ScenarioEntry> perturbed;
    if (!options.perturb.empty()) perturbed = perturbation_entry(options, family_options);
    std::error_code error;
    std::filesystem::create_directories(options.out_dir, error);
    if (error) {
      std::cerr << "rrlab: error: --out: cannot create '" << options.out_dir << "': " << error.message() << '\n';
      return 2;
    }
    for (const int index : indices) {
      const nlohmann::json doc =
          perturbed ? perturb_scenario(perturbed->scenario->json, perturbed->dir, perturbed->name, perturbed->perturbation,
                                       perturbed->perturbation_scale, options.seed, index)
                    : generate_scenario(options.family, family_options, options.seed, index);
      parse_scenario(doc, perturbed ? perturbed->dir : std::string());  // what a run of the file will read
      const std::filesystem::path file =
          std::filesystem::path(options.out_dir) / (doc["name"].get<std::string>() + ".json");
      std::ofstream out(file);
      out << doc.dump(1) << '\n';
      if (!out) {
        std::cerr << "rrlab: error: --out: cannot write '" << file.string() << "'\n";
        return 2;
      }
      std::cout << file.string() << '\n';
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace rrlab::cli
