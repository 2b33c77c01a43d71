#include <rrlab/generators/generator_clearance.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/kinematics/kinematics.hpp>

namespace rrlab {

double capsules_clearance(const std::vector<CapsuleSegment>& capsules, const Obstacle& obstacle) {
  if (capsules.empty()) return std::numeric_limits<double>::infinity();
  // A stand-in chain with one link per capsule carries the radii; its link
  // segments are then set to the capsules' own, which is all compute() reads.
  std::vector<PlanarLinkSpec> links;
  for (const CapsuleSegment& c : capsules) links.push_back({1.0, c.radius});
  const Model chain = make_planar(links, Eigen::Vector2d::Zero());
  KinematicsData kin(chain);
  for (size_t i = 0; i < capsules.size(); ++i) {
    kin.link_start.col(i) = capsules[i].a;
    kin.link_end.col(i) = capsules[i].b;
  }
  Scene scene;
  scene.obstacles.push_back(obstacle);
  scene.obstacles.back().position = obstacle.position0;
  CollisionWorld world(chain, scene);
  DistanceTable table;
  world.compute(kin, table);
  return table.min_distance;
}

ArmSweep arm_sweep(const Model& model, const std::vector<Eigen::VectorXd>& steps, double dt) {
  ArmSweep sweep;
  sweep.links = model.link_count();
  sweep.dt = dt;
  KinematicsData kin(model);
  sweep.capsules.reserve(steps.size() * size_t(sweep.links));
  for (const Eigen::VectorXd& q : steps) {
    forward_kinematics(model, q, kin);
    for (int l = 0; l < sweep.links; ++l)
      sweep.capsules.push_back({kin.link_start.col(l), kin.link_end.col(l), model.links[l].radius});
  }
  return sweep;
}

namespace {

double capsule_center_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// A ball around the obstacle at t = 0 that holds every point a capsule can
// touch (for the planar arms' prisms, boxes turned about z and polygons, only
// their footprint matters: the capsules lie in z = 0), and the radius of a
// ball about the same centre inside it (0: the centre itself is inside; the
// generator's boxes and star polygons hold their centre).
void bounding_ball(const Obstacle& o, bool planar, Eigen::Vector3d& center, double& radius, double& inner) {
  center = o.position0;
  radius = 0;
  inner = o.shape == ShapeKind::sphere ? o.radius : 0.0;
  switch (o.shape) {
    case ShapeKind::sphere: radius = o.radius; break;
    case ShapeKind::box:
      radius = planar ? 0.5 * std::hypot(o.size.x(), o.size.y()) : 0.5 * o.size.norm();
      break;
    case ShapeKind::polygon: {
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const Eigen::Vector2d& p : o.points) mean += p;
      mean /= double(o.points.size());
      for (const Eigen::Vector2d& p : o.points) radius = std::max(radius, (p - mean).norm());
      center = o.position0 + Eigen::Vector3d(mean.x(), mean.y(), 0);
      if (!planar) radius = std::hypot(radius, std::max(std::abs(o.z_min), std::abs(o.z_max)));
      break;
    }
    case ShapeKind::point: break;
    default: radius = std::numeric_limits<double>::infinity();  // walls, meshes: always measured
  }
}

}  // namespace

double sweep_clearance(const ArmSweep& sweep, const Obstacle& obstacle, double enough) {
  Eigen::Vector3d center;
  double radius = 0;
  const bool planar = std::all_of(sweep.capsules.begin(), sweep.capsules.end(),
                                  [](const CapsuleSegment& c) { return c.a.z() == 0 && c.b.z() == 0; });
  double inner = 0;
  bounding_ball(obstacle, planar, center, radius, inner);
  const bool decide = std::isfinite(enough);
  // each capsule, moved into the obstacle's frame at t = 0, with a lower bound of its distance
  struct Candidate {
    double bound;
    CapsuleSegment capsule;
  };
  std::vector<Candidate> candidates;
  const int links = std::max(sweep.links, 1);
  for (size_t c = 0; c < sweep.capsules.size(); ++c) {
    const Eigen::Vector3d shift = -obstacle.velocity * (double(c / size_t(links)) * sweep.dt);
    CapsuleSegment moved = sweep.capsules[c];
    moved.a += shift;
    moved.b += shift;
    if (!std::isfinite(radius)) {
      candidates.push_back({-std::numeric_limits<double>::infinity(), moved});
      continue;
    }
    const double to_center = capsule_center_distance(center, moved.a, moved.b) - moved.radius;
    // the centre (or the inner ball) is inside the obstacle: it is at most this far
    if (decide && to_center - inner <= enough) return to_center - inner;
    const double bound = to_center - radius;
    if (bound <= enough) candidates.push_back({bound, moved});
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) { return x.bound < y.bound; });
  // measured nearest first, in batches, until the next bound exceeds the best
  constexpr size_t kBatch = 64;
  double best = std::numeric_limits<double>::infinity();
  std::vector<CapsuleSegment> batch;
  for (size_t i = 0; i < candidates.size() && candidates[i].bound < best; i += kBatch) {
    batch.clear();
    for (size_t j = i; j < std::min(i + kBatch, candidates.size()); ++j) batch.push_back(candidates[j].capsule);
    best = std::min(best, capsules_clearance(batch, obstacle));
    if (best <= enough && enough < std::numeric_limits<double>::infinity()) break;
  }
  return best;
}

}  // namespace rrlab
