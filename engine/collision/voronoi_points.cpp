#include <rrlab/collision/voronoi_points.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <rrlab/collision/mesh_loader.hpp>

namespace rrlab {
namespace {

constexpr double kInfiniteDistance = std::numeric_limits<double>::infinity();

Eigen::Vector3d pose_point(const Obstacle& o, double time_offset, const Eigen::Vector3d& local) {
  return o.position + time_offset * o.velocity + o.rotation * local;
}

Eigen::Vector3d wall_normal(const Obstacle& o) { return (o.rotation * o.normal).normalized(); }

// Foot of the perpendicular from p on the wall plane.
Eigen::Vector3d wall_foot(const Obstacle& o, double time_offset, const Eigen::Vector3d& p) {
  const Eigen::Vector3d n = wall_normal(o);
  const Eigen::Vector3d origin = o.position + time_offset * o.velocity;
  return p - n.dot(p - origin) * n;
}

// Vertex-pair gap with sphere radii taken off, and the midpoint of the gap.
double gap(const ControlPoint& a, const ControlPoint& b, Eigen::Vector3d* mid) {
  const Eigen::Vector3d d = b.point - a.point;
  const double len = d.norm();
  if (mid) {
    const Eigen::Vector3d u = len > 0 ? Eigen::Vector3d(d / len) : Eigen::Vector3d::Zero();
    *mid = 0.5 * ((a.point + a.radius * u) + (b.point - b.radius * u));
  }
  return len - a.radius - b.radius;
}

}  // namespace

void obstacle_vertices(const Obstacle& o, double z, double time_offset, bool edge_midpoints,
                       std::vector<ControlPoint>& out) {
  switch (o.shape) {
    case ShapeKind::polygon: {
      const double zc = std::clamp(z, o.z_min, o.z_max);
      const size_t k = o.points.size();
      for (size_t i = 0; i < k; ++i) {
        const Eigen::Vector2d& v = o.points[i];
        out.push_back({pose_point(o, time_offset, {v.x(), v.y(), zc}), 0.0});
        if (edge_midpoints) {
          const Eigen::Vector2d m = 0.5 * (v + o.points[(i + 1) % k]);
          out.push_back({pose_point(o, time_offset, {m.x(), m.y(), zc}), 0.0});
        }
      }
      break;
    }
    case ShapeKind::box:
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d s((c & 1) ? 0.5 : -0.5, (c & 2) ? 0.5 : -0.5, (c & 4) ? 0.5 : -0.5);
        out.push_back({pose_point(o, time_offset, s.cwiseProduct(o.size)), 0.0});
      }
      break;
    case ShapeKind::sphere: out.push_back({pose_point(o, time_offset, Eigen::Vector3d::Zero()), o.radius}); break;
    case ShapeKind::point: out.push_back({pose_point(o, time_offset, Eigen::Vector3d::Zero()), 0.0}); break;
    case ShapeKind::wall: break;
    case ShapeKind::mesh:  // every vertex (as the box gives its corners)
      for (const Eigen::Vector3d& v : o.mesh->vertices) out.push_back({pose_point(o, time_offset, v), 0.0});
      break;
  }
}

namespace {

// The point of candidate c seen from p: spheres give their surface point toward p.
Eigen::Vector3d seen_from(const ControlPoint& c, const Eigen::Vector3d& p) {
  if (c.radius <= 0) return c.point;
  const Eigen::Vector3d d = p - c.point;
  const double len = d.norm();
  return len > 0 ? Eigen::Vector3d(c.point + (c.radius / len) * d) : c.point;
}

}  // namespace

NearestObstaclePoint nearest_obstacle_point(const Scene& scene, const Eigen::Vector3d& p,
                                            double time_offset, bool edge_midpoints,
                                            std::vector<ControlPoint>& scratch) {
  NearestObstaclePoint best;
  best.distance = kInfiniteDistance;
  for (size_t k = 0; k < scene.obstacles.size(); ++k) {
    const Obstacle& o = scene.obstacles[k];
    auto consider = [&](const Eigen::Vector3d& x, int candidate) {
      const double d = (x - p).norm();
      if (d < best.distance) best = {true, int(k), candidate, d, x};
    };
    if (o.shape == ShapeKind::wall) {
      consider(wall_foot(o, time_offset, p), 0);
      continue;
    }
    scratch.clear();
    obstacle_vertices(o, p.z(), time_offset, edge_midpoints, scratch);
    for (size_t c = 0; c < scratch.size(); ++c) consider(seen_from(scratch[c], p), int(c));
  }
  return best;
}

NearestObstaclePoint obstacle_candidate(const Scene& scene, int obstacle, int candidate, const Eigen::Vector3d& p,
                                        double time_offset, bool edge_midpoints,
                                        std::vector<ControlPoint>& scratch) {
  NearestObstaclePoint out;
  if (obstacle < 0 || obstacle >= int(scene.obstacles.size()) || candidate < 0) return out;
  const Obstacle& o = scene.obstacles[size_t(obstacle)];
  if (o.shape == ShapeKind::wall) {
    if (candidate != 0) return out;
    out.point = wall_foot(o, time_offset, p);
  } else {
    scratch.clear();
    obstacle_vertices(o, p.z(), time_offset, edge_midpoints, scratch);
    if (candidate >= int(scratch.size())) return out;
    out.point = seen_from(scratch[size_t(candidate)], p);
  }
  out.found = true;
  out.obstacle = obstacle;
  out.candidate = candidate;
  out.distance = (out.point - p).norm();
  return out;
}

void voronoi_control_points(const Scene& scene, double time_offset, std::vector<ControlPoint>& a,
                            std::vector<ControlPoint>& b, std::vector<Eigen::Vector3d>& out,
                            double tie) {
  out.clear();
  const size_t count = scene.obstacles.size();
  for (size_t i = 0; i < count; ++i) {
    const Obstacle& oi = scene.obstacles[i];
    if (oi.shape == ShapeKind::wall) continue;
    a.clear();
    obstacle_vertices(oi, 0.0, time_offset, false, a);
    for (size_t j = 0; j < count; ++j) {
      if (j == i) continue;
      const Obstacle& oj = scene.obstacles[j];
      if (oj.shape == ShapeKind::wall) {
        // the gap between obstacle i and wall j: nearest vertex to the plane
        const Eigen::Vector3d n = wall_normal(oj);
        const Eigen::Vector3d origin = oj.position + time_offset * oj.velocity;
        double smallest = kInfiniteDistance;
        for (const ControlPoint& v : a) smallest = std::min(smallest, n.dot(v.point - origin) - v.radius);
        for (const ControlPoint& v : a) {
          const double h = n.dot(v.point - origin) - v.radius;
          if (h <= smallest + tie * std::max(1.0, std::abs(smallest)))
            out.push_back(v.point - (v.radius + 0.5 * h) * n);
        }
        continue;
      }
      if (j < i) continue;  // each obstacle pair once
      b.clear();
      obstacle_vertices(oj, 0.0, time_offset, false, b);
      double smallest = kInfiniteDistance;
      for (const ControlPoint& u : a)
        for (const ControlPoint& v : b) smallest = std::min(smallest, gap(u, v, nullptr));
      const double limit = smallest + tie * std::max(1.0, std::abs(smallest));
      Eigen::Vector3d mid;
      for (const ControlPoint& u : a)
        for (const ControlPoint& v : b)
          if (gap(u, v, &mid) <= limit) out.push_back(mid);
    }
  }
}

}  // namespace rrlab
