#include <rrlab/scenario/mesh_obstacle.hpp>

#include <filesystem>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/scenario/urdf_robot.hpp>

namespace rrlab {

std::shared_ptr<TriangleMesh> read_scenario_mesh(const std::string& as_written, const std::string& full,
                                                 const Eigen::Vector3d& scale, const std::string& path,
                                                 const std::string& use) {
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(full, ec);
  if (ec) throw ScenarioError(path, "cannot read \"" + as_written + "\": " + ec.message());
  if (bytes > std::uintmax_t(ScenarioLimits::max_mesh_bytes))
    throw ScenarioError(path, "\"" + as_written + "\" has " + std::to_string(bytes) + " bytes, at most " +
                                  std::to_string(ScenarioLimits::max_mesh_bytes) + " allowed " + use);
  std::shared_ptr<TriangleMesh> mesh;
  try {
    mesh = std::make_shared<TriangleMesh>(load_mesh_file(full, scale));
  } catch (const MeshError& e) {
    // assimp's reason, with the file as the scenario names it (not the server's path)
    std::string reason = e.what();
    for (size_t at = reason.find(full); at != std::string::npos; at = reason.find(full))
      reason.replace(at, full.size(), as_written);
    throw ScenarioError(path, reason);
  }
  if (int(mesh->triangles.size()) > ScenarioLimits::max_mesh_triangles)
    throw ScenarioError(path, "\"" + as_written + "\" has " + std::to_string(mesh->triangles.size()) +
                                  " triangles, at most " + std::to_string(ScenarioLimits::max_mesh_triangles) +
                                  " allowed " + use);
  return mesh;
}

std::shared_ptr<const TriangleMesh> load_obstacle_mesh(const std::string& file, const Eigen::Vector3d& scale,
                                                       const std::string& dir, const std::string& path) {
  if (const std::string problem = uri_problem(file, "scenario file"); !problem.empty())
    throw ScenarioError(path, "\"" + file + "\": " + problem);
  const std::string full = confined_path(file, dir, path);  // the same confinement as a URDF robot's file
  return read_scenario_mesh(file, full, scale, path, "for a mesh obstacle");
}

}  // namespace rrlab
