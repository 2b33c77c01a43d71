// Triangle meshes in distance queries: a mesh's bounding-volume tree, the
// exact signed distance of a segment (a capsule's axis) to a mesh obstacle,
// whether a mesh is closed and a point inside it, and a mesh link against the
// analytic obstacles (walls, spheres, points).
//
// The tree is FCL's BVHModel of OBBRSS volumes, declared here, not included:
// no header brings FCL in (mesh_distance.cpp and fcl_pairs.cpp include it).
#pragma once

#include <Eigen/Geometry>
#include <memory>

#include <rrlab/collision/link_obstacle_distance.hpp>
#include <rrlab/collision/mesh_loader.hpp>

namespace fcl {
template <typename S_>
class OBBRSS;
template <typename BV>
class BVHModel;
}  // namespace fcl

namespace rrlab::collision {

using MeshBvh = fcl::BVHModel<fcl::OBBRSS<double>>;

// Reported for touching or penetrating meshes, whose depth FCL does not give.
inline constexpr double kMeshContact = 1e-9;

// The mesh's OBBRSS tree (built once per mesh; allocates).
std::shared_ptr<MeshBvh> make_bvh(const TriangleMesh& mesh);

// Whether every edge of the mesh (vertices welded by position) borders
// exactly two triangles: a closed surface, whose inside a ray's parity finds.
bool closed_mesh(const TriangleMesh& mesh);

// Whether p (the mesh's frame) lies inside a closed mesh, by a ray's parity.
bool inside_mesh(const MeshBvh& bvh, const Eigen::Vector3d& p);

// Signed distance of segment a-b (world, no radius) to a mesh obstacle posed
// by rotation and position, through its tree (allocation free): exact when
// apart; -kMeshContact when the segment crosses the surface; minus its
// distance to the surface when wholly inside a closed mesh (`closed`, tested
// when its start lies in the mesh's `bounds`, own frame).
void segment_mesh(const MeshBvh& bvh, bool closed, const Eigen::AlignedBox3d& bounds,
                  const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position, const Eigen::Vector3d& a,
                  const Eigen::Vector3d& b, LinkObstacleDistance& out);

// A mesh link (triangles in the link's frame, posed by link_pose) against a
// wall through `point` with outward unit `normal` (world): its lowest vertex.
void mesh_wall(const TriangleMesh& mesh, const Eigen::Isometry3d& link_pose, const Eigen::Vector3d& point,
               const Eigen::Vector3d& normal, LinkObstacleDistance& out);

// A mesh link against a sphere (a point for radius 0): the nearest point of
// its triangles to the centre; a centre inside the mesh is not detected.
void mesh_sphere(const TriangleMesh& mesh, const Eigen::Isometry3d& link_pose, const Eigen::Vector3d& centre,
                 double radius, LinkObstacleDistance& out);

}  // namespace rrlab::collision
