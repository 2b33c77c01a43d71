#include <rrlab/scenario/urdf_robot.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <rrlab/collision/mesh_loader.hpp>
#include <rrlab/scenario/mesh_obstacle.hpp>
#include <rrlab/scenario/physical_bounds.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/urdf/urdf_chain.hpp>

namespace rrlab {

namespace fs = std::filesystem;

std::string uri_problem(const std::string& file, const std::string& relative_to) {
  if (file.rfind("package://", 0) != 0 && file.rfind("file://", 0) != 0) return "";
  return "package:// and file:// URIs are not resolved; give a path relative to the " + relative_to;
}

std::string confined_path(const std::string& file, const std::string& dir, const std::string& path,
                          const std::string& subdir) {
  if (file.empty()) throw ScenarioError(path, "must name a file");
  const fs::path relative(file);
  if (relative.is_absolute() || relative.has_root_name())
    throw ScenarioError(path, "must be a path relative to the scenario's directory, got the absolute path \"" + file + "\"");
  const std::string root_dir = dir.empty() ? scenario_catalogue_dir() : dir;
  if (root_dir.empty())
    throw ScenarioError(path, "has no scenario directory to be resolved in; send the URDF text inline as robot.urdf");
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(fs::absolute(root_dir, ec), ec);
  const fs::path full = fs::weakly_canonical(root / fs::path(subdir) / relative, ec);
  if (ec) throw ScenarioError(path, "cannot resolve \"" + file + "\": " + ec.message());
  // Confinement: every component of the root must start the resolved path.
  const auto [root_end, full_end] = std::mismatch(root.begin(), root.end(), full.begin(), full.end());
  if (root_end != root.end() || full_end == full.end())
    throw ScenarioError(path, "\"" + file + "\" leads outside the scenario directory");
  if (!fs::is_regular_file(full, ec)) throw ScenarioError(path, "no file \"" + file + "\" in the scenario directory");
  return full.string();
}

std::string read_confined_file(const std::string& file, const std::string& dir, const std::string& path) {
  const fs::path full = confined_path(file, dir, path);
  std::error_code ec;
  if (fs::file_size(full, ec) > std::uintmax_t(ScenarioLimits::max_urdf_bytes))
    throw ScenarioError(path, "\"" + file + "\" is larger than " + std::to_string(ScenarioLimits::max_urdf_bytes) + " bytes");
  std::ifstream in(full);
  if (!in) throw ScenarioError(path, "cannot read \"" + file + "\"");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Stays whole (over 100 lines): the robot object's keys are read and checked
// in one pass, in the order the scenario format lists them, so that each
// error names the first bad key.
Model parse_urdf_robot(JsonObject& robot, double radians_per_unit, const std::string& dir, std::string& urdf_text) {
  const bool has_file = robot.has("file"), has_text = robot.has("urdf");
  if (has_file == has_text)
    throw ScenarioError(robot.child("file"), "a urdf robot needs exactly one of \"file\" (a path) and \"urdf\" (the text)");
  std::string source_path;
  if (has_file) {
    source_path = robot.child("file");
    urdf_text = read_confined_file(robot.string("file"), dir, source_path);
  } else {
    source_path = robot.child("urdf");
    urdf_text = robot.string("urdf");
    if (long(urdf_text.size()) > ScenarioLimits::max_urdf_bytes)
      throw ScenarioError(source_path, "is longer than " + std::to_string(ScenarioLimits::max_urdf_bytes) + " bytes");
  }
  // A fault in a file names the file; a base_link or tip_link the URDF lacks
  // is the fault of that key.
  std::string in_file;  // built by appending: GCC 12 warns (-Wrestrict, falsely) on "\"" + string
  if (has_file) in_file.append("\"").append(robot.string("file")).append("\": ");
  UrdfChain chain;
  try {
    chain = read_urdf_chain(urdf_text, robot.string("base_link", ""), robot.string("tip_link", ""));
  } catch (const UrdfError& e) {
    throw ScenarioError(e.key().empty() ? source_path : robot.child(e.key()), in_file + e.what());
  }
  if (int(chain.joints.size()) > ScenarioLimits::max_joints)
    throw ScenarioError(source_path, "has " + std::to_string(chain.joints.size()) + " moving joints, at most " +
                                         std::to_string(ScenarioLimits::max_joints) + " allowed");

  // Link capsules: robot.link_radius (one number, or one per moving joint)
  // wins; otherwise the radius fitted to the link's <collision> primitives.
  const int n = int(chain.joints.size());
  if (robot.has("link_radius")) {
    const nlohmann::json& value = robot.raw("link_radius");
    const std::string path = robot.child("link_radius");
    std::vector<double> radii;
    if (value.is_number()) radii.assign(n, json_number(value, path));
    else radii = json_numbers(value, path, n, n);
    for (int i = 0; i < n; ++i) {
      const std::string at = value.is_number() ? path : index_path(path, i);
      if (radii[i] < 0) throw ScenarioError(at, "must be >= 0");
      chain.joints[i].radius = check_quantity(radii[i], PhysicalBounds::length, at);
    }
  } else {
    for (int i = 0; i < n; ++i)
      if (chain.joints[i].radius < 0 && chain.meshes[i].empty())
        throw ScenarioError(robot.child("link_radius"),
                            "is needed: the link after joint '" + chain.joint_names[i] + "' has no collision " +
                                "cylinder, sphere, box or mesh");
  }

  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  if (robot.has("base")) {
    const std::vector<double> p = robot.numbers("base", 3, 3);
    for (size_t i = 0; i < 3; ++i) check_quantity(p[i], PhysicalBounds::length, index_path(robot.child("base"), i));
    base.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (robot.has("base_rpy")) {
    std::vector<double> rpy = robot.numbers("base_rpy", 3, 3);
    for (size_t i = 0; i < 3; ++i) {
      check_quantity(rpy[i], PhysicalBounds::angle, index_path(robot.child("base_rpy"), i), radians_per_unit);
      rpy[i] *= radians_per_unit;
    }
    base.linear() = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
  }
  // A link with meshes and no primitive (and no link_radius) collides as its
  // meshes; the capsule radius then bounds them (for the methods that sweep
  // a capsule, and for drawing).
  // Every <mesh> reference counts against one triangle budget for the robot
  // (a file named twice counts twice: its triangles are checked twice per
  // step); a file is read once per scale.
  std::vector<std::shared_ptr<TriangleMesh>> meshes(n);
  std::map<std::pair<std::string, std::array<double, 3>>, std::shared_ptr<const TriangleMesh>> read;
  long triangles = 0;
  for (int i = 0; i < n; ++i) {
    if (chain.joints[i].radius >= 0) continue;
    chain.joints[i].radius = 0;
    auto merged = std::make_shared<TriangleMesh>();
    for (const UrdfMesh& m : chain.meshes[i]) {
      const std::string where = " (link '" + m.link + "')";
      if (const std::string problem = uri_problem(m.filename, "URDF file"); !problem.empty())
        throw ScenarioError(source_path, in_file + "mesh \"" + m.filename + "\"" + where + ": " + problem);
      const std::string urdf_dir = has_file ? fs::path(robot.string("file")).parent_path().string() : std::string();
      const std::string file = confined_path(m.filename, dir, source_path, urdf_dir);
      auto& mesh = read[{file, {m.scale.x(), m.scale.y(), m.scale.z()}}];
      try {
        if (!mesh) mesh = read_scenario_mesh(m.filename, file, m.scale, "", "for a URDF mesh");
      } catch (const ScenarioError& e) {  // at no path: the message alone
        throw ScenarioError(source_path, in_file + e.what() + where);
      }
      triangles += long(mesh->triangles.size());
      if (triangles > ScenarioLimits::max_robot_mesh_triangles)
        throw ScenarioError(source_path, in_file + "the robot's collision meshes would have " +
                                             std::to_string(triangles) + " triangles together at mesh \"" +
                                             m.filename + "\"" + where + ", at most " +
                                             std::to_string(ScenarioLimits::max_robot_mesh_triangles) + " allowed");
      merged->append(*mesh, m.pose);
    }
    meshes[i] = merged;
  }
  Model model = make_chain(base, chain.joints, chain.tip);
  model.limits = chain.limits;  // the file's; robot.limits may override entries
  for (int i = 0; i < n; ++i) {
    if (!meshes[i]) continue;
    // vertices into the frame after joint i (the child frame times `post`)
    const Eigen::Isometry3d to_frame = model.joints[i].post.inverse();
    const Eigen::Vector3d end = model.joints[i].post.translation();  // segment: child origin -> end
    double radius = 0;
    for (Eigen::Vector3d& v : meshes[i]->vertices) {
      const double t = end.squaredNorm() > 0 ? std::clamp(v.dot(end) / end.squaredNorm(), 0.0, 1.0) : 0.0;
      radius = std::max(radius, (v - t * end).norm());
      v = to_frame * v;
    }
    model.links[i].radius = radius;
    model.links[i].mesh = meshes[i];
    urdf_text.clear();  // mesh files are needed anyway: the scenario keeps naming its file
  }
  return model;
}

}  // namespace rrlab
