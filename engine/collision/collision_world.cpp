// Link–obstacle distances: the one file that includes FCL.
//
// Which pairs use what (every link is a capsule: its axis segment plus a radius;
// each pair is first solved for the bare segment, then the radius is
// subtracted, which is exact for capsules, including penetration depths):
//
//   link x point, sphere  analytic: closest point of a segment to a point.
//   link x wall           analytic: a half-space's signed distance is linear,
//                         so the segment's minimum is at an end point.
//   link x box, polygon   analytic convex-polytope routine (segment_polytope):
//                         separated: exact minimum over the finite features
//                         (end point x face, segment x edge); intersecting:
//                         separating-axis penetration depth over face normals
//                         and segment x edge directions, which is exactly the
//                         minimum translation (see best_separating_axis). A
//                         polygon is the minimum over its convex parts: exact
//                         when apart; when penetrating, the deepest part's
//                         depth, which near an internal diagonal can be less
//                         than the whole polygon's and point across it.
//   link x mesh           the segment against the obstacle's OBBRSS tree (FCL's
//                         BVHModel, built once per mesh): RSS bounds prune,
//                         leaves are exact segment–triangle distances
//                         (segment_mesh). Exact when apart and while only the
//                         capsule's radius overlaps the mesh; a segment crossing
//                         the surface reports -kMeshContact (minus the radius);
//                         one wholly inside a closed mesh, minus its distance
//                         to the surface (ray parity decides inside).
//
// Why not FCL in compute(): FCL 0.7 (Debian 0.7.0) failed here in four ways,
// all reproduced while writing this file:
//   - a capsule of radius ~0 (a bare segment) against a box: GJK stops early
//     and returns distances up to 30% too large;
//   - signed distance (EPA via libccd) aborts the process on an assertion in
//     ComputeVisiblePatch for some penetrating capsule-box poses, and throws
//     near touching contact elsewhere (issues #319, #493; Drake #21673);
//   - capsule vs Halfspace distance dereferences a missing GJK support
//     function and crashes;
//   - nearest points are ~1e-7 accurate and lie on the capsule surface, and
//     distances carry GJK's tolerance (issues #127, #275).
// The analytic routines are exact up to rounding and allocate nothing. FCL
// stays the independent reference: compute_with_fcl() fills the same table
// from fcl::distance / fcl::collide (Capsule vs Convex, Box, Sphere; walls
// analytic there too), and the tests check that both agree on random poses.
//
// A zero link radius needs no special case: the segment routines are exact.
//
// Links with a collision mesh (URDF robots) are the exception: their
// distances come from FCL's BVH model (OBBRSS) of the mesh against each
// obstacle's FCL shape, in compute() as in compute_with_fcl(); walls stay
// analytic (the lowest vertex). FCL's mesh distance gives no penetration
// depth: a penetrating mesh link reports -kMeshContact. A mesh link against a
// mesh obstacle is FCL's BVH–BVH distance (exact triangle pairs).
#include "collision/mesh_loader.hpp"
#include "collision/collision_world.hpp"

#include <fcl/fcl.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <array>
#include <limits>
#include <map>
#include <stdexcept>

#include "collision/polygon.hpp"

namespace rrlab {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Below this separation (m) a normal from the nearest points is noise: the
// separating-axis normal, defined at contact, is used instead.
constexpr double kTouching = 1e-12;
// Slack (m) for "this point lies on that face" tests.
constexpr double kOnFace = 1e-12;
// Relative tolerance for parallel directions.
constexpr double kParallel = 1e-12;

// --- convex polytopes in an obstacle's own frame ------------------------------

struct Face {
  Vector3d normal;  // outward, unit; inside is normal·x <= offset
  double offset = 0;
};

struct Edge {
  int from = 0, to = 0;
  Vector3d direction;  // unit
};

struct ConvexPolytope {
  std::vector<Vector3d> vertices;
  std::vector<Face> faces;
  std::vector<Edge> edges;
  std::vector<Vector3d> edge_axes;  // distinct edge directions up to sign
};

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

// --- small exact geometry ------------------------------------------------------

// Closest points of segments p1-q1 and p2-q2 (Ericson, Real-Time Collision
// Detection, 5.1.9), robust to zero-length segments.
void closest_points_segments(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2,
                             const Vector3d& q2, Vector3d& c1, Vector3d& c2) {
  const Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kDegenerate = 1e-30;
  double s = 0, t = 0;
  if (a <= kDegenerate && e <= kDegenerate) {
    s = t = 0;
  } else if (a <= kDegenerate) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kDegenerate) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  c1 = p1 + s * d1;
  c2 = p2 + t * d2;
}

Vector3d closest_point_on_segment(const Vector3d& a, const Vector3d& b, const Vector3d& p) {
  const Vector3d d = b - a;
  const double len_sq = d.squaredNorm();
  if (len_sq <= 1e-30) return a;
  return a + std::clamp((p - a).dot(d) / len_sq, 0.0, 1.0) * d;
}

// A unit direction across the segment, for contacts on its axis where "away"
// is ambiguous; in the x–y plane when possible so planar arms stay planar.
Vector3d any_perpendicular(const Vector3d& d) {
  if (d.norm() <= 1e-15) return Vector3d::UnitY();
  Vector3d across = d.cross(Vector3d::UnitZ());
  if (across.norm() <= 1e-9 * d.norm()) across = d.cross(Vector3d::UnitX());
  return across.normalized();
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
  for (const Edge& edge : poly.edges) {
    closest_points_segments(a, b, poly.vertices[edge.from], poly.vertices[edge.to], c1, c2);
    const double dist_sq = (c1 - c2).squaredNorm();
    if (dist_sq >= best_sq) continue;
    best_sq = dist_sq;
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

// --- triangle meshes (mesh links and mesh obstacles) ------------------------------

using MeshBvh = fcl::BVHModel<fcl::OBBRSSd>;

// Reported for touching or penetrating meshes, whose depth FCL does not give.
constexpr double kMeshContact = 1e-9;

std::shared_ptr<MeshBvh> make_bvh(const TriangleMesh& mesh) {
  auto bvh = std::make_shared<MeshBvh>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel();
  bvh->addSubModel(mesh.vertices, triangles);
  bvh->endModel();
  return bvh;
}

// Ericson, "Real-Time Collision Detection", 5.1.5: the point of triangle abc nearest p.
Vector3d closest_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// The point of segment a-b nearest triangle p0 p1 p2 and the triangle's
// point nearest it, exact: 0 where the segment crosses the triangle, else the
// minimum over the end points against the triangle and the segment against
// its three edges (a nearest pair interior to both would make them parallel,
// where such a pair is as near). `crossing` tells the first case.
double segment_triangle(const Vector3d& a, const Vector3d& b, const Vector3d& p0, const Vector3d& p1,
                        const Vector3d& p2, Vector3d& on_segment, Vector3d& on_triangle, bool& crossing) {
  crossing = false;
  const Vector3d n = (p1 - p0).cross(p2 - p0);
  const double da = n.dot(a - p0), db = n.dot(b - p0);
  if (n.squaredNorm() > 0 && ((da <= 0 && db >= 0) || (da >= 0 && db <= 0)) && da != db) {
    const Vector3d x = a + da / (da - db) * (b - a);  // where the line meets the plane
    if (n.dot((p1 - p0).cross(x - p0)) >= 0 && n.dot((p2 - p1).cross(x - p1)) >= 0 &&
        n.dot((p0 - p2).cross(x - p2)) >= 0) {
      on_segment = on_triangle = x;
      crossing = true;
      return 0.0;
    }
  }
  double best = kInfinity;
  for (const Vector3d* end : {&a, &b}) {
    const Vector3d c = closest_on_triangle(*end, p0, p1, p2);
    const double d = (c - *end).squaredNorm();
    if (d < best) {
      best = d;
      on_segment = *end;
      on_triangle = c;
    }
  }
  const Vector3d* corners[3] = {&p0, &p1, &p2};
  Vector3d c1, c2;
  for (int e = 0; e < 3; ++e) {
    closest_points_segments(a, b, *corners[e], *corners[(e + 1) % 3], c1, c2);
    const double d = (c1 - c2).squaredNorm();
    if (d < best) {
      best = d;
      on_segment = c1;
      on_triangle = c2;
    }
  }
  return std::sqrt(best);
}

// Segment against a mesh through its OBBRSS tree (FCL's BVH, built once): a
// node is opened only when its RSS (rectangle swept sphere, the OBBRSS's
// distance volume) lies nearer than the best triangle so far, the nearer
// child first; leaves are solved exactly by segment_triangle. Allocation
// free (fcl::distance on a capsule allocates while bounding the capsule).
struct SegmentMeshQuery {
  Vector3d a, b;
  fcl::RSSd segment;  // the segment as a zero-width, zero-radius RSS
  double best = kInfinity;
  int triangle = -1;
  bool crossing = false;
  Vector3d on_segment = Vector3d::Zero(), on_mesh = Vector3d::Zero();
};

void descend(const MeshBvh& bvh, int node, SegmentMeshQuery& q) {
  const fcl::BVNode<fcl::OBBRSSd>& n = bvh.getBV(node);
  if (n.isLeaf()) {
    const fcl::Triangle& t = bvh.tri_indices[n.primitiveId()];
    Vector3d on_segment, on_mesh;
    bool crossing = false;
    const double d = segment_triangle(q.a, q.b, bvh.vertices[t[0]], bvh.vertices[t[1]], bvh.vertices[t[2]],
                                      on_segment, on_mesh, crossing);
    if (d < q.best) {
      q.best = d;
      q.triangle = n.primitiveId();
      q.crossing = crossing;
      q.on_segment = on_segment;
      q.on_mesh = on_mesh;
    }
    return;
  }
  int first = n.leftChild(), second = n.rightChild();
  double d_first = bvh.getBV(first).bv.rss.distance(q.segment);
  double d_second = bvh.getBV(second).bv.rss.distance(q.segment);
  if (d_second < d_first) {
    std::swap(first, second);
    std::swap(d_first, d_second);
  }
  if (d_first < q.best) descend(bvh, first, q);
  if (d_second < q.best) descend(bvh, second, q);
}

// Whether every edge of the mesh (vertices welded by position) borders
// exactly two triangles: a closed surface, whose inside a ray's parity finds.
bool closed_mesh(const TriangleMesh& mesh) {
  std::map<std::array<double, 3>, int> welded;
  std::vector<int> id(mesh.vertices.size());
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Vector3d& p = mesh.vertices[v];
    id[v] = welded.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, int(welded.size())).first->second;
  }
  std::map<std::pair<int, int>, int> edges;
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const int i = id[size_t(t[e])], j = id[size_t(t[(e + 1) % 3])];
      if (i != j) ++edges[{std::min(i, j), std::max(i, j)}];
    }
  for (const auto& [edge, count] : edges)
    if (count != 2) return false;
  return !edges.empty();
}

// Whether p lies inside a closed mesh: the parity of a ray's crossings
// (Möller & Trumbore's ray–triangle test) along a fixed direction chosen off
// the axes and diagonals, so that it seldom meets an edge or vertex exactly.
bool inside_mesh(const MeshBvh& bvh, const Vector3d& p) {
  static const Vector3d ray = Vector3d(0.2672612419124244, 0.5345224838248488, 0.8017837257372732);  // (1, 2, 3)/√14
  bool inside = false;
  for (int i = 0; i < bvh.num_tris; ++i) {
    const fcl::Triangle& t = bvh.tri_indices[i];
    const Vector3d& v0 = bvh.vertices[t[0]];
    const Vector3d e1 = bvh.vertices[t[1]] - v0, e2 = bvh.vertices[t[2]] - v0;
    const Vector3d h = ray.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-300) continue;  // parallel to the ray
    const Vector3d s = p - v0;
    const double u = s.dot(h) / det;
    if (u < 0 || u > 1) continue;
    const Vector3d q = s.cross(e1);
    const double v = ray.dot(q) / det;
    if (v < 0 || u + v > 1) continue;
    if (e2.dot(q) / det > 0) inside = !inside;
  }
  return inside;
}

// Signed distance of segment a-b (world, no radius) to a mesh obstacle. A
// segment crossing the surface reports -kMeshContact with the crossed
// triangle's normal (outward for counter-clockwise triangles). A segment
// wholly inside a closed mesh (`closed`, tested when its start lies in the
// mesh's bounds) reports minus its distance to the surface, with the normal
// pointing out to that nearest surface point: the depth of the nearest point,
// at most the depth that separates. Inside an open mesh nothing is detected.
void segment_mesh(const MeshBvh& bvh, bool closed, const Eigen::AlignedBox3d& bounds, const Matrix3d& rotation,
                  const Vector3d& position, const Vector3d& a, const Vector3d& b, LinkObstacleDistance& out) {
  SegmentMeshQuery q;
  q.a = rotation.transpose() * (a - position);
  q.b = rotation.transpose() * (b - position);
  const Vector3d d = q.b - q.a;
  const Vector3d along = d.norm() > 0 ? Vector3d(d.normalized()) : Vector3d::UnitZ();
  const Vector3d across = any_perpendicular(along);
  q.segment.axis.col(0) = along;
  q.segment.axis.col(1) = across;
  q.segment.axis.col(2) = along.cross(across);
  q.segment.To = q.a;
  q.segment.l[0] = d.norm();
  q.segment.l[1] = 0;
  q.segment.r = 0;
  descend(bvh, 0, q);
  out.on_link = rotation * q.on_segment + position;
  out.on_obstacle = rotation * q.on_mesh + position;
  if (!q.crossing && q.best > kTouching) {
    if (closed && bounds.contains(q.a) && inside_mesh(bvh, q.a)) {
      out.distance = -q.best;
      out.normal = (out.on_obstacle - out.on_link) / q.best;
      return;
    }
    out.distance = q.best;
    out.normal = (out.on_link - out.on_obstacle) / q.best;
    return;
  }
  const fcl::Triangle& t = bvh.tri_indices[q.triangle];
  const Vector3d face = (bvh.vertices[t[1]] - bvh.vertices[t[0]]).cross(bvh.vertices[t[2]] - bvh.vertices[t[0]]);
  out.normal = face.norm() > 0 ? Vector3d(rotation * face.normalized()) : any_perpendicular(b - a);
  out.distance = q.crossing ? -kMeshContact : q.best;
}

// --- obstacles -------------------------------------------------------------------

struct ObstacleGeometry {
  ShapeKind shape = ShapeKind::point;
  std::vector<ConvexPolytope> parts;  // polygon parts or the box, own frame
  double radius = 0;                  // sphere
  Vector3d normal = Vector3d::UnitY();  // wall, own frame, unit
  std::shared_ptr<const TriangleMesh> mesh;  // mesh, own frame
  std::shared_ptr<MeshBvh> bvh;              // mesh: built once, shared across reshapes
  bool closed = false;                       // mesh: a closed surface (inside is detected)
  Eigen::AlignedBox3d bounds;                // mesh: its vertices' box, own frame
  Matrix3d rotation = Matrix3d::Identity();
  Vector3d position = Vector3d::Zero();
};

std::invalid_argument bad_obstacle(const Obstacle& o, const std::string& problem) {
  return std::invalid_argument("obstacle '" + o.id + "': " + problem);
}

ObstacleGeometry build_geometry(const Obstacle& o) {
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
      g.mesh = o.mesh;  // the BVH and `closed` are built (or reused) by the caller
      for (const Vector3d& v : o.mesh->vertices) g.bounds.extend(v);
      break;
  }
  return g;
}

// Signed distance of segment a-b (world) to one obstacle, without the radius.
void segment_obstacle(const ObstacleGeometry& g, const Vector3d& a, const Vector3d& b,
                      LinkObstacleDistance& out) {
  switch (g.shape) {
    case ShapeKind::point: segment_sphere(a, b, g.position, 0.0, out); return;
    case ShapeKind::sphere: segment_sphere(a, b, g.position, g.radius, out); return;
    case ShapeKind::wall: segment_wall(a, b, g.position, g.rotation * g.normal, out); return;
    case ShapeKind::mesh: segment_mesh(*g.bvh, g.closed, g.bounds, g.rotation, g.position, a, b, out); return;
    case ShapeKind::polygon:
    case ShapeKind::box: break;
  }
  // in the obstacle's frame, then back; the minimum over convex parts
  const Vector3d a_local = g.rotation.transpose() * (a - g.position);
  const Vector3d b_local = g.rotation.transpose() * (b - g.position);
  LinkObstacleDistance part_result;
  out.distance = kInfinity;
  for (const ConvexPolytope& part : g.parts) {
    segment_polytope(part, a_local, b_local, part_result);
    if (part_result.distance < out.distance) out = part_result;
  }
  out.on_link = g.rotation * out.on_link + g.position;
  out.on_obstacle = g.rotation * out.on_obstacle + g.position;
  out.normal = g.rotation * out.normal;
}

// --- the FCL reference path ----------------------------------------------------------

std::shared_ptr<fcl::Convexd> make_fcl_prism(const ConvexPolytope& prism) {
  // make_prism's layout: k bottom vertices, then k top ones
  const int k = static_cast<int>(prism.vertices.size()) / 2;
  auto vertices = std::make_shared<std::vector<Vector3d>>(prism.vertices);
  auto faces = std::make_shared<std::vector<int>>();
  faces->push_back(k);  // bottom, seen from below: clockwise in x–y
  for (int i = k - 1; i >= 0; --i) faces->push_back(i);
  faces->push_back(k);  // top
  for (int i = 0; i < k; ++i) faces->push_back(k + i);
  for (int i = 0; i < k; ++i) {
    const int j = (i + 1) % k;
    faces->insert(faces->end(), {4, i, j, k + j, k + i});
  }
  return std::make_shared<fcl::Convexd>(vertices, k + 2, faces);
}

struct FclObstacle {
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> parts;
};

FclObstacle build_fcl(const Obstacle& o, const ObstacleGeometry& g) {
  FclObstacle f;
  switch (o.shape) {
    case ShapeKind::polygon:
      for (const ConvexPolytope& part : g.parts) f.parts.push_back(make_fcl_prism(part));
      break;
    case ShapeKind::box: f.parts.push_back(std::make_shared<fcl::Boxd>(o.size)); break;
    case ShapeKind::sphere: f.parts.push_back(std::make_shared<fcl::Sphered>(g.radius)); break;
    case ShapeKind::point: f.parts.push_back(std::make_shared<fcl::Sphered>(0.0)); break;
    case ShapeKind::wall:
      // none: FCL 0.7 has no distance query for a Halfspace; its generic GJK
      // then calls a missing support function and crashes
      break;
    case ShapeKind::mesh: f.parts.push_back(g.bvh); break;  // BVH: against capsules and mesh links
  }
  return f;
}

// Smallest capsule radius FCL's GJK handles (see compute_with_fcl).
constexpr double kFclMinRadius = 1e-3;

fcl::Transform3d capsule_pose(const Vector3d& a, const Vector3d& b) {
  fcl::Transform3d pose = fcl::Transform3d::Identity();
  pose.translation() = 0.5 * (a + b);
  if ((b - a).norm() > 0)
    pose.linear() = Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), b - a).toRotationMatrix();
  return pose;
}

struct FclLink {
  const fcl::Capsuled* capsule;
  fcl::Transform3d pose;
  Vector3d start, end;  // axis segment
  double inflation;     // added to the radius for FCL's sake
};

// FCL's points lie on the capsule surface: step back to the axis.
void from_fcl_points(const FclLink& link, double distance, const Vector3d& on_capsule,
                     const Vector3d& on_obstacle, LinkObstacleDistance& out) {
  out.distance = distance + link.inflation;
  out.on_link = closest_point_on_segment(link.start, link.end, on_capsule);
  out.on_obstacle = on_obstacle;
  const Vector3d gap = on_capsule - on_obstacle;
  out.normal = gap.norm() > 0 ? Vector3d(gap.normalized()) : Vector3d::Zero();
}

// One capsule against one FCL shape: GJK distance when apart, else the depth
// from fcl::collide's contact (libccd MPR). FCL's signed distance (EPA) is not
// used: in 0.7 it aborts on an assertion in ComputeVisiblePatch for some
// penetrating poses, which no try/catch survives.
void fcl_pair(const FclLink& link, const fcl::CollisionGeometryd& shape,
              const fcl::Transform3d& shape_pose, LinkObstacleDistance& out) {
  fcl::DistanceRequestd distance_request(true, false, 0.0, 0.0, 1e-10, fcl::GST_LIBCCD);
  fcl::DistanceResultd distance_result;
  fcl::distance(link.capsule, link.pose, &shape, shape_pose, distance_request, distance_result);
  // a shape against a BVH (a mesh obstacle) is solved as BVH against shape,
  // and FCL 0.7 hands back the nearest points in that order
  if (shape.getObjectType() == fcl::OT_BVH)
    std::swap(distance_result.nearest_points[0], distance_result.nearest_points[1]);
  if (distance_result.min_distance > 0) {
    from_fcl_points(link, distance_result.min_distance, distance_result.nearest_points[0],
                    distance_result.nearest_points[1], out);
    return;
  }
  fcl::CollisionRequestd collision_request(1, true);
  fcl::CollisionResultd collision_result;
  fcl::collide(link.capsule, link.pose, &shape, shape_pose, collision_request, collision_result);
  if (collision_result.numContacts() == 0) {  // touching: GJK says 0, MPR says apart
    from_fcl_points(link, 0.0, distance_result.nearest_points[0],
                    distance_result.nearest_points[1], out);
    return;
  }
  const fcl::Contactd& contact = collision_result.getContact(0);
  out.distance = -contact.penetration_depth + link.inflation;
  out.normal = -contact.normal;  // FCL's points from the link into the obstacle
  out.on_link = closest_point_on_segment(link.start, link.end, contact.pos);
  out.on_obstacle = contact.pos;
}

void track_minimum(DistanceTable& table, int link, int obstacle) {
  const double distance = table.at(link, obstacle).distance;
  if (distance < table.min_distance) {
    table.min_distance = distance;
    table.min_link = link;
    table.min_obstacle = obstacle;
  }
}

}  // namespace

// --- DistanceTable -----------------------------------------------------------------

void DistanceTable::resize(int link_count, int obstacle_count) {
  links = link_count;
  obstacles = obstacle_count;
  pairs.resize(static_cast<size_t>(link_count) * static_cast<size_t>(obstacle_count));
  min_distance = kInfinity;
  min_link = min_obstacle = -1;
}

int DistanceTable::nearest_obstacle(int link) const {
  int nearest = -1;
  double nearest_distance = kInfinity;
  for (int o = 0; o < obstacles; ++o) {
    if (nearest < 0 || at(link, o).distance < nearest_distance) {
      nearest = o;
      nearest_distance = at(link, o).distance;
    }
  }
  return nearest;
}

// --- CollisionWorld ------------------------------------------------------------------

// One mesh link against one obstacle: FCL BVH distance for boxes and
// polygon prisms; spheres and points by the nearest triangle (FCL 0.7.0's
// mesh–sphere distance reported contact at every pose here, with either GJK
// solver); walls by the lowest vertex.
void mesh_obstacle(const MeshBvh& bvh, const TriangleMesh& mesh, const fcl::Transform3d& link_pose,
                   const ObstacleGeometry& g, const FclObstacle& shapes, LinkObstacleDistance& out) {
  if (g.shape == ShapeKind::wall) {  // the half-space's distance is its lowest vertex's
    out.distance = kInfinity;
    const Vector3d normal = g.rotation * g.normal;
    for (const Vector3d& v : mesh.vertices) {
      const Vector3d w = link_pose * v;
      const double h = normal.dot(w - g.position);
      if (h < out.distance) {
        out.distance = h;
        out.on_link = w;
      }
    }
    out.normal = normal;
    out.on_obstacle = out.on_link - out.distance * normal;
    return;
  }
  if (g.shape == ShapeKind::sphere || g.shape == ShapeKind::point) {
    // nearest point of the mesh to the centre, in the link's frame; a centre
    // inside the mesh is not detected (the surface distance is reported)
    const Vector3d centre = link_pose.inverse() * g.position;
    double best = kInfinity;
    Vector3d nearest = Vector3d::Zero();
    for (const Eigen::Vector3i& t : mesh.triangles) {
      const Vector3d p = closest_on_triangle(centre, mesh.vertices[size_t(t[0])], mesh.vertices[size_t(t[1])],
                                             mesh.vertices[size_t(t[2])]);
      const double d2 = (p - centre).squaredNorm();
      if (d2 < best) {
        best = d2;
        nearest = p;
      }
    }
    const double radius = g.shape == ShapeKind::sphere ? g.radius : 0.0;
    const double to_centre = std::sqrt(best);
    out.on_link = link_pose * nearest;
    out.normal = to_centre > 0 ? Vector3d((out.on_link - g.position) / to_centre) : Vector3d::UnitZ();
    out.on_obstacle = g.position + radius * out.normal;
    out.distance = to_centre - radius;
    return;
  }
  fcl::Transform3d obstacle_pose = fcl::Transform3d::Identity();
  obstacle_pose.linear() = g.rotation;
  obstacle_pose.translation() = g.position;
  out.distance = kInfinity;
  for (const auto& part : shapes.parts) {
    // FCL's own GJK (GST_INDEP): with libccd's, a mesh against a sphere
    // reported contact at every pose here (FCL 0.7.0)
    fcl::DistanceRequestd request(true, false, 0.0, 0.0, 1e-10, fcl::GST_INDEP);
    fcl::DistanceResultd result;
    fcl::distance(&bvh, link_pose, part.get(), obstacle_pose, request, result);
    double d = result.min_distance;
    if (d >= out.distance) continue;
    out.on_link = result.nearest_points[0];
    out.on_obstacle = result.nearest_points[1];
    if (d <= 0) {  // touching or penetrating: no depth, nor points, from FCL's mesh distance
      d = -kMeshContact;
      out.on_link = link_pose.translation();
      out.on_obstacle = g.position;
      const Vector3d away = link_pose.translation() - g.position;
      out.normal = away.norm() > 0 ? Vector3d(away.normalized()) : Vector3d::UnitZ();
    } else {
      out.normal = (out.on_link - out.on_obstacle) / d;
    }
    out.distance = d;
  }
}

struct CollisionWorld::Impl {
  std::vector<double> link_radii;
  // mesh links: a BVH per link (null for capsules), posed by joint_frames[last_joint]
  std::vector<std::shared_ptr<MeshBvh>> link_bvh;
  std::vector<std::shared_ptr<const TriangleMesh>> link_mesh;
  std::vector<int> last_joint;
  std::vector<ObstacleGeometry> obstacles;
  // reference path
  std::vector<std::shared_ptr<fcl::Capsuled>> fcl_links;
  std::vector<FclObstacle> fcl_obstacles;

  void reshape(const Scene& scene) {
    std::vector<ObstacleGeometry> previous = std::move(obstacles);
    obstacles.clear();
    fcl_obstacles.clear();
    for (const Obstacle& o : scene.obstacles) {
      obstacles.push_back(build_geometry(o));
      ObstacleGeometry& g = obstacles.back();
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
      fcl_obstacles.push_back(build_fcl(o, obstacles.back()));
    }
  }

  void read_poses(const Scene& scene) {
    for (size_t i = 0; i < obstacles.size(); ++i) {
      obstacles[i].rotation = scene.obstacles[i].rotation;
      obstacles[i].position = scene.obstacles[i].position;
    }
  }
};

CollisionWorld::CollisionWorld(const Model& model, const Scene& scene)
    : impl_(std::make_unique<Impl>()) {
  for (const Link& link : model.links) {
    impl_->link_radii.push_back(link.radius);
    impl_->link_mesh.push_back(link.mesh);
    impl_->link_bvh.push_back(link.mesh ? make_bvh(*link.mesh) : nullptr);
    impl_->last_joint.push_back(link.last_joint);
    impl_->fcl_links.push_back(std::make_shared<fcl::Capsuled>(link.radius, 0.0));
  }
  sync(scene, true);
}

CollisionWorld::~CollisionWorld() = default;

void CollisionWorld::sync(const Scene& scene, bool reshape) {
  // a changed obstacle count means new geometry, whatever the caller said
  if (reshape || scene.obstacles.size() != impl_->obstacles.size()) impl_->reshape(scene);
  impl_->read_poses(scene);
}

void CollisionWorld::compute(const KinematicsData& kin, DistanceTable& out) {
  const int link_count = static_cast<int>(impl_->link_radii.size());
  const int obstacle_count = static_cast<int>(impl_->obstacles.size());
  out.resize(link_count, obstacle_count);
  for (int l = 0; l < link_count; ++l) {
    if (impl_->link_bvh[l]) {
      mesh_link(kin, l, out);
      continue;
    }
    const Vector3d a = kin.link_start.col(l), b = kin.link_end.col(l);
    for (int o = 0; o < obstacle_count; ++o) {
      LinkObstacleDistance& pair = out.at(l, o);
      segment_obstacle(impl_->obstacles[o], a, b, pair);
      pair.distance -= impl_->link_radii[l];  // capsule = segment grown by its radius
      track_minimum(out, l, o);
    }
  }
}

void CollisionWorld::compute_with_fcl(const KinematicsData& kin, DistanceTable& out) {
  const int link_count = static_cast<int>(impl_->link_radii.size());
  const int obstacle_count = static_cast<int>(impl_->obstacles.size());
  out.resize(link_count, obstacle_count);
  for (int l = 0; l < link_count; ++l) {
    if (impl_->link_bvh[l]) {
      mesh_link(kin, l, out);
      continue;
    }
    const Vector3d a = kin.link_start.col(l), b = kin.link_end.col(l);
    const double radius = impl_->link_radii[l];
    // FCL's GJK stops early on a segment (radius ~0) against a box and can be
    // 30% off: give such links 1 mm and take it back from the distances
    const double inflation = std::max(0.0, kFclMinRadius - radius);
    fcl::Capsuled& capsule = *impl_->fcl_links[l];
    capsule.radius = radius + inflation;
    capsule.lz = (b - a).norm();
    capsule.computeLocalAABB();
    const FclLink link{&capsule, capsule_pose(a, b), a, b, inflation};
    for (int o = 0; o < obstacle_count; ++o) {
      const ObstacleGeometry& g = impl_->obstacles[o];
      LinkObstacleDistance& pair = out.at(l, o);
      if (g.shape == ShapeKind::wall) {  // analytic, as in compute()
        segment_obstacle(g, a, b, pair);
        pair.distance -= radius;
      } else {
        fcl::Transform3d obstacle_pose = fcl::Transform3d::Identity();
        obstacle_pose.linear() = g.rotation;
        obstacle_pose.translation() = g.position;
        pair.distance = kInfinity;
        LinkObstacleDistance part_result;
        for (const auto& part : impl_->fcl_obstacles[o].parts) {
          fcl_pair(link, *part, obstacle_pose, part_result);
          if (part_result.distance < pair.distance) pair = part_result;
        }
      }
      track_minimum(out, l, o);
    }
  }
}

void CollisionWorld::mesh_link(const KinematicsData& kin, int link, DistanceTable& out) {
  const fcl::Transform3d pose = kin.joint_frames[size_t(impl_->last_joint[size_t(link)])];
  for (int o = 0; o < out.obstacles; ++o) {
    mesh_obstacle(*impl_->link_bvh[size_t(link)], *impl_->link_mesh[size_t(link)], pose, impl_->obstacles[size_t(o)],
                  impl_->fcl_obstacles[size_t(o)], out.at(link, o));
    track_minimum(out, link, o);
  }
}

}  // namespace rrlab
