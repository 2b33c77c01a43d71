// The "mesh" obstacle shape of a scenario: its triangle file, found like a
// URDF robot's file (confined to the scenario's directory, or the catalogue),
// read with assimp, bounded in size. Errors are ScenarioErrors naming the path.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "collision/mesh_loader.hpp"

namespace rrlab {

// The mesh in `file` (relative to `dir`, or to the catalogue directory when
// `dir` is empty), scaled per axis. `path` is the JSON path of the "file" key.
std::shared_ptr<const TriangleMesh> load_obstacle_mesh(const std::string& file, const Eigen::Vector3d& scale,
                                                       const std::string& dir, const std::string& path);

}  // namespace rrlab
