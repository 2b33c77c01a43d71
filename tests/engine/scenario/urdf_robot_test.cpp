// The "urdf" robot kind of scenarios: files confined to the scenario's
// directory, inline text, link radii, limits, and errors naming the path.
#include <rrlab/scenario/urdf_robot.hpp>

#include <gtest/gtest.h>

#include <filesystem>

#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/scenario/scenario.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

using nlohmann::json;

const std::string kScenarios = test::source_path("scenarios");

json iiwa_scenario() { return read_json_file(kScenarios + "/40_urdf_iiwa14_pose.json", "scenario file"); }

std::string error_path(const json& doc, const std::string& dir) {
  try {
    parse_scenario(doc, dir);
  } catch (const ScenarioError& e) {
    return e.path() + " | " + e.what();
  }
  return "(accepted)";
}

TEST(UrdfScenario, ShippedArmsLoadWithTheirLimits) {
  for (const char* file : {"40_urdf_iiwa14_pose.json", "41_urdf_panda_pose.json", "42_urdf_gen3_pose.json"}) {
    const Scenario sc = load_scenario_file(kScenarios + "/" + file);
    EXPECT_EQ(sc.model.kind, ModelKind::urdf) << file;
    EXPECT_EQ(sc.model.dof(), 7) << file;
    EXPECT_EQ(sc.model.link_count(), 7) << file;
    EXPECT_TRUE(sc.model.limits.has_velocity()) << file;
    // the scenario now carries its URDF inline
    EXPECT_FALSE(sc.json["robot"].contains("file")) << file;
    EXPECT_GT(sc.json["robot"]["urdf"].get<std::string>().size(), 1000u) << file;
    // and re-parses without any directory
    EXPECT_EQ(parse_scenario(sc.json).model.dof(), 7) << file;
  }
}

TEST(UrdfScenario, IiwaUrdfMatchesTheDhScenario) {
  const Scenario urdf = load_scenario_file(kScenarios + "/40_urdf_iiwa14_pose.json");
  const Scenario dh = load_scenario_file(kScenarios + "/03_dh7_pose.json");
  KinematicsData a(urdf.model), b(dh.model);
  forward_kinematics(urdf.model, urdf.q0, a);
  forward_kinematics(dh.model, urdf.q0, b);
  EXPECT_LT((a.end_effector().translation() - b.end_effector().translation()).norm(), 1e-9);
  EXPECT_NEAR(urdf.model.limits.upper[0], dh.model.limits.upper[0], 1e-9);  // the URDF carries 10 decimals
}

TEST(UrdfScenario, PathsOutsideTheDirectoryAreRefused) {
  json doc = iiwa_scenario();
  doc["robot"]["file"] = "../CMakeLists.txt";
  EXPECT_NE(error_path(doc, kScenarios).find("robot.file | robot.file: \"../CMakeLists.txt\" leads outside the scenario directory"),
            std::string::npos)
      << error_path(doc, kScenarios);
  doc["robot"]["file"] = "robots/../../README.md";
  EXPECT_NE(error_path(doc, kScenarios).find("leads outside"), std::string::npos) << error_path(doc, kScenarios);
  doc["robot"]["file"] = "robots/../../scenarios/robots/iiwa14.urdf";  // resolves inside: accepted
  EXPECT_EQ(error_path(doc, kScenarios), "(accepted)");
  doc["robot"]["file"] = "/etc/passwd";
  EXPECT_NE(error_path(doc, kScenarios).find("robot.file | robot.file: must be a path relative"), std::string::npos);
  doc["robot"]["file"] = "robots/missing.urdf";
  EXPECT_NE(error_path(doc, kScenarios).find("no file \"robots/missing.urdf\" in the scenario directory"), std::string::npos);
  doc["robot"]["file"] = "robots/./iiwa14.urdf";  // inside: accepted
  EXPECT_EQ(error_path(doc, kScenarios), "(accepted)");
}

TEST(UrdfScenario, WithoutADirectoryTheCatalogueIsUsed) {
  json doc = iiwa_scenario();
  set_scenario_catalogue_dir("");
  EXPECT_NE(error_path(doc, "").find("robot.file | robot.file: has no scenario directory"), std::string::npos);
  set_scenario_catalogue_dir(kScenarios);
  EXPECT_EQ(error_path(doc, ""), "(accepted)");
  set_scenario_catalogue_dir("");
}

TEST(UrdfScenario, InlineTextAndItsFaults) {
  json doc = iiwa_scenario();
  doc["robot"].erase("file");
  doc["robot"]["urdf"] = test::read_source_file("scenarios/robots/iiwa14.urdf");
  EXPECT_EQ(error_path(doc, ""), "(accepted)");
  doc["robot"]["urdf"] = "<robot name='x'><link name='a'></robot>";
  EXPECT_NE(error_path(doc, "").find("robot.urdf | robot.urdf: malformed XML"), std::string::npos) << error_path(doc, "");
  doc["robot"]["urdf"] = std::string(ScenarioLimits::max_urdf_bytes + 1, ' ');
  EXPECT_NE(error_path(doc, "").find("is longer than"), std::string::npos);
  doc["robot"]["file"] = "robots/iiwa14.urdf";
  EXPECT_NE(error_path(doc, kScenarios).find("exactly one of"), std::string::npos);
}

TEST(UrdfScenario, MimicJointNamedWithTheRobotPath) {
  json doc = iiwa_scenario();
  doc["robot"].erase("file");
  std::string urdf = test::read_source_file("scenarios/robots/iiwa14.urdf");
  const std::string axis = "<axis xyz=\"0 0 1\"/>";
  const size_t at = urdf.find(axis, urdf.find("iiwa_joint_3"));
  urdf.insert(at + axis.size(), "<mimic joint=\"iiwa_joint_2\"/>");
  doc["robot"]["urdf"] = urdf;
  EXPECT_NE(error_path(doc, "").find("robot.urdf | robot.urdf: joint 'iiwa_joint_3' is a mimic joint"), std::string::npos)
      << error_path(doc, "");
}

TEST(UrdfScenario, FaultsNameTheFileAndTheKey) {
  json doc = iiwa_scenario();
  doc["robot"]["tip_link"] = "iiwa_gripper";
  EXPECT_EQ(error_path(doc, kScenarios),
            "robot.tip_link | robot.tip_link: \"robots/iiwa14.urdf\": tip_link 'iiwa_gripper' is not a link of the URDF");
  doc["robot"]["tip_link"] = "iiwa_link_3";
  doc["robot"]["base_link"] = "iiwa_link_5";
  EXPECT_NE(error_path(doc, kScenarios).find("robot.tip_link | robot.tip_link: \"robots/iiwa14.urdf\": tip_link 'iiwa_link_3' is not below"),
            std::string::npos) << error_path(doc, kScenarios);
  doc = iiwa_scenario();
  doc["robot"]["base_link"] = "iiwa_link_99";
  EXPECT_EQ(error_path(doc, kScenarios),
            "robot.base_link | robot.base_link: \"robots/iiwa14.urdf\": base_link 'iiwa_link_99' is not a link of the URDF");
}

TEST(UrdfScenario, LinkRadiusAndLimitsOverride) {
  json doc = iiwa_scenario();
  doc["robot"]["link_radius"] = 0.1;
  doc["robot"]["limits"] = {{"velocity", {50, 50, 50, 50, 50, 50, nullptr}}};
  const Scenario sc = parse_scenario(doc, kScenarios);
  EXPECT_DOUBLE_EQ(sc.model.links[3].radius, 0.1);
  EXPECT_NEAR(sc.model.limits.velocity[0], 50 * M_PI / 180, 1e-12);
  EXPECT_TRUE(std::isinf(sc.model.limits.velocity[6]));
  EXPECT_NEAR(sc.model.limits.upper[0], 170 * M_PI / 180, 1e-9);  // the URDF's, not overridden
  doc["robot"]["link_radius"] = {0.1, 0.1};
  EXPECT_NE(error_path(doc, kScenarios).find("robot.link_radius"), std::string::npos);
  doc["robot"]["link_radius"] = 0.1;
  doc["robot"]["q0"] = {0, 130, 0, 0, 0, 0, 0};  // beyond the URDF's ±120°
  EXPECT_NE(error_path(doc, kScenarios).find("robot.q0[1] | robot.q0[1]: value"), std::string::npos) << error_path(doc, kScenarios);
  doc["robot"]["links"] = json::array();
  EXPECT_NE(error_path(doc, kScenarios).find("robot.links"), std::string::npos);
}

// Every <mesh> reference counts against the robot's triangle budget: 2,000
// references to the 576-triangle torus (a 159 KB request) once made 1.15 M
// triangles, 11.8 s to validate and 149 ms per step.
TEST(UrdfScenario, MeshReferencesShareOneTriangleBudget) {
  const auto robot_with = [](int references) {
    std::string collisions;
    for (int i = 0; i < references; ++i)
      collisions += R"(<collision><geometry><mesh filename="meshes/torus.obj"/></geometry></collision>)";
    json doc = iiwa_scenario();
    doc["robot"] = {{"kind", "urdf"}, {"q0", {0.1}},
                    {"urdf", R"(<robot name="r"><link name="base"/><link name="l1">)" + collisions +
                                 R"(</link><link name="tip"/><joint name="j1" type="revolute"><parent link="base"/>)"
                                 R"(<child link="l1"/><axis xyz="0 0 1"/>)"
                                 R"(<limit lower="-2" upper="2" velocity="1" effort="1"/></joint>)"
                                 R"(<joint name="jt" type="fixed"><parent link="l1"/><child link="tip"/>)"
                                 R"(<origin xyz="0.5 0 0"/></joint></robot>)"}};
    return doc;
  };
  EXPECT_EQ(error_path(robot_with(2000), kScenarios),
            "robot.urdf | robot.urdf: the robot's collision meshes would have 20160 triangles together at mesh "
            "\"meshes/torus.obj\" (link 'l1'), at most 20000 allowed");
  // 34 references (19,584 triangles) are within it: whatever else is refused, not the meshes
  EXPECT_EQ(error_path(robot_with(34), kScenarios).find("collision meshes"), std::string::npos)
      << error_path(robot_with(34), kScenarios);
}

// A chain of 10,000 fixed links (1 MB) took 22 s per request (a quadratic
// cycle check); the link count is capped before urdfdom parses it.
TEST(UrdfScenario, LinkAndJointCountsAreCapped) {
  std::string links = R"(<link name="l0"/>)", joints;
  for (int i = 1; i <= 1001; ++i) {
    links += "<link name=\"l" + std::to_string(i) + "\"/>";
    joints += "<joint name=\"j" + std::to_string(i) + "\" type=\"fixed\"><parent link=\"l" + std::to_string(i - 1) +
              "\"/><child link=\"l" + std::to_string(i) + "\"/></joint>";
  }
  json doc = iiwa_scenario();
  doc["robot"] = {{"kind", "urdf"}, {"link_radius", 0.05}, {"urdf", "<robot name=\"r\">" + links + joints + "</robot>"}};
  EXPECT_EQ(error_path(doc, kScenarios), "robot.urdf | robot.urdf: the URDF has more than 1000 links");
}

}  // namespace
}  // namespace rrlab
