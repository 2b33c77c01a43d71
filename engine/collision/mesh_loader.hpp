// Triangle meshes for collision (a URDF link's <collision><mesh>), read with
// Debian's assimp: STL, DAE (COLLADA), OBJ and the other formats it knows.
#pragma once

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrlab {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // vertex indices
  // Appends `other` with its vertices mapped by `pose`.
  void append(const TriangleMesh& other, const Eigen::Isometry3d& pose);
};

class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every mesh of the file's scene, node transforms applied, then scaled per
// axis. Throws MeshError naming the file (and assimp's reason).
TriangleMesh load_mesh_file(const std::string& path, const Eigen::Vector3d& scale);

// At most this many triangles per file (a collision mesh, not a render mesh).
constexpr int kMaxMeshTriangles = 200000;
// Every vertex coordinate, in metres after scaling, lies within this bound
// (the bound on any length in a scenario); non-finite ones are refused too.
constexpr double kMaxMeshCoordinate = 1.0e4;

}  // namespace rrlab
