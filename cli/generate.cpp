// rrlab generate FAMILY --seed S --count N [--first I] [--option KEY=VALUE ...] --out DIR:
// the cases a sweep entry {"generator": FAMILY, "seed": S, "count": N, KEY: VALUE}
// runs, as scenario files DIR/FAMILY-INDEX.json (witness included).
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli.hpp"
#include "scenario/generators.hpp"
#include "scenario/scenario.hpp"
#include "util/nesting_depth.hpp"

namespace rrlab::cli {

namespace {

// KEY=VALUE: VALUE as JSON (numbers, [min, max], arrays of names), else as a string.
void add_option(nlohmann::json& options, const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ScenarioError("--option", "expects KEY=VALUE, got '" + text + "'");
  const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  try {
    options[key] = parse_json(value);
  } catch (const std::exception&) {
    options[key] = value;
  }
}

}  // namespace

int generate(const GenerateOptions& options) {
  try {
    nlohmann::json family_options = nlohmann::json::object();
    for (const std::string& text : options.options) add_option(family_options, text);
    std::error_code error;
    std::filesystem::create_directories(options.out_dir, error);
    if (error) {
      std::cerr << "rrlab: error: --out: cannot create '" << options.out_dir << "': " << error.message() << '\n';
      return 2;
    }
    for (int i = 0; i < options.count; ++i) {
      const int index = options.first + i;
      const nlohmann::json doc = generate_scenario(options.family, family_options, options.seed, index);
      parse_scenario(doc);  // what a run of the file will read
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
