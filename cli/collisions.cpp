// `rrlab collisions SCENARIO`: the robot's allowed-collision matrix (which
// link pairs self-collision checks skip, and why) as JSON.
#include <algorithm>
#include <iostream>

#include <rrlab/collision/allowed_collisions.hpp>
#include <rrlab/scenario/scenario.hpp>

#include "cli.hpp"

namespace rrlab::cli {

namespace {

nlohmann::json links_json(const SelfPair& p) { return nlohmann::json::array({p.a + 1, p.b + 1}); }

nlohmann::json pairs_json(const std::vector<SelfPair>& pairs) {
  nlohmann::json out = nlohmann::json::array();
  for (const SelfPair& p : pairs) out.push_back(links_json(p));
  return out;
}

}  // namespace

int collisions(const std::string& scenario_file) {
  Scenario scenario;
  try {
    scenario = load_scenario_file(scenario_file);
  } catch (const std::exception& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  }
  const Model& model = scenario.model;
  nlohmann::json out = {{"scenario", scenario.name}, {"links", model.link_count()},
                        {"self_collision", !model.self_pairs.empty()}, {"checked", pairs_json(model.self_pairs)}};
  if (model.self_pairs.empty()) {
    std::cout << out.dump(2) << '\n';
    return 0;
  }
  const std::shared_ptr<const AllowedCollisionMatrix> matrix = allowed_collision_matrix(model);
  nlohmann::json allowed = nlohmann::json::array();
  for (const AllowedPair& p : matrix->allowed) allowed.push_back({{"links", links_json(p.pair)}, {"reason", to_string(p.reason)}});
  for (const SelfPair& p : matrix->checked)  // the scenario's own robot.allowed_collisions
    if (std::find(model.self_pairs.begin(), model.self_pairs.end(), p) == model.self_pairs.end())
      allowed.push_back({{"links", links_json(p)}, {"reason", to_string(AllowedReason::user)}});
  out["allowed"] = allowed;
  out["never_in_contact"] = pairs_json(matrix->never_in_contact);
  out["samples"] = matrix->samples;
  std::cout << out.dump(2) << '\n';
  return 0;
}

}  // namespace rrlab::cli
