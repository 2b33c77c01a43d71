#include "scenario/generators.hpp"

#include "scenario/scenario.hpp"

namespace rrlab {

const std::vector<std::string>& generator_families() {
  static const std::vector<std::string> families = {"planar_clutter", "planar_limits", "narrow_passage",
                                                    "spatial_clutter", "moving_obstacles"};
  return families;
}

nlohmann::json generate_scenario(const std::string& family, const nlohmann::json&, std::uint64_t, int) {
  throw ScenarioError("generator", "family '" + family + "' is not implemented yet");
}

}  // namespace rrlab
