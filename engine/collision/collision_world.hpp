// Link–obstacle distances: every link against every obstacle, through the
// pair table (pair_table.hpp). No FCL here: fcl_pairs.cpp and
// mesh_distance.cpp are the only files that include it.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <vector>

#include <rrlab/collision/link_obstacle_distance.hpp>
#include <rrlab/collision/scene.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/model/model.hpp>

namespace rrlab {

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

// Which routines fill the table (pair_table.cpp says which serves each pair).
enum class DistanceBackend {
  analytic,  // capsule links by exact segment routines, allocation free
  fcl,       // capsule links by FCL's own queries (GJK distance, libccd MPR depth
             // when penetrating; walls analytic): a slower, less exact reference
             // for cross-checks and benchmarks. Mesh links are the same in both.
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
  // Distances of every link to every obstacle at the current frames, each
  // pair by the backend's entry in the pair table; the analytic one by default.
  void compute(const KinematicsData& kin, DistanceTable& out, DistanceBackend backend);
  void compute(const KinematicsData& kin, DistanceTable& out) { compute(kin, out, DistanceBackend::analytic); }
  // As compute (analytic backend), for callers that only weigh pairs nearer
  // than `cutoff`: a capsule–box or capsule–polygon pair whose face planes
  // alone prove it at least `cutoff` apart is not computed; its distance is
  // that lower bound (> cutoff), its points and normal are NaN.
  void compute_near(const KinematicsData& kin, DistanceTable& out, double cutoff);
  // The same table from FCL's own queries: compute with DistanceBackend::fcl,
  // kept as a member for callers that take its address (bench/urdf_mesh_bench.cpp).
  void compute_with_fcl(const KinematicsData& kin, DistanceTable& out) { compute(kin, out, DistanceBackend::fcl); }

 private:
  void compute_pairs(const KinematicsData& kin, DistanceTable& out, DistanceBackend backend, double cutoff);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rrlab
