// Triangle meshes: mesh obstacles against capsule links (segment_mesh) and
// mesh links against walls and spheres. With fcl_pairs.cpp, the only file
// that includes FCL: the tree is FCL's BVHModel (OBBRSS), descended here by
// hand (fcl::distance on a capsule allocates while bounding the capsule).
#include <rrlab/collision/mesh_distance.hpp>

#include <fcl/fcl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include <rrlab/collision/segment_geometry.hpp>

namespace rrlab::collision {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

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

}  // namespace

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

// A mesh link against a wall: the half-space's distance is its lowest vertex's.
void mesh_wall(const TriangleMesh& mesh, const Eigen::Isometry3d& link_pose, const Vector3d& point,
               const Vector3d& normal, LinkObstacleDistance& out) {
  out.distance = kInfinity;
  for (const Vector3d& v : mesh.vertices) {
    const Vector3d w = link_pose * v;
    const double h = normal.dot(w - point);
    if (h < out.distance) {
      out.distance = h;
      out.on_link = w;
    }
  }
  out.normal = normal;
  out.on_obstacle = out.on_link - out.distance * normal;
}

// A mesh link against a sphere or point: by the nearest triangle (FCL 0.7.0's
// mesh–sphere distance reported contact at every pose here, with either GJK
// solver).
void mesh_sphere(const TriangleMesh& mesh, const Eigen::Isometry3d& link_pose, const Vector3d& centre_world,
                 double radius, LinkObstacleDistance& out) {
  // nearest point of the mesh to the centre, in the link's frame; a centre
  // inside the mesh is not detected (the surface distance is reported)
  const Vector3d centre = link_pose.inverse() * centre_world;
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
  const double to_centre = std::sqrt(best);
  out.on_link = link_pose * nearest;
  out.normal = to_centre > 0 ? Vector3d((out.on_link - centre_world) / to_centre) : Vector3d::UnitZ();
  out.on_obstacle = centre_world + radius * out.normal;
  out.distance = to_centre - radius;
}

}  // namespace rrlab::collision
