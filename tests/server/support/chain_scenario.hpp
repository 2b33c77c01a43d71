// A planar chain of `dof` links (2 m in all) tracing a circle with pinv for
// `steps` frames: a run as large as a test needs (exports, soak).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rrlab::testing {

inline nlohmann::json chain_scenario(const std::string& name, int dof, int steps) {
  using nlohmann::json;
  json links = json::array();
  for (int i = 0; i < dof; ++i) links.push_back({{"length", 2.0 / dof}, {"radius", 0.005}});
  return {{"name", name},
          {"dt", 0.01},
          {"duration", steps * 0.01},
          {"angle_unit", "deg"},
          {"robot", {{"kind", "planar"}, {"base", {0, 0}}, {"links", links}, {"q0", std::vector<double>(dof, 5.0)}}},
          {"task",
           {{"space", "xy"},
            {"trajectory", {{"type", "circle"}, {"center", {1.2, 0.3}}, {"radius", 0.2}, {"direction", "ccw"}}}}},
          {"method", {{"name", "pinv"}}}};
}

}  // namespace rrlab::testing
