// The "mesh" obstacle shape of a scenario: its triangle file, found like a
// URDF robot's file (confined to the scenario's directory, or the catalogue),
// read with assimp, bounded in size. Errors are ScenarioErrors naming the path.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include <rrlab/collision/mesh_loader.hpp>

namespace rrlab {

// A mesh file a scenario names, already confined to `full`: at most
// max_mesh_bytes, at most max_mesh_triangles, finite coordinates. Errors are
// at `path` and name the file `as_written` (never the server's full path);
// `use` ends the byte-limit message ("for a mesh obstacle").
std::shared_ptr<TriangleMesh> read_scenario_mesh(const std::string& as_written, const std::string& full,
                                                 const Eigen::Vector3d& scale, const std::string& path,
                                                 const std::string& use);

// The mesh in `file` (relative to `dir`, or to the catalogue directory when
// `dir` is empty), scaled per axis. `path` is the JSON path of the "file" key.
std::shared_ptr<const TriangleMesh> load_obstacle_mesh(const std::string& file, const Eigen::Vector3d& scale,
                                                       const std::string& dir, const std::string& path);

}  // namespace rrlab
