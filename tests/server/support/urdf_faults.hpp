// URDF robots that rrlab must refuse with a clear error, for the command-line
// (`rrlab run` exits 2) and REST (422) tests: small URDF texts, the scenario
// around them, and a scenario directory of fixture files (with a symbolic
// link and a file that lie outside it). Each case names the JSON path and a
// fragment of the message the error must carry.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrlab::testing::urdf_faults {

// base -j1-> l1 -j2-> l2 -j3-> l3 -jt (fixed)-> tip; j2's type, parent,
// child and extra elements, and more elements before </robot>, are the
// variations.
inline std::string chain(const std::string& j2_type = "revolute", const std::string& j2_child = "l2",
                         const std::string& j2_extra = "", const std::string& more = "",
                         const std::string& j2_parent = "l1") {
  const std::string limit = "<limit lower=\"-2\" upper=\"2\" velocity=\"2\" effort=\"1\"/>";
  return "<robot name=\"r\">\n<link name=\"base\"/><link name=\"l1\"/><link name=\"l2\"/><link name=\"l3\"/>"
         "<link name=\"tip\"/>\n"
         "<joint name=\"j1\" type=\"revolute\"><parent link=\"base\"/><child link=\"l1\"/><origin xyz=\"0 0 0.5\"/>"
         "<axis xyz=\"0 0 1\"/>" + limit + "</joint>\n"
         "<joint name=\"j2\" type=\"" + j2_type + "\"><parent link=\"" + j2_parent + "\"/><child link=\"" + j2_child +
         "\"/><origin xyz=\"0.4 0 0\"/><axis xyz=\"0 1 0\"/>" + limit + j2_extra + "</joint>\n"
         "<joint name=\"j3\" type=\"revolute\"><parent link=\"l2\"/><child link=\"l3\"/><origin xyz=\"0.3 0 0\"/>"
         "<axis xyz=\"0 1 0\"/>" + limit + "</joint>\n"
         "<joint name=\"jt\" type=\"fixed\"><parent link=\"l3\"/><child link=\"tip\"/><origin xyz=\"0.2 0 0\"/></joint>\n" +
         more + "</robot>\n";
}

inline const std::string kMalformed = "<robot name=\"r\">\n<link name=\"a\">\n</robot>\n";  // <link> never closed

// A scenario around a robot (its "urdf" or "file" and other robot keys): the
// three-joint chain's tool point follows a small circle; valid with chain().
inline nlohmann::json scenario(const nlohmann::json& robot_keys) {
  nlohmann::json robot = {{"kind", "urdf"}, {"link_radius", 0.05}, {"q0", {0.3, 0.4, 0.4}}};
  robot.update(robot_keys);
  return {{"name", "urdf_fault"},
          {"dt", 0.01},
          {"duration", 0.5},
          {"robot", robot},
          {"obstacles", nlohmann::json::array()},
          {"task", {{"space", "xyz"}, {"trajectory", {{"type", "circle"}, {"center", {0.55, 0.0, 0.4}},
                                                      {"radius", 0.02}, {"normal", {1, 0, 0}}}}}},
          {"method", {{"name", "dls"}}}};
}

struct Fault {
  std::string name;
  nlohmann::json robot;  // the robot keys that make the fault
  std::string path;      // JSON path of the error, in the scenario
  std::string message;   // a fragment the message must contain
};

// Faults in the URDF text, sent inline as robot.urdf.
inline std::vector<Fault> inline_faults() {
  const std::string mesh_l1 = "<link name=\"l1\"><collision><geometry><mesh filename=\"package://arm/l1.stl\"/>"
                              "</geometry></collision></link>";
  const auto cylinder = [](const std::string& link) {
    return "<link name=\"" + link + "\"><collision><geometry><cylinder radius=\"0.05\" length=\"0.3\"/></geometry></collision></link>";
  };
  std::string package_mesh = chain();  // l1 a mesh, the other links cylinders: no link_radius needed
  package_mesh.replace(package_mesh.find("<link name=\"l1\"/>"), 17, mesh_l1);
  package_mesh.replace(package_mesh.find("<link name=\"l2\"/>"), 17, cylinder("l2"));
  package_mesh.replace(package_mesh.find("<link name=\"l3\"/>"), 17, cylinder("l3"));
  std::string no_limit = chain();
  no_limit.erase(no_limit.find("<limit"), no_limit.find("</joint>") - no_limit.find("<limit"));  // j1's <limit>
  using nlohmann::json;
  return {
      {"mimic", {{"urdf", chain("revolute", "l2", "<mimic joint=\"j1\" multiplier=\"1\"/>")}}, "robot.urdf",
       "joint 'j2' is a mimic joint (of 'j1'); mimic joints are not supported"},
      {"floating", {{"urdf", chain("floating")}}, "robot.urdf",
       "joint 'j2' is a floating joint; only revolute, continuous, prismatic and fixed joints are supported"},
      {"planar", {{"urdf", chain("planar")}}, "robot.urdf", "joint 'j2' is a planar joint"},
      {"missing child link", {{"urdf", chain("revolute", "l9")}}, "robot.urdf",
       "joint 'j2' names child link 'l9', which is not defined"},
      {"missing parent link", {{"urdf", chain("revolute", "l2", "", "", "l7")}}, "robot.urdf",
       "joint 'j2' names parent link 'l7', which is not defined"},
      {"missing base_link", {{"urdf", chain()}, {"base_link", "pedestal"}}, "robot.base_link",
       "base_link 'pedestal' is not a link of the URDF"},
      {"missing tip_link", {{"urdf", chain()}, {"tip_link", "gripper"}}, "robot.tip_link",
       "tip_link 'gripper' is not a link of the URDF"},
      {"cycle", {{"urdf", chain("revolute", "l2", "", "<joint name=\"back\" type=\"fixed\"><parent link=\"tip\"/><child link=\"base\"/></joint>")}},
       "robot.urdf", "the joints form a cycle through link 'base' (joint 'back')"},
      {"two parents", {{"urdf", chain("revolute", "l2", "", "<joint name=\"again\" type=\"fixed\"><parent link=\"base\"/><child link=\"l2\"/></joint>")}},
       "robot.urdf", "link 'l2' is the child of two joints ('j2' and 'again')"},
      {"malformed XML", {{"urdf", kMalformed}}, "robot.urdf", "malformed XML at line 3, column 1"},
      {"empty text", {{"urdf", ""}}, "robot.urdf", "the URDF is empty"},
      {"blank text", {{"urdf", " \n "}}, "robot.urdf", "the URDF is empty"},
      {"not a robot", {{"urdf", "<model name=\"m\"/>"}}, "robot.urdf", "not a URDF: no <robot> element"},
      {"urdfdom's reason", {{"urdf", no_limit}}, "robot.urdf",
       "urdfdom rejected the URDF: Joint [j1] is of type REVOLUTE but it does not specify limits"},
      {"package:// mesh", {{"urdf", package_mesh}, {"link_radius", nullptr}}, "robot.urdf",
       "mesh \"package://arm/l1.stl\" (link 'l1'): package:// and file:// URIs are not resolved"},
      {"base_link not an ancestor of tip_link", {{"urdf", chain()}, {"base_link", "l2"}, {"tip_link", "l1"}},
       "robot.tip_link", "tip_link 'l1' is not below base_link 'l2' (base_link must be an ancestor of tip_link)"},
      {"no moving joint between base and tip", {{"urdf", chain()}, {"base_link", "l3"}, {"tip_link", "tip"}, {"q0", nullptr}},
       "robot.urdf", "no revolute, continuous or prismatic joint between 'l3' and 'tip'"},
  };
}

// A scenario directory for the `file` cases: DIR/scenarios/robots/ holds the
// chain (good.urdf), faulty files, and link.urdf, a symbolic link to
// DIR/outside.urdf (a valid URDF outside the scenario directory).
struct Catalogue {
  static std::string fresh_dir() {  // server_process.hpp's temp_dir(), which CLI tests do not include
    std::string pattern = "/tmp/rrlab-urdf-XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    return pattern;
  }
  std::string root = fresh_dir();
  std::string dir = root + "/scenarios";
  Catalogue() {
    namespace fs = std::filesystem;
    fs::create_directories(dir + "/robots");
    std::ofstream(root + "/outside.urdf") << chain();
    std::ofstream(dir + "/robots/good.urdf") << chain();
    std::ofstream(dir + "/robots/malformed.urdf") << kMalformed;
    std::ofstream(dir + "/robots/mimic.urdf") << chain("revolute", "l2", "<mimic joint=\"j1\"/>");
    std::ofstream(dir + "/robots/empty.urdf");
    fs::create_symlink("../../outside.urdf", dir + "/robots/link.urdf");
  }
  ~Catalogue() { std::filesystem::remove_all(root); }
  Catalogue(const Catalogue&) = delete;
  Catalogue& operator=(const Catalogue&) = delete;

  // Faults of robot.file in this directory.
  std::vector<Fault> file_faults() const {
    return {
        {"file escaping with ..", {{"file", "../outside.urdf"}}, "robot.file",
         "\"../outside.urdf\" leads outside the scenario directory"},
        {"file escaping through robots/../..", {{"file", "robots/../../outside.urdf"}}, "robot.file",
         "\"robots/../../outside.urdf\" leads outside the scenario directory"},
        {"absolute file path", {{"file", root + "/outside.urdf"}}, "robot.file",
         "must be a path relative to the scenario's directory, got the absolute path \"" + root + "/outside.urdf\""},
        {"symbolic link out of the directory", {{"file", "robots/link.urdf"}}, "robot.file",
         "\"robots/link.urdf\" leads outside the scenario directory"},
        {"missing file", {{"file", "robots/none.urdf"}}, "robot.file", "no file \"robots/none.urdf\" in the scenario directory"},
        {"malformed file", {{"file", "robots/malformed.urdf"}}, "robot.file",
         "\"robots/malformed.urdf\": malformed XML at line 3, column 1"},
        {"mimic joint in a file", {{"file", "robots/mimic.urdf"}}, "robot.file",
         "\"robots/mimic.urdf\": joint 'j2' is a mimic joint (of 'j1')"},
        {"empty file", {{"file", "robots/empty.urdf"}}, "robot.file", "\"robots/empty.urdf\": the URDF is empty"},
        {"missing tip_link in a file", {{"file", "robots/good.urdf"}, {"tip_link", "gripper"}}, "robot.tip_link",
         "\"robots/good.urdf\": tip_link 'gripper' is not a link of the URDF"},
    };
  }
};

// robot keys with JSON null are removed (a default the fault case drops).
inline nlohmann::json scenario_for(const Fault& fault) {
  nlohmann::json doc = scenario(fault.robot);
  for (auto it = doc["robot"].begin(); it != doc["robot"].end();)
    it = it->is_null() ? doc["robot"].erase(it) : std::next(it);
  return doc;
}

}  // namespace rrlab::testing::urdf_faults
