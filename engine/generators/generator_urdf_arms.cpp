#include <rrlab/generators/generator_urdf_arms.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include <rrlab/generators/generator_case.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

constexpr double kUrdfDrawShare = 0.9;  // of each joint's half range, around the middle

// The catalogue scenarios' starting postures (scenarios 40-42), in degrees.
const std::map<std::string, std::vector<double>>& ready_postures() {
  static const std::map<std::string, std::vector<double>> postures = {
      {"iiwa14", {0, 40, 0, -70, 0, 60, 0}},
      {"panda", {0, -20, 0, -120, 0, 100, 45}},
      {"gen3", {0, 20, 0, 100, 0, 60, 90}},
  };
  return postures;
}

nlohmann::json urdf_robot_json(const UrdfArmText& text) {
  return {{"kind", "urdf"}, {"urdf", text.urdf}, {"base_link", text.base_link}, {"tip_link", text.tip_link}};
}

// The model of a URDF arm, as a scenario carrying its robot object builds it.
Model parse_urdf_arm_model(const UrdfArmText& text) {
  nlohmann::json robot = urdf_robot_json(text);
  robot["q0"] = ready_postures().at(text.name);  // zeros are outside some arm's limits
  nlohmann::json doc = {{"name", "urdf-arm"},
                        {"dt", 0.01},
                        {"duration", 1.0},
                        {"angle_unit", "deg"},
                        {"robot", robot},
                        {"task",
                         {{"space", "xyz"},
                          {"trajectory", {{"type", "polyline"}, {"points", {{0.5, 0, 0.5}, {0.5, 0, 0.6}}}}}}}};
  return parse_scenario(doc).model;
}

const UrdfArmText& urdf_arm_text(const std::string& name) {
  for (const UrdfArmText& t : urdf_arm_texts())
    if (t.name == name) return t;
  throw ScenarioError("options.arms", "unknown arm \"" + name + "\"");
}

}  // namespace

std::vector<std::string> urdf_arm_names() {
  std::vector<std::string> names;
  for (const UrdfArmText& t : urdf_arm_texts()) names.push_back(t.name);
  return names;
}

std::vector<std::string> read_urdf_arms(const GeneratorOptions& options) {
  return options.subset("arms", urdf_arm_names(), urdf_arm_names());
}

GeneratedArm draw_urdf_arm(const std::vector<std::string>& arms, Rng& rng) {
  // parsed once per process: the models are the same for every case
  static const std::map<std::string, Model> models = [] {
    std::map<std::string, Model> out;
    for (const UrdfArmText& t : urdf_arm_texts()) out.emplace(t.name, parse_urdf_arm_model(t));
    return out;
  }();
  const std::string& name = arms[rng.below(arms.size())];
  const UrdfArmText& text = urdf_arm_text(name);
  GeneratedArm arm;
  arm.model = models.at(name);
  arm.robot = urdf_robot_json(text);
  arm.name = name;
  arm.reach = arm.model.reach();
  // a continuous joint (Gen3's 1, 3, 5, 7) has no position limits: its box is one turn, ±π
  const Eigen::VectorXd lower = arm.model.limits.lower.unaryExpr([](double v) { return std::isfinite(v) ? v : -M_PI; });
  const Eigen::VectorXd upper = arm.model.limits.upper.unaryExpr([](double v) { return std::isfinite(v) ? v : M_PI; });
  arm.draw_lower = 0.5 * (lower + upper) - 0.5 * kUrdfDrawShare * (upper - lower);
  arm.draw_upper = 0.5 * (lower + upper) + 0.5 * kUrdfDrawShare * (upper - lower);
  arm.link_radius = arm.model.links.back().radius;
  arm.summary = "the " + name + " URDF arm (" + std::to_string(arm.model.dof()) + " joints, reach " +
                fixed_digits(arm.reach, 3) + " m, its URDF joint limits)";
  return arm;
}

Eigen::VectorXd draw_ready_configuration(const GeneratedArm& arm, double spread, Rng& rng) {
  Eigen::VectorXd ready(arm.model.dof());
  const std::vector<double>& degrees = ready_postures().at(arm.name);
  for (Eigen::Index i = 0; i < ready.size(); ++i) ready[i] = degrees[size_t(i)] * M_PI / 180.0;
  return draw_configuration_near(arm, ready.cwiseMax(arm.draw_lower).cwiseMin(arm.draw_upper), spread, rng);
}

}  // namespace rrlab
