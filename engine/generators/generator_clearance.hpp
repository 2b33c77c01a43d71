// Clearance of generated cases, measured by the engine's own collision code
// (CollisionWorld over capsules), so "clear of an obstacle" in a generated
// case means what a run of it measures.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include <rrlab/collision/scene.hpp>
#include <rrlab/model/model.hpp>

namespace rrlab {

// A segment grown by a radius: an arm link, or a stretch of the hand's path.
struct CapsuleSegment {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  double radius = 0;
};

// Smallest signed distance (m, < 0 when penetrating) from the capsules to the
// obstacle placed at its position0 (t = 0).
double capsules_clearance(const std::vector<CapsuleSegment>& capsules, const Obstacle& obstacle);

// The least signed distance (m, < 0 when they overlap) between two
// obstacles placed at their position0 (t = 0), by the same measure: each
// one's edges (a box's, a polygon part's, a mesh's triangles'), or its centre
// grown by its radius (a sphere, a point), against the other, the smaller of
// the two ways. Exact for convex parts apart (their nearest points lie on an
// edge of one of them). A wall has no edges: two walls are +inf apart.
double obstacles_distance(const Obstacle& a, const Obstacle& b);

// The arm's link capsules at every step of a witness.
struct ArmSweep {
  int links = 0;
  double dt = 0;
  std::vector<CapsuleSegment> capsules;  // step k's links at [k * links, (k + 1) * links)
};
ArmSweep arm_sweep(const Model& model, const std::vector<Eigen::VectorXd>& steps, double dt);

// Smallest signed distance between the swept arm and `obstacle` moving as a
// run moves it (position0 + velocity t), by the engine's collision code.
// Capsules whose bounding distance exceeds the best found so far (or
// `enough`, when finite: then a result above it only says "more than
// enough", and one at or below it may be an upper bound, found without
// measuring) are not measured.
double sweep_clearance(const ArmSweep& sweep, const Obstacle& obstacle,
                       double enough = std::numeric_limits<double>::infinity());

// The least distance of a point from the swept arm's surface over its steps,
// the point moving as an obstacle's centre does: the room an obstacle
// centred there has. Built once per sweep: each link's steps in chunks, each
// with a bounding ball, so that a query measures the nearest chunks only.
class SweepRoom {
 public:
  explicit SweepRoom(const ArmSweep& sweep);
  // The point is at `point` at time `t` (s) and moves at `velocity`. Exact
  // below `enough`; a result at or above it says only "at least enough".
  // `away`, when given and the result is below enough: from the arm's
  // nearest axis point to the point, at the step where they are nearest.
  double at(const Eigen::Vector3d& point, double t, const Eigen::Vector3d& velocity,
            double enough = std::numeric_limits<double>::infinity(), Eigen::Vector3d* away = nullptr) const;

 private:
  struct Chunk {
    size_t link = 0, begin = 0, end = 0;  // the link's capsules at steps [begin, end)
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    double radius = 0;         // the capsules' surfaces lie within it
    double t0 = 0, t1 = 0;     // s: the steps' times
  };
  const ArmSweep& sweep_;
  std::vector<Chunk> chunks_;
};

// Which of the sweep's capsules (by index) `obstacle` meets (distance <= 0)
// at the capsule's own step, as a run moves it: the same measure, one answer
// per capsule.
std::vector<bool> capsules_met(const ArmSweep& sweep, const std::vector<size_t>& indices, const Obstacle& obstacle);

}  // namespace rrlab
