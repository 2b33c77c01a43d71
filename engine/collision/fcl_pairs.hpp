// The FCL adapters: capsule links against FCL's shapes (the reference
// backend, DistanceBackend::fcl) and mesh links against boxes, polygon prisms
// and meshes (FCL's BVH distance, in both backends). FCL's types stay opaque
// here: fcl_pairs.cpp (with mesh_distance.cpp, for the mesh tree) is the only
// file that includes FCL, and no header does.
#pragma once

#include <Eigen/Geometry>
#include <memory>

#include <rrlab/collision/link_obstacle_distance.hpp>
#include <rrlab/collision/mesh_distance.hpp>
#include <rrlab/collision/obstacle_geometry.hpp>
#include <rrlab/collision/scene.hpp>

namespace rrlab::collision {

struct FclObstacle;  // an obstacle's FCL shapes: its convex parts, box, sphere or mesh tree (none for a wall)
struct FclCapsule;   // a capsule link as FCL's capsule, posed for each query

// Built with the obstacle's geometry (allocates; the mesh tree is shared with g).
std::shared_ptr<FclObstacle> build_fcl(const Obstacle& o, const ObstacleGeometry& g);
std::shared_ptr<FclCapsule> make_fcl_capsule(double radius);

// Places the capsule on the axis segment a-b with the link's radius (below
// 1 mm it is inflated for GJK's sake and the distances corrected).
void pose_fcl_capsule(FclCapsule& capsule, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius);

// A posed capsule against an obstacle's FCL shapes (the minimum over its
// parts): GJK distance when apart, libccd MPR depth when penetrating. Not
// for walls (FCL 0.7 has no Halfspace distance). Allocates.
void fcl_capsule_obstacle(const FclCapsule& capsule, const ObstacleGeometry& g, const FclObstacle& shapes,
                          LinkObstacleDistance& out);

// A mesh link (its tree, posed by link_pose) against an obstacle's FCL
// shapes: boxes, polygon prisms, meshes. Touching or penetrating reports
// -kMeshContact (FCL's mesh distance gives no depth).
void fcl_mesh_obstacle(const MeshBvh& bvh, const Eigen::Isometry3d& link_pose, const ObstacleGeometry& g,
                       const FclObstacle& shapes, LinkObstacleDistance& out);

// Two mesh links (self-collision): FCL's BVH distance, nearest points in
// `on_a`, `on_b` (world). Touching or penetrating reports -kMeshContact.
double fcl_mesh_mesh(const MeshBvh& a, const Eigen::Isometry3d& pose_a, const MeshBvh& b,
                     const Eigen::Isometry3d& pose_b, Eigen::Vector3d& on_a, Eigen::Vector3d& on_b);

}  // namespace rrlab::collision
