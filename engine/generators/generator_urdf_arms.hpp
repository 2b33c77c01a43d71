// The shipped URDF arms (KUKA LBR iiwa 14, Franka Panda, Kinova Gen3, from
// scenarios/robots) as arms of generated scenarios: the URDF text is compiled
// in and written inline into each case ("robot": {"kind": "urdf", "urdf":
// ...}), so a case needs no file to run or to reproduce.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_options.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

struct UrdfArmText {
  std::string name, base_link, tip_link, urdf;
};
// iiwa14, panda, gen3 (generated from scenarios/robots/*.urdf at build time).
const std::vector<UrdfArmText>& urdf_arm_texts();
std::vector<std::string> urdf_arm_names();

// Option "arms": the arms drawn from (uniformly); default all three.
std::vector<std::string> read_urdf_arms(const GeneratorOptions& options);

// One of `arms`, its model (parsed once per process), configurations drawn
// within 0.9 of each joint's half range around the middle (a continuous
// joint's range taken as ±π).
GeneratedArm draw_urdf_arm(const std::vector<std::string>& arms, Rng& rng);

// How far a URDF family's start is drawn from the ready posture, per joint (rad).
constexpr double kReadySpread = 0.3;

// A configuration near the arm's "ready" posture (the one its catalogue
// scenario starts from: elbow bent, hand in front of the base at mid height),
// each joint moved by up to `spread` rad within the draw box.
Eigen::VectorXd draw_ready_configuration(const GeneratedArm& arm, double spread, Rng& rng);

}  // namespace rrlab
