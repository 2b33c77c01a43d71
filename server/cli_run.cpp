#include <iostream>

#include "cli.hpp"
#include "csv_recorder.hpp"
#include "methods/registry.hpp"
#include "scenario/scenario.hpp"
#include "sim/simulator.hpp"

namespace rrlab::cli {

namespace {

int bad_input(const std::string& message) {
  std::cerr << "rrlab: error: " << message << '\n';
  return 2;
}

// "--param NAME=VALUE": VALUE is a number or an enumeration label.
std::pair<std::string, double> parse_param(const std::string& method, const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ScenarioError("--param " + text, "must be NAME=VALUE");
  const std::string name = text.substr(0, eq), value = text.substr(eq + 1);
  nlohmann::json v = value;
  try {
    size_t used = 0;
    const double number = std::stod(value, &used);
    if (used == value.size()) v = number;
  } catch (const std::exception&) {
  }
  return resolve_method_param(method, name, v, "--param " + name);
}

}  // namespace

int run(const RunOptions& options) {
  try {
    Scenario scenario = load_scenario_file(options.scenario_file);
    if (options.method && *options.method != scenario.method.name) {
      if (!find_method(*options.method))
        throw ScenarioError("--method", "unknown method \"" + *options.method + "\" (known: " +
                                            method_names() + ")");
      scenario.method.name = *options.method;
      scenario.method.params.clear();  // the scenario's parameters belong to its own method
    }
    for (const std::string& text : options.params)
      scenario.method.params.push_back(parse_param(scenario.method.name, text));

    Simulator sim(scenario);
    if (options.steps) {
      if (*options.steps < 1 || *options.steps > ScenarioLimits::max_steps)
        throw ScenarioError("--steps", "must be in [1, " + std::to_string(ScenarioLimits::max_steps) + "]");
      sim.set_total_steps(*options.steps);
    }
    std::unique_ptr<CsvRecorder> csv;
    if (options.out_csv) csv = std::make_unique<CsvRecorder>(*options.out_csv);
    const Summary summary = run_to_end(sim, csv.get());
    std::cout << summary_to_json(summary).dump() << '\n';
    return 0;
  } catch (const ScenarioError& e) {
    return bad_input(e.what());
  } catch (const ParamError& e) {
    return bad_input(std::string("method.params.") + e.what());
  } catch (const std::exception& e) {
    return bad_input(e.what());
  }
}

}  // namespace rrlab::cli
