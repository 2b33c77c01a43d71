// Link–link distances for self-collision over the model's self pairs
// (Model::self_pairs, from the allowed-collision matrix): capsule–capsule by
// exact segment routines, a capsule against a mesh link through the mesh's
// tree, and two mesh links through FCL's BVH distance. No FCL in this header.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <vector>

#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/model/model.hpp>

namespace rrlab {

// One self pair at the current frames.
struct SelfPairDistance {
  SelfPair pair;
  double distance = 0;                                 // signed, radii included: < 0 is penetration
  Eigen::Vector3d on_a = Eigen::Vector3d::Zero();      // nearest point on link a (its axis for a capsule)
  Eigen::Vector3d on_b = Eigen::Vector3d::Zero();      // nearest point on link b
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    // unit, b -> a: moving on_a along it increases distance
};

struct SelfDistanceTable {
  std::vector<SelfPairDistance> pairs;  // one per model self pair, in its order
  double min_distance = std::numeric_limits<double>::infinity();  // +inf without pairs
  int min_pair = -1;                                               // index into pairs, -1 without
  const SelfPairDistance* nearest() const { return min_pair < 0 ? nullptr : &pairs[size_t(min_pair)]; }
};

class SelfCollisionWorld {
 public:
  explicit SelfCollisionWorld(const Model& model);
  ~SelfCollisionWorld();
  SelfCollisionWorld(const SelfCollisionWorld&) = delete;
  SelfCollisionWorld& operator=(const SelfCollisionWorld&) = delete;

  bool empty() const;
  // Every self pair's distance at the current frames (allocation free for
  // capsule links once `out` has its size).
  void compute(const KinematicsData& kin, SelfDistanceTable& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The least self distance of a configuration, for callers without a world of
// their own (builds one: not for a step loop). +inf without self pairs.
double min_self_distance(const Model& model, const Eigen::VectorXd& q);

}  // namespace rrlab
