// Convex primitives and the segment's signed distance to each. The polytope
// routine (segment_polytope): separated, the exact minimum over the finite
// features (end point x face, segment x edge); intersecting, the
// separating-axis penetration depth over face normals and segment x edge
// directions, which is exactly the minimum translation (see
// best_separating_axis).
#include <rrlab/collision/convex_polytope.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

#include <rrlab/collision/segment_geometry.hpp>

namespace rrlab::collision {

using Eigen::Vector3d;

namespace {

constexpr double kEdgeSkipMargin = 1e-9;  // m: far above the rounding of closest_points_segments

void add_edge_axis(ConvexPolytope& poly, const Vector3d& direction) {
  for (const Vector3d& axis : poly.edge_axes)
    if (axis.cross(direction).norm() <= 1e-9) return;
  poly.edge_axes.push_back(direction);
}

void add_edge(ConvexPolytope& poly, int from, int to) {
  const Vector3d direction = (poly.vertices[to] - poly.vertices[from]).normalized();
  poly.edges.push_back({from, to, direction});
  add_edge_axis(poly, direction);
}

// Parameter interval [t0, t1] of a-b inside all faces but `skip`, each pushed
// out by `slack`. False when empty.
bool clip_segment(const ConvexPolytope& poly, const Vector3d& a, const Vector3d& b, int skip,
                  double slack, double& t0, double& t1) {
  const Vector3d d = b - a;
  t0 = 0;
  t1 = 1;
  for (int f = 0; f < static_cast<int>(poly.faces.size()); ++f) {
    if (f == skip) continue;
    const Face& face = poly.faces[f];
    const double along = face.normal.dot(d);
    const double room = face.offset + slack - face.normal.dot(a);
    if (along == 0) {
      if (room < 0) return false;
    } else if (along > 0) {
      t1 = std::min(t1, room / along);
    } else {
      t0 = std::max(t0, room / along);
    }
    if (t0 > t1) return false;
  }
  return true;
}

bool inside_other_faces(const ConvexPolytope& poly, const Vector3d& p, int skip) {
  for (int f = 0; f < static_cast<int>(poly.faces.size()); ++f)
    if (f != skip && poly.faces[f].normal.dot(p) - poly.faces[f].offset > kOnFace) return false;
  return true;
}

// Separated segment vs polytope: the nearest pair is an end point against a
// face interior or the segment against an edge (a pair interior to both the
// segment and a face implies the segment is parallel to that face, where an
// end point or edge pair is just as near). Returns the distance.
double separated_features(const ConvexPolytope& poly, const Vector3d& a, const Vector3d& b,
                          Vector3d& on_link, Vector3d& on_obstacle) {
  double best_sq = kInfinity;
  for (const Vector3d* end : {&a, &b}) {
    for (int f = 0; f < static_cast<int>(poly.faces.size()); ++f) {
      const Face& face = poly.faces[f];
      const double height = face.normal.dot(*end) - face.offset;
      if (height <= 0 || height * height >= best_sq) continue;
      const Vector3d foot = *end - height * face.normal;
      if (!inside_other_faces(poly, foot, f)) continue;
      best_sq = height * height;
      on_link = *end;
      on_obstacle = foot;
    }
  }
  Vector3d c1, c2;
  const Vector3d low = a.cwiseMin(b), high = a.cwiseMax(b);
  double best = std::sqrt(best_sq);
  for (const Edge& edge : poly.edges) {
    // the boxes around segment and edge are apart by at least their gap on
    // every axis: an edge whose gap exceeds the best distance by more than
    // rounding could come out below it cannot win (the result is unchanged;
    // a prism's top and bottom edges are skipped for a planar arm)
    const Vector3d& p = poly.vertices[edge.from];
    const Vector3d& q = poly.vertices[edge.to];
    const Vector3d gap = (p.cwiseMin(q) - high).cwiseMax(low - p.cwiseMax(q)).cwiseMax(0.0);
    if (gap.norm() > best + kEdgeSkipMargin) continue;
    closest_points_segments(a, b, p, q, c1, c2);
    const double dist_sq = (c1 - c2).squaredNorm();
    if (dist_sq >= best_sq) continue;
    best_sq = dist_sq;
    best = std::sqrt(best_sq);
    on_link = c1;
    on_obstacle = c2;
  }
  return std::sqrt(best_sq);
}

// Penetration by separating axes. The segment S meets P exactly when the
// origin lies in the Minkowski sum P ⊕ (−S), whose facet normals are P's face
// normals and d × e for P's edge directions e; the depth (minimum translation
// that separates) is the smallest support h(n) = h_P(n) − min_S n·s over those
// normals, and any extra candidate only gives a larger value. Valid at zero
// and at small negative depth (touching) too: that is what gives a normal.
struct Axis {
  double depth = kInfinity;  // translation along `normal` that separates
  Vector3d normal = Vector3d::Zero();
  int face = -1;  // >= 0: a face normal; else an edge axis
  Vector3d edge = Vector3d::Zero();  // the edge direction of an edge axis
};

Axis best_separating_axis(const ConvexPolytope& poly, const Vector3d& a, const Vector3d& b) {
  Axis best;
  for (int f = 0; f < static_cast<int>(poly.faces.size()); ++f) {
    const Face& face = poly.faces[f];
    const double depth = face.offset - std::min(face.normal.dot(a), face.normal.dot(b));
    if (depth < best.depth) best = {depth, face.normal, f, Vector3d::Zero()};
  }
  const Vector3d d = b - a;
  for (const Vector3d& e : poly.edge_axes) {
    const Vector3d c = d.cross(e);
    const double len = c.norm();
    if (len <= kParallel * d.norm()) continue;  // parallel: no facet of this kind
    const Vector3d n = c / len;
    double hi = -kInfinity, lo = kInfinity;
    for (const Vector3d& v : poly.vertices) {
      hi = std::max(hi, n.dot(v));
      lo = std::min(lo, n.dot(v));
    }
    const double along = n.dot(a);  // the same for every point of the segment
    // strictly better only: on ties a face normal has the cleaner witness
    if (hi - along < best.depth - kOnFace) best = {hi - along, n, -1, e};
    if (along - lo < best.depth - kOnFace) best = {along - lo, -n, -1, e};
  }
  return best;
}

// Witness points of a face axis: the deepest end point, or, for a segment
// parallel to the face, the middle of the part that slides onto the face.
void face_axis_witness(const ConvexPolytope& poly, const Vector3d& a, const Vector3d& b,
                       const Axis& axis, Vector3d& on_link) {
  const Vector3d d = b - a;
  const double da = axis.normal.dot(a), db = axis.normal.dot(b);
  if (std::abs(db - da) > kParallel * d.norm()) {
    on_link = da < db ? a : b;
    return;
  }
  const Vector3d shift = axis.depth * axis.normal;
  double t0 = 0, t1 = 1;
  const double mid = clip_segment(poly, a + shift, b + shift, axis.face, 1e-9, t0, t1)
                         ? 0.5 * (t0 + t1)
                         : 0.5;
  on_link = a + mid * d;
}

// Witness points of an edge axis: the segment against the edge along that
// direction which sticks out furthest along the normal (the obstacle lies
// behind the normal).
void edge_axis_witness(const ConvexPolytope& poly, const Vector3d& a, const Vector3d& b,
                       const Axis& axis, Vector3d& on_link, Vector3d& on_obstacle) {
  const Edge* support = nullptr;
  double support_height = -kInfinity;
  for (const Edge& edge : poly.edges) {
    if (edge.direction.cross(axis.edge).norm() > 1e-9) continue;
    const double height = axis.normal.dot(poly.vertices[edge.from]);
    if (height > support_height) {
      support_height = height;
      support = &edge;
    }
  }
  assert(support);
  closest_points_segments(a, b, poly.vertices[support->from], poly.vertices[support->to],
                          on_link, on_obstacle);
}

}  // namespace

// A counter-clockwise convex polygon extruded over z in [z_min, z_max].
ConvexPolytope make_prism(const Polygon2& ccw, double z_min, double z_max) {
  const int k = static_cast<int>(ccw.size());
  ConvexPolytope poly;
  for (const auto& p : ccw) poly.vertices.emplace_back(p.x(), p.y(), z_min);
  for (const auto& p : ccw) poly.vertices.emplace_back(p.x(), p.y(), z_max);
  poly.faces.push_back({-Vector3d::UnitZ(), -z_min});
  poly.faces.push_back({Vector3d::UnitZ(), z_max});
  for (int i = 0; i < k; ++i) {
    const Eigen::Vector2d edge = ccw[(i + 1) % k] - ccw[i];
    const Vector3d outward = Vector3d(edge.y(), -edge.x(), 0).normalized();  // right of a CCW edge
    poly.faces.push_back({outward, outward.dot(poly.vertices[i])});
  }
  for (int i = 0; i < k; ++i) {
    add_edge(poly, i, (i + 1) % k);
    add_edge(poly, k + i, k + (i + 1) % k);
    add_edge(poly, i, k + i);
  }
  return poly;
}

ConvexPolytope make_box(const Vector3d& size) {
  const double hx = size.x() / 2, hy = size.y() / 2;
  const Polygon2 rectangle{{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
  return make_prism(rectangle, -size.z() / 2, size.z() / 2);
}

// Signed distance of the segment a-b (no radius) to a convex polytope, in the
// polytope's frame.
void segment_polytope(const ConvexPolytope& poly, const Vector3d& a, const Vector3d& b,
                      LinkObstacleDistance& out) {
  double t0, t1;
  const bool intersecting = clip_segment(poly, a, b, -1, 0.0, t0, t1);
  if (!intersecting) {
    const double separation = separated_features(poly, a, b, out.on_link, out.on_obstacle);
    out.distance = separation;
    if (separation > kTouching) {
      out.normal = (out.on_link - out.on_obstacle) / separation;
      return;
    }
  }
  const Axis axis = best_separating_axis(poly, a, b);
  out.normal = axis.normal;
  if (!intersecting) return;  // touching from outside: keep the exact nearest points
  out.distance = -axis.depth;
  if (axis.face >= 0) {
    face_axis_witness(poly, a, b, axis, out.on_link);
    out.on_obstacle = out.on_link + axis.depth * axis.normal;
  } else {
    edge_axis_witness(poly, a, b, axis, out.on_link, out.on_obstacle);
  }
}

double separating_face_bound(const ConvexPolytope& poly, const Vector3d& a, const Vector3d& b) {
  double bound = -kInfinity;
  for (const Face& f : poly.faces)
    bound = std::max(bound, std::min(f.normal.dot(a), f.normal.dot(b)) - f.offset);
  return bound;
}

void segment_sphere(const Vector3d& a, const Vector3d& b, const Vector3d& centre, double radius,
                    LinkObstacleDistance& out) {
  out.on_link = closest_point_on_segment(a, b, centre);
  const Vector3d offset = out.on_link - centre;
  const double dist = offset.norm();
  out.normal = dist > kTouching ? Vector3d(offset / dist) : any_perpendicular(b - a);
  out.distance = dist - radius;
  out.on_obstacle = centre + radius * out.normal;
}

// Half-space behind the plane through `point` with outward unit `normal`.
void segment_wall(const Vector3d& a, const Vector3d& b, const Vector3d& point,
                  const Vector3d& normal, LinkObstacleDistance& out) {
  const double ha = normal.dot(a - point), hb = normal.dot(b - point);
  if (std::abs(ha - hb) <= kOnFace) {
    out.on_link = 0.5 * (a + b);  // parallel: the middle is as near as any
  } else {
    out.on_link = ha < hb ? a : b;
  }
  out.distance = std::min(ha, hb);
  out.normal = normal;
  out.on_obstacle = out.on_link - out.distance * normal;
}

}  // namespace rrlab::collision
