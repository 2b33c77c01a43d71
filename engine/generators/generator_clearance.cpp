#include <rrlab/generators/generator_clearance.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/mesh_loader.hpp>
#include <rrlab/collision/obstacle_geometry.hpp>
#include <rrlab/collision/segment_geometry.hpp>
#include <rrlab/kinematics/kinematics.hpp>

namespace rrlab {

namespace {

// The distance table of the capsules against the obstacle at its position0:
// a stand-in chain with one link per capsule carries the radii; its link
// segments are then set to the capsules' own, which is all compute() reads.
void stand_in_distances(const std::vector<CapsuleSegment>& capsules, const Obstacle& obstacle, DistanceTable& table) {
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
  world.compute(kin, table);
}

}  // namespace

double capsules_clearance(const std::vector<CapsuleSegment>& capsules, const Obstacle& obstacle) {
  if (capsules.empty()) return std::numeric_limits<double>::infinity();
  DistanceTable table;
  stand_in_distances(capsules, obstacle, table);
  return table.min_distance;
}

namespace {

// An obstacle as zero-radius capsules along its edges at t = 0, or one
// capsule at its centre (a sphere, a point); none for a wall.
std::vector<CapsuleSegment> obstacle_edges(const Obstacle& o) {
  std::vector<CapsuleSegment> edges;
  const auto world = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d { return o.rotation * v + o.position0; };
  switch (o.shape) {
    case ShapeKind::sphere: edges.push_back({o.position0, o.position0, o.radius}); break;
    case ShapeKind::point: edges.push_back({o.position0, o.position0, 0.0}); break;
    case ShapeKind::wall: break;
    case ShapeKind::mesh:
      for (const Eigen::Vector3i& t : o.mesh->triangles)
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3d& from = o.mesh->vertices[size_t(t[k])];
          const Eigen::Vector3d& to = o.mesh->vertices[size_t(t[(k + 1) % 3])];
          edges.push_back({world(from), world(to), 0.0});
        }
      break;
    case ShapeKind::polygon:
    case ShapeKind::box:
      for (const collision::ConvexPolytope& part : collision::build_geometry(o).parts)
        for (const collision::Edge& e : part.edges)
          edges.push_back({world(part.vertices[size_t(e.from)]), world(part.vertices[size_t(e.to)]), 0.0});
      break;
  }
  return edges;
}

}  // namespace

double obstacles_distance(const Obstacle& a, const Obstacle& b) {
  return std::min(capsules_clearance(obstacle_edges(a), b), capsules_clearance(obstacle_edges(b), a));
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

SweepRoom::SweepRoom(const ArmSweep& sweep) : sweep_(sweep) {
  constexpr size_t kChunkSteps = 16;
  const size_t links = size_t(std::max(sweep.links, 1)), steps = sweep.capsules.size() / links;
  for (size_t link = 0; link < links; ++link)
    for (size_t begin = 0; begin < steps; begin += kChunkSteps) {
      Chunk chunk;
      chunk.link = link;
      chunk.begin = begin;
      chunk.end = std::min(steps, begin + kChunkSteps);
      for (size_t j = chunk.begin; j < chunk.end; ++j)
        chunk.center += sweep.capsules[j * links + link].a + sweep.capsules[j * links + link].b;
      chunk.center /= double(2 * (chunk.end - chunk.begin));
      for (size_t j = chunk.begin; j < chunk.end; ++j) {
        const CapsuleSegment& c = sweep.capsules[j * links + link];
        chunk.radius = std::max(chunk.radius, std::max((c.a - chunk.center).norm(), (c.b - chunk.center).norm()) + c.radius);
      }
      chunk.t0 = double(chunk.begin) * sweep.dt;
      chunk.t1 = double(chunk.end - 1) * sweep.dt;
      chunks_.push_back(chunk);
    }
}

double SweepRoom::at(const Eigen::Vector3d& point, double t, const Eigen::Vector3d& velocity, double enough,
                     Eigen::Vector3d* away) const {
  const size_t links = size_t(std::max(sweep_.links, 1));
  const double speed = velocity.norm();
  // each chunk's lower bound: the point at the chunk's middle time, which the
  // point leaves by at most speed × half the chunk's span
  std::vector<std::pair<double, size_t>> bounds;
  bounds.reserve(chunks_.size());
  for (size_t k = 0; k < chunks_.size(); ++k) {
    const Chunk& c = chunks_[k];
    const Eigen::Vector3d middle = point + (0.5 * (c.t0 + c.t1) - t) * velocity;
    const double bound = (middle - c.center).norm() - c.radius - 0.5 * speed * (c.t1 - c.t0);
    if (bound < enough) bounds.emplace_back(bound, k);
  }
  std::sort(bounds.begin(), bounds.end());
  double least = enough;
  for (const auto& [bound, k] : bounds) {
    if (bound >= least) break;
    for (size_t j = chunks_[k].begin; j < chunks_[k].end; ++j) {
      const CapsuleSegment& s = sweep_.capsules[j * links + chunks_[k].link];
      const Eigen::Vector3d p = point + (double(j) * sweep_.dt - t) * velocity;
      const Eigen::Vector3d on_axis = collision::closest_point_on_segment(s.a, s.b, p);
      const double d = (on_axis - p).norm() - s.radius;
      if (d < least) {
        least = d;
        if (away) *away = p - on_axis;
      }
    }
  }
  return least;
}

std::vector<bool> capsules_met(const ArmSweep& sweep, const std::vector<size_t>& indices, const Obstacle& obstacle) {
  Eigen::Vector3d center;
  double radius = 0, inner = 0;
  const bool planar = std::all_of(sweep.capsules.begin(), sweep.capsules.end(),
                                  [](const CapsuleSegment& c) { return c.a.z() == 0 && c.b.z() == 0; });
  bounding_ball(obstacle, planar, center, radius, inner);
  const int links = std::max(sweep.links, 1);
  // only capsules within the obstacle's bounding ball are measured, in one batch
  std::vector<CapsuleSegment> near;
  std::vector<size_t> near_at;
  for (size_t i = 0; i < indices.size(); ++i) {
    CapsuleSegment moved = sweep.capsules[indices[i]];
    const Eigen::Vector3d shift = -obstacle.velocity * (double(indices[i] / size_t(links)) * sweep.dt);
    moved.a += shift;
    moved.b += shift;
    if (std::isfinite(radius) && capsule_center_distance(center, moved.a, moved.b) - moved.radius - radius > 0) continue;
    near.push_back(moved);
    near_at.push_back(i);
  }
  std::vector<bool> met(indices.size(), false);
  if (near.empty()) return met;
  DistanceTable table;
  stand_in_distances(near, obstacle, table);
  for (size_t j = 0; j < near.size(); ++j) met[near_at[j]] = table.at(int(j), 0).distance <= 0;
  return met;
}

}  // namespace rrlab
