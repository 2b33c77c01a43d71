// Random arms of generated scenarios, and random configurations of them:
// planar chains (optionally with symmetric joint limits) and 7-DOF DH arms
// in the manner of a KUKA LBR iiwa. Each comes as the document's "robot"
// (without q0) and the engine Model the document describes.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include <rrlab/generators/generator_options.hpp>
#include <rrlab/model/model.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

struct GeneratedArm {
  Model model;             // links and limits as the document gives them
  nlohmann::json robot;    // the document's "robot", q0 still to set
  Eigen::VectorXd draw_lower, draw_upper;  // the box configurations are drawn from
  double reach = 0;        // Model::reach(): no hand position is farther from the base
  double hole_radius = 0;  // around the base, unreachable by the hand (planar arms without limits)
  double link_radius = 0;  // of the hand's link
  std::string summary;     // for descriptions: "a 7-DOF planar arm (links ...)"
  std::string name;        // shipped URDF arms: "iiwa14", "panda", "gen3"
};

// Options "dof", "link_length", "link_radius" (planar) and "limit_deg"
// (planar_limits); see docs/generators.md.
struct PlanarArmOptions {
  IntRange dof{3, 12};
  Range link_length{0.2, 0.6};
  double link_radius = 0.02;
  std::optional<Range> limit_deg;  // half-range of each joint's symmetric limits
};
PlanarArmOptions read_planar_arm_options(const GeneratorOptions& options, bool with_limits);

// Options "length_scale", "a_offset", "link_radius" (spatial_clutter).
struct DhArmOptions {
  Range length_scale{0.8, 1.2};
  Range a_offset{-0.05, 0.05};
  double link_radius = 0.05;
};
DhArmOptions read_dh_arm_options(const GeneratorOptions& options);

GeneratedArm draw_planar_arm(const PlanarArmOptions& options, Rng& rng);
GeneratedArm draw_dh7_arm(const DhArmOptions& options, Rng& rng);

// A configuration uniform in the arm's draw box (rounded to kDrawStep).
Eigen::VectorXd draw_configuration(const GeneratedArm& arm, Rng& rng);

// A configuration uniform in the box of +-step (rad) around `from`, within the draw box.
Eigen::VectorXd draw_configuration_near(const GeneratedArm& arm, const Eigen::VectorXd& from, double step, Rng& rng);

// The document's "robot" with q0 set.
nlohmann::json robot_with_q0(const GeneratedArm& arm, const Eigen::VectorXd& q0);

}  // namespace rrlab
