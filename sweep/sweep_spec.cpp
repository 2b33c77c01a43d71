#include <rrlab/sweep/sweep_spec.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <rrlab/generators/generators.hpp>
#include <rrlab/methods/method.hpp>
#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab::sweep {

namespace {

constexpr int kMaxCount = 1'000'000;
constexpr size_t kMaxEntries = 10'000;

std::uint64_t non_negative_integer(const nlohmann::json& value, const std::string& path) {
  if (!value.is_number_integer() || value.get<long long>() < 0)
    throw ScenarioError(path, "must be a non-negative integer, got " + (value.is_number() ? value.dump() : json_type_name(value)));
  return value.get<std::uint64_t>();
}

std::string prefixed(const std::string& prefix, const ScenarioError& e) {
  return e.path().empty() ? prefix : prefix + "." + e.path();
}

// The message without its "path: " prefix.
std::string bare_message(const ScenarioError& e) {
  const std::string what = e.what();
  return e.path().empty() ? what : what.substr(e.path().size() + 2);
}

// Each entry's count, an integer in [1, kMaxCount].
int entry_count(JsonObject& object) {
  const double count = object.number("count");
  // the range first: casting a double beyond long is undefined behaviour
  if (!(count >= 1 && count <= kMaxCount) || count != double(long(count)))
    throw ScenarioError(object.child("count"), "must be an integer in [1, " + std::to_string(kMaxCount) + "]");
  return int(count);
}

ScenarioEntry file_entry(const std::string& text, const std::string& path, const SpecDirs& dirs) {
  ScenarioEntry entry;
  entry.family = "file";
  std::filesystem::path file;
  const bool is_path = text.find('/') != std::string::npos || text.ends_with(".json");
  if (is_path) {
    file = std::filesystem::path(text).is_absolute() ? std::filesystem::path(text) : dirs.spec_dir / text;
    entry.name = file.stem().string();
  } else {
    if (!is_plain_name(text))
      throw ScenarioError(path, "\"" + text + "\" is neither a catalogue name ([A-Za-z0-9_.-]) nor a path ending in .json");
    file = dirs.scenarios_dir / (text + ".json");
    entry.name = text;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw ScenarioError(path, is_path ? "no scenario file '" + file.string() + "'"
                                      : "no catalogue scenario '" + text + "' (" + file.string() + ")");
  entry.dir = file.parent_path().string();
  try {
    entry.scenario = load_scenario_file(file.string());
  } catch (const ScenarioError& e) {
    throw ScenarioError(prefixed(path, e), bare_message(e));
  }
  return entry;
}

ScenarioEntry generator_entry(const nlohmann::json& value, const std::string& path) {
  JsonObject object(value, path);
  ScenarioEntry entry;
  entry.family = object.string("generator");
  const auto& families = generator_families();
  if (std::find(families.begin(), families.end(), entry.family) == families.end()) {
    std::string known;
    for (const std::string& f : families) known += (known.empty() ? "" : ", ") + f;
    throw ScenarioError(object.child("generator"), "unknown family \"" + entry.family + "\" (known: " + known + ")");
  }
  entry.count = entry_count(object);
  entry.seed = object.has("seed") ? non_negative_integer(object.raw("seed"), object.child("seed")) : 1;
  entry.name = entry.family;
  for (auto it = value.begin(); it != value.end(); ++it)
    if (it.key() != "generator" && it.key() != "count" && it.key() != "seed") entry.options[it.key()] = it.value();
  // the options are checked, not a case generated (that can take tens of
  // milliseconds, and a spec may have thousands of entries)
  try {
    check_generator_options(entry.family, entry.options);
  } catch (const ScenarioError& e) {
    std::string at = e.path();
    if (at.starts_with("options.")) at = at.substr(8);
    const std::string message = bare_message(e);
    throw ScenarioError(at.empty() ? path : path + "." + at, message);
  }
  return entry;
}

// {"perturb": SCENARIO, "count", "seed", "obstacles", "speed", "q0_self_motion", "path"}
ScenarioEntry perturb_entry(const nlohmann::json& value, const std::string& path, const SpecDirs& dirs) {
  JsonObject object(value, path);
  object.check_keys({"perturb", "count", "seed", "obstacles", "speed", "q0_self_motion", "path"});
  ScenarioEntry entry = file_entry(object.string("perturb"), object.child("perturb"), dirs);
  entry.family = "perturb:" + entry.name;
  entry.count = entry_count(object);
  entry.seed = object.has("seed") ? non_negative_integer(object.raw("seed"), object.child("seed")) : 1;
  for (auto it = value.begin(); it != value.end(); ++it)
    if (it.key() != "perturb" && it.key() != "count" && it.key() != "seed") entry.options[it.key()] = it.value();
  entry.perturbation = parse_perturbation_options(value, path);
  if (entry.perturbation.sized_to_scene()) entry.perturbation_scale = perturbation_scale(*entry.scenario);
  return entry;
}

// Builds each file scenario's simulator and installs each configuration's
// method with its parameters, so that a parameter a scenario cannot take
// (ccp_link past its links) is bad input now. One simulator per scenario:
// a configuration costs its method's construction (none when it only
// changes the values of the previous one's parameters), so a grid of 100,000
// configurations is checked in a fraction of a second.
void check_configs_on_files(const SweepSpec& spec) {
  for (size_t s = 0; s < spec.scenarios.size(); ++s) {
    if (!spec.scenarios[s].scenario || spec.configs.empty()) continue;
    std::optional<Simulator> sim;
    std::string installed;  // the method and the names of the parameters set on it
    for (const MethodConfig& config : spec.configs) {
      try {
        std::string names = config.method;
        for (const ParamValue& p : config.params) names += ' ' + p.name;
        if (!sim) {
          Scenario scenario = *spec.scenarios[s].scenario;
          scenario.method.name = config.method;
          scenario.method.params.clear();
          sim.emplace(scenario);
        } else if (names != installed) {
          sim->switch_method(config.method);
        }
        installed = names;
        for (const ParamValue& p : config.params) sim->set_param(p.name, p.value);
      } catch (const ParamError& e) {
        throw ScenarioError(index_path("methods", config.entry),
                            config.key + " on " + index_path("scenarios", s) + ": " + e.what());
      } catch (const ScenarioError& e) {
        throw ScenarioError(index_path("methods", config.entry),
                            config.key + " on " + index_path("scenarios", s) + ": " + e.what());
      }
    }
  }
}

}  // namespace

std::string ScenarioEntry::case_key(int index) const {
  if (!generated()) return "file:" + name;
  if (perturbs()) return family + ":" + std::to_string(seed) + ":" + std::to_string(index);
  return "gen:" + family + ":" + std::to_string(seed) + ":" + std::to_string(index);
}

bool is_plain_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-')) return false;
  return true;
}

ScenarioEntry parse_scenario_entry(const nlohmann::json& value, const std::string& path, const SpecDirs& dirs) {
  if (value.is_string()) return file_entry(value.get<std::string>(), path, dirs);
  if (value.is_object() && value.contains("perturb")) return perturb_entry(value, path, dirs);
  if (value.is_object()) return generator_entry(value, path);
  throw ScenarioError(path, "must be a path, a catalogue name, {\"generator\", ...} or {\"perturb\", ...}, got " +
                                json_type_name(value));
}

SweepSpec parse_sweep_spec(const nlohmann::json& doc, const SpecDirs& dirs) {
  JsonObject root(doc, "");
  root.check_keys({"name", "description", "scenarios", "methods", "seeds", "success", "steps"});
  SweepSpec spec;
  spec.name = root.string("name");
  if (!is_plain_name(spec.name)) throw ScenarioError("name", "must match [A-Za-z0-9_.-]{1,64}");
  if (root.has("description")) root.string("description");

  const nlohmann::json& scenarios = root.array("scenarios", kMaxEntries);
  if (scenarios.empty()) throw ScenarioError("scenarios", "must list at least one scenario");
  std::map<std::string, size_t> seen;  // entry identity -> index
  for (size_t i = 0; i < scenarios.size(); ++i) {
    const std::string path = index_path("scenarios", i);
    const nlohmann::json& value = scenarios[i];
    spec.scenarios.push_back(parse_scenario_entry(value, path, dirs));
    const ScenarioEntry& entry = spec.scenarios.back();
    const std::string identity = entry.perturbs()    ? entry.family + ":" + std::to_string(entry.seed)
                                 : entry.generated() ? "gen:" + entry.family + ":" + std::to_string(entry.seed)
                                                     : entry.case_key(0);
    const auto [it, fresh] = seen.emplace(identity, i);
    if (!fresh)
      throw ScenarioError(path, "gives the same case keys (" + identity + ") as " + index_path("scenarios", it->second) +
                                    (entry.generated() ? ": give it another seed" : ""));
  }

  spec.configs = parse_method_configs(root.raw("methods"), "methods");

  if (root.has("seeds")) {
    const nlohmann::json& seeds = root.array("seeds", 100000);
    if (seeds.empty()) throw ScenarioError("seeds", "must list at least one seed (or be left out)");
    std::set<std::uint64_t> distinct;
    for (size_t i = 0; i < seeds.size(); ++i) {
      const std::uint64_t seed = non_negative_integer(seeds[i], index_path("seeds", i));
      if (!distinct.insert(seed).second) throw ScenarioError(index_path("seeds", i), "repeats seed " + std::to_string(seed));
      spec.seeds.push_back(seed);
    }
  }
  spec.success = parse_success_criteria(root.raw("success"), "success");
  if (root.has("steps")) {
    const double steps = root.number("steps");
    if (!(steps >= 1 && steps <= double(ScenarioLimits::max_steps)) || steps != double(long(steps)))
      throw ScenarioError("steps", "must be an integer in [1, " + std::to_string(ScenarioLimits::max_steps) + "]");
    spec.steps = long(steps);
  }
  check_configs_on_files(spec);
  return spec;
}

SweepSpec load_sweep_spec(const std::string& file, const std::filesystem::path& scenarios_dir) {
  const nlohmann::json doc = read_json_file(file, "sweep spec");
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  return parse_sweep_spec(doc, {parent.empty() ? std::filesystem::path(".") : parent, scenarios_dir});
}

}  // namespace rrlab::sweep
