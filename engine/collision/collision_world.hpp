// Link–obstacle distances. The only interface to FCL: the implementation
// (collision_world.cpp) is the one file that includes it.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "collision/scene.hpp"
#include "kinematics/kinematics.hpp"
#include "model/model.hpp"

namespace rrlab {

struct LinkObstacleDistance {
  double distance = 0;  // signed: < 0 is penetration depth
  Eigen::Vector3d on_link = Eigen::Vector3d::Zero();      // nearest point on the link's axis segment
  Eigen::Vector3d on_obstacle = Eigen::Vector3d::Zero();  // nearest point on the obstacle surface
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();       // unit, obstacle -> link: moving on_link along it increases distance
};

// Every link against every obstacle, plus the overall minimum.
struct DistanceTable {
  int links = 0, obstacles = 0;
  std::vector<LinkObstacleDistance> pairs;  // row-major: link * obstacles + obstacle
  double min_distance = std::numeric_limits<double>::infinity();
  int min_link = -1, min_obstacle = -1;

  void resize(int link_count, int obstacle_count);
  LinkObstacleDistance& at(int link, int obstacle) { return pairs[link * obstacles + obstacle]; }
  const LinkObstacleDistance& at(int link, int obstacle) const { return pairs[link * obstacles + obstacle]; }
  // Index of the nearest obstacle to one link (-1 without obstacles).
  int nearest_obstacle(int link) const;
};

class CollisionWorld {
 public:
  CollisionWorld(const Model& model, const Scene& scene);
  ~CollisionWorld();
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;

  // Re-read obstacle poses (cheap) and, with reshape, their geometry too
  // (after an obstacle was resized, added or removed).
  void sync(const Scene& scene, bool reshape = false);
  // Distances of every link capsule to every obstacle at the current frames.
  void compute(const KinematicsData& kin, DistanceTable& out);
  // The same table from FCL's own queries (GJK distance, libccd MPR depth when
  // penetrating; walls analytic): a slower, less exact reference for
  // cross-checks and benchmarks. See collision_world.cpp for its limits.
  void compute_with_fcl(const KinematicsData& kin, DistanceTable& out);

 private:
  void mesh_link(const KinematicsData& kin, int link, DistanceTable& out);  // a link with a collision mesh
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rrlab
