// What every generated-scenario family works with: the case being drawn (its
// seeded random stream), the finished document, and the family functions
// generate_scenario() dispatches to. Internal to engine/scenario.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include <rrlab/util/rng.hpp>

namespace rrlab {

// One case: (family, options, seed, index) and the random stream drawn from
// them alone.
struct GeneratorCase {
  GeneratorCase(std::string family, nlohmann::json options, std::uint64_t seed, int index);

  std::string family;
  nlohmann::json options;
  std::uint64_t seed;
  int index;
  std::uint64_t key;  // mixed from family, seed and index: seeds `rng`
  Rng rng;
  // check_generator_options(): the family reads its options (throwing for a
  // bad one) and returns null before drawing anything
  bool options_only = false;
  // the family's _open variant: no obstacle is placed to block the
  // minimum-norm solution (options "blocking" and "block_pinv" refused)
  bool open = false;
};

// Drawn quantities are rounded to this step (m or rad) so documents read well;
// everything derived (end-effector waypoints) is computed from rounded values.
constexpr double kDrawStep = 1e-4;
double rounded(double value, double step = kDrawStep);

// `value` with `digits` decimals, for descriptions.
std::string fixed_digits(double value, int digits);

// How many whole cases a family draws before giving up (ScenarioError at
// "generator" naming the options to loosen).
constexpr int kCaseAttempts = 200;

// The scenario document of a case: name "<family>-<index>", the description,
// a source line that records family, seed, index and options, a method-level
// seed from the case, and the given parts. `obstacles` may be empty.
nlohmann::json case_document(const GeneratorCase& c, const std::string& description, double dt, double duration,
                             const nlohmann::json& robot, const nlohmann::json& obstacles,
                             const nlohmann::json& task);

// "planar_clutter case 17 (seed 42)": how descriptions begin.
std::string case_title(const GeneratorCase& c);

// The ScenarioError a family throws when no case passed within kCaseAttempts.
[[noreturn]] void no_case_found(const GeneratorCase& c, const std::string& what_to_loosen);

nlohmann::json generate_planar_clutter(GeneratorCase& c);
nlohmann::json generate_planar_limits(GeneratorCase& c);
nlohmann::json generate_narrow_passage(GeneratorCase& c);
nlohmann::json generate_spatial_clutter(GeneratorCase& c);
nlohmann::json generate_moving_obstacles(GeneratorCase& c);
nlohmann::json generate_urdf_tabletop(GeneratorCase& c);
nlohmann::json generate_urdf_shelf(GeneratorCase& c);

}  // namespace rrlab
