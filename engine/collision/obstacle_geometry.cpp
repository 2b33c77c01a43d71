// An obstacle's geometry, and a segment's distance to each obstacle kind.
#include <rrlab/collision/obstacle_geometry.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <rrlab/collision/polygon.hpp>
#include <rrlab/collision/segment_geometry.hpp>

namespace rrlab::collision {

using Eigen::Vector3d;

namespace {

std::invalid_argument bad_obstacle(const Obstacle& o, const std::string& problem) {
  return std::invalid_argument("obstacle '" + o.id + "': " + problem);
}

}  // namespace

ObstacleGeometry build_geometry(const Obstacle& o, const std::vector<ObstacleGeometry>& previous) {
  ObstacleGeometry g;
  g.shape = o.shape;
  switch (o.shape) {
    case ShapeKind::polygon: {
      if (std::string problem = polygon_problem(o.points); !problem.empty())
        throw bad_obstacle(o, problem);
      if (!(o.z_max > o.z_min)) throw bad_obstacle(o, "z_max must be > z_min");
      for (const Polygon2& part : convex_decomposition(o.points))
        g.parts.push_back(make_prism(part, o.z_min, o.z_max));
      break;
    }
    case ShapeKind::box:
      if (!(o.size.minCoeff() > 0) || !o.size.allFinite())
        throw bad_obstacle(o, "box size must be > 0");
      g.parts.push_back(make_box(o.size));
      break;
    case ShapeKind::sphere:
      if (!(o.radius >= 0) || !std::isfinite(o.radius))
        throw bad_obstacle(o, "sphere radius must be >= 0");
      g.radius = o.radius;
      break;
    case ShapeKind::point: break;
    case ShapeKind::wall:
      if (!(o.normal.norm() > 0) || !o.normal.allFinite())
        throw bad_obstacle(o, "wall normal must be non-zero");
      g.normal = o.normal.normalized();
      break;
    case ShapeKind::mesh:
      if (!o.mesh || o.mesh->triangles.empty()) throw bad_obstacle(o, "mesh has no triangles");
      g.mesh = o.mesh;  // the BVH and `closed` are reused or built below
      for (const Vector3d& v : o.mesh->vertices) g.bounds.extend(v);
      break;
  }
  if (g.mesh) {  // a mesh's BVH (and whether it is closed) outlives edits of other obstacles
    for (const ObstacleGeometry& old : previous)
      if (old.mesh == g.mesh) {
        g.bvh = old.bvh;
        g.closed = old.closed;
      }
    if (!g.bvh) {
      g.bvh = make_bvh(*g.mesh);
      g.closed = closed_mesh(*g.mesh);
    }
  }
  return g;
}

void segment_point(const ObstacleGeometry& g, const Vector3d& a, const Vector3d& b, LinkObstacleDistance& out) {
  segment_sphere(a, b, g.position, 0.0, out);
}

void segment_sphere_obstacle(const ObstacleGeometry& g, const Vector3d& a, const Vector3d& b,
                             LinkObstacleDistance& out) {
  segment_sphere(a, b, g.position, g.radius, out);
}

void segment_wall_obstacle(const ObstacleGeometry& g, const Vector3d& a, const Vector3d& b,
                           LinkObstacleDistance& out) {
  segment_wall(a, b, g.position, g.rotation * g.normal, out);
}

void segment_mesh_obstacle(const ObstacleGeometry& g, const Vector3d& a, const Vector3d& b,
                           LinkObstacleDistance& out) {
  segment_mesh(*g.bvh, g.closed, g.bounds, g.rotation, g.position, a, b, out);
}

double segment_polytopes_bound(const ObstacleGeometry& g, const Vector3d& a, const Vector3d& b) {
  const Vector3d a_local = g.rotation.transpose() * (a - g.position);
  const Vector3d b_local = g.rotation.transpose() * (b - g.position);
  double bound = kInfinity;
  for (const ConvexPolytope& part : g.parts) bound = std::min(bound, separating_face_bound(part, a_local, b_local));
  return bound;
}

// A box or polygon: the minimum over its convex parts.
void segment_polytopes(const ObstacleGeometry& g, const Vector3d& a, const Vector3d& b, LinkObstacleDistance& out) {
  // in the obstacle's frame, then back; the minimum over convex parts
  const Vector3d a_local = g.rotation.transpose() * (a - g.position);
  const Vector3d b_local = g.rotation.transpose() * (b - g.position);
  LinkObstacleDistance part_result;
  out.distance = kInfinity;
  for (const ConvexPolytope& part : g.parts) {
    // a part whose face planes keep it farther than the nearest so far cannot be the nearest
    if (separating_face_bound(part, a_local, b_local) > out.distance + kBoundMargin) continue;
    segment_polytope(part, a_local, b_local, part_result);
    if (part_result.distance < out.distance) out = part_result;
  }
  out.on_link = g.rotation * out.on_link + g.position;
  out.on_obstacle = g.rotation * out.on_obstacle + g.position;
  out.normal = g.rotation * out.normal;
}

}  // namespace rrlab::collision
