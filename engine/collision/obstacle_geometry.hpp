// An obstacle's geometry, built once from its scenario description (convex
// parts, the sphere's radius, the wall's unit normal, the mesh's tree), and
// the signed distance of a segment (a capsule's axis, no radius) to each
// obstacle kind. pair_table.cpp puts these in the dispatch table.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include <rrlab/collision/convex_polytope.hpp>
#include <rrlab/collision/link_obstacle_distance.hpp>
#include <rrlab/collision/mesh_distance.hpp>
#include <rrlab/collision/scene.hpp>

namespace rrlab::collision {

struct ObstacleGeometry {
  ShapeKind shape = ShapeKind::point;
  std::vector<ConvexPolytope> parts;  // polygon parts or the box, own frame
  double radius = 0;                  // sphere
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // wall, own frame, unit
  std::shared_ptr<const TriangleMesh> mesh;  // mesh, own frame
  std::shared_ptr<MeshBvh> bvh;              // mesh: built once, shared across reshapes
  bool closed = false;                       // mesh: a closed surface (inside is detected)
  Eigen::AlignedBox3d bounds;                // mesh: its vertices' box, own frame
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

// The obstacle's geometry in its own frame (the pose is read separately).
// A mesh's tree and whether it is closed are taken from `previous` when one
// of those has the same mesh (they outlive edits of other obstacles), else
// built. Throws std::invalid_argument naming the obstacle for bad geometry.
ObstacleGeometry build_geometry(const Obstacle& o, const std::vector<ObstacleGeometry>& previous = {});

// Signed distance of segment a-b (world) to one obstacle, without the radius:
// one function per obstacle kind (the polytope one serves boxes and polygons).
void segment_point(const ObstacleGeometry& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   LinkObstacleDistance& out);
void segment_sphere_obstacle(const ObstacleGeometry& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             LinkObstacleDistance& out);
void segment_wall_obstacle(const ObstacleGeometry& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           LinkObstacleDistance& out);
void segment_polytopes(const ObstacleGeometry& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                       LinkObstacleDistance& out);
// A lower bound of segment_polytopes' distance from the parts' face planes
// (separating_face_bound); kBoundMargin above a distance it proves the exact
// routine, rounding included, would not come out below that distance.
double segment_polytopes_bound(const ObstacleGeometry& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b);
inline constexpr double kBoundMargin = 1e-9;  // m
void segment_mesh_obstacle(const ObstacleGeometry& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           LinkObstacleDistance& out);

}  // namespace rrlab::collision
