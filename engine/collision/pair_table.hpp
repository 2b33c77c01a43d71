// The dispatch table of link–obstacle distances, in the manner of MuJoCo's
// collision driver (engine_collision_driver.c: a static 2-D array of
// functions indexed by the two geom types): one function per backend, link
// shape and obstacle shape. CollisionWorld::compute walks the pairs through
// it; the table itself is in pair_table.cpp with which routine serves what.
#pragma once

#include <Eigen/Geometry>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/link_obstacle_distance.hpp>
#include <rrlab/collision/mesh_distance.hpp>
#include <rrlab/collision/obstacle_geometry.hpp>
#include <rrlab/collision/scene.hpp>

namespace rrlab::collision {

struct FclCapsule;   // fcl_pairs.hpp
struct FclObstacle;  // fcl_pairs.hpp

enum class LinkShape { capsule, mesh };

inline constexpr int kBackends = 2;        // DistanceBackend: analytic, fcl
inline constexpr int kLinkShapes = 2;      // LinkShape: capsule, mesh
inline constexpr int kObstacleShapes = 6;  // ShapeKind: polygon, box, sphere, point, wall, mesh
static_assert(static_cast<int>(DistanceBackend::fcl) == kBackends - 1);
static_assert(static_cast<int>(LinkShape::mesh) == kLinkShapes - 1);
static_assert(static_cast<int>(ShapeKind::mesh) == kObstacleShapes - 1);

// One link at the current frames, as every pair function sees it.
struct PairLink {
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();  // capsule: axis segment (world)
  double radius = 0;                       // capsule
  const FclCapsule* fcl = nullptr;         // capsule, FCL backend: posed on start-end
  const TriangleMesh* mesh = nullptr;      // mesh link: triangles in its frame
  const MeshBvh* bvh = nullptr;            // mesh link: their tree
  const Eigen::Isometry3d* pose = nullptr;  // mesh link: its frame (world)
};

// One obstacle at its current pose.
struct PairObstacle {
  const ObstacleGeometry* geometry = nullptr;
  const FclObstacle* fcl = nullptr;  // its FCL shapes (the FCL backend and mesh links)
};

// Fills every field of `out`: the signed distance of the link (its radius
// included) to the obstacle, the nearest points and the normal.
using PairFunction = void (*)(const PairLink& link, const PairObstacle& obstacle, LinkObstacleDistance& out);

// [backend][link shape][obstacle shape]; every entry is set.
extern const PairFunction kPairTable[kBackends][kLinkShapes][kObstacleShapes];

inline PairFunction pair_function(DistanceBackend backend, LinkShape link, ShapeKind obstacle) {
  return kPairTable[static_cast<int>(backend)][static_cast<int>(link)][static_cast<int>(obstacle)];
}

}  // namespace rrlab::collision
