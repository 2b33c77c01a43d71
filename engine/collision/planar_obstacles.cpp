#include <rrlab/collision/planar_obstacles.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <rrlab/collision/polygon.hpp>

namespace rrlab {

using Eigen::Vector2d;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Squared distance from p to the segment a-b.
double plane_point_segment2(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d d = b - a;
  const double length2 = d.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).squaredNorm();
}

// Squared distance between two segments of the plane that do not cross.
double plane_segment_segment2(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
  return std::min(std::min(plane_point_segment2(a, c, d), plane_point_segment2(b, c, d)),
                  std::min(plane_point_segment2(c, a, b), plane_point_segment2(d, a, b)));
}

bool upright_about_z(const Eigen::Matrix3d& r) {
  return r(2, 2) == 1.0 && r(0, 2) == 0.0 && r(1, 2) == 0.0 && r(2, 0) == 0.0 && r(2, 1) == 0.0;
}

}  // namespace

bool PlanarObstacles::build(const Scene& scene) {
  shapes_.clear();
  for (const Obstacle& o : scene.obstacles) {
    Shape shape;
    switch (o.shape) {
      case ShapeKind::sphere:
      case ShapeKind::point:
        shape.round = true;
        shape.radius = o.shape == ShapeKind::sphere ? o.radius : 0.0;
        break;
      case ShapeKind::polygon:
      case ShapeKind::box: {
        std::vector<Polygon2> parts;
        if (o.shape == ShapeKind::polygon) {
          parts = convex_decomposition(o.points);  // the parts the collision world uses
          shape.z_min = o.z_min, shape.z_max = o.z_max;
        } else {
          const double hx = o.size.x() / 2, hy = o.size.y() / 2;
          parts.push_back({{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}});
          shape.z_min = -o.size.z() / 2, shape.z_max = o.size.z() / 2;
        }
        for (Polygon2& polygon : parts) {
          if (signed_area(polygon) < 0) std::reverse(polygon.begin(), polygon.end());
          Part part;
          part.local = polygon;
          part.vertices = part.normals = polygon;
          part.offsets.assign(polygon.size(), 0.0);
          shape.parts.push_back(std::move(part));
        }
        break;
      }
      default: return false;  // a wall or a mesh: the collision world's
    }
    shapes_.push_back(std::move(shape));
  }
  return true;
}

bool PlanarObstacles::place(const Scene& scene, double ahead) {
  for (size_t k = 0; k < shapes_.size(); ++k) {
    const Obstacle& o = scene.obstacles[k];
    Shape& shape = shapes_[k];
    const Eigen::Vector3d position = o.position + o.velocity * ahead;
    if (shape.round) {
      shape.centre = position;
      continue;
    }
    if (!upright_about_z(o.rotation)) return false;
    const double z0 = -position.z();  // the plane z = 0 in the prism's frame
    shape.cap_depth = std::min(shape.z_max - z0, z0 - shape.z_min);
    if (!(shape.cap_depth > 0)) return false;
    const Eigen::Matrix2d r = o.rotation.topLeftCorner<2, 2>();
    const Vector2d t = position.head<2>();
    for (Part& part : shape.parts) {
      const int count = int(part.local.size());
      for (int i = 0; i < count; ++i) part.vertices[i] = r * part.local[i] + t;
      for (int i = 0; i < count; ++i) {
        // outward normal: right of a counter-clockwise edge (as make_prism)
        const Vector2d edge = part.vertices[(i + 1) % count] - part.vertices[i];
        part.normals[i] = Vector2d(edge.y(), -edge.x()).normalized();
        part.offsets[i] = part.normals[i].dot(part.vertices[i]);
      }
    }
  }
  return true;
}

double PlanarObstacles::part_distance(const Shape& shape, const Part& part, const Vector2d& a,
                                      const Vector2d& b) const {
  const int count = int(part.vertices.size());
  // the segment's stretch inside every side: empty = separated
  const Vector2d d = b - a;
  double t0 = 0, t1 = 1;
  bool inside = true;
  for (int f = 0; f < count && inside; ++f) {
    const double along = part.normals[f].dot(d), room = part.offsets[f] - part.normals[f].dot(a);
    if (along == 0)
      inside = room >= 0;
    else if (along > 0)
      t1 = std::min(t1, room / along);
    else
      t0 = std::max(t0, room / along);
    inside = inside && t0 <= t1;
  }
  if (!inside) {  // separated: the nearest pair of features (no edge crosses the segment)
    double distance2 = kInf;
    for (int i = 0; i < count; ++i)
      distance2 = std::min(distance2, plane_segment_segment2(a, b, part.vertices[i], part.vertices[(i + 1) % count]));
    return std::sqrt(distance2);
  }
  // overlapping: the least depth over the separating axes — the sides, the
  // caps (the 3D routine's horizontal edge axes give the same) and the
  // segment's normal (its vertical edge axes)
  double depth = shape.cap_depth;
  for (int f = 0; f < count; ++f)
    depth = std::min(depth, part.offsets[f] - std::min(part.normals[f].dot(a), part.normals[f].dot(b)));
  if (d.squaredNorm() > 0) {
    const Vector2d m = Vector2d(-d.y(), d.x()).normalized();
    const double s = m.dot(a);
    double lo = kInf, hi = -kInf;
    for (const Vector2d& v : part.vertices) lo = std::min(lo, m.dot(v)), hi = std::max(hi, m.dot(v));
    depth = std::min(depth, std::min(hi - s, s - lo));
  }
  return -depth;
}

// A lower bound of the segment's distance to the part: its distance beyond
// the side plane that separates them best (≤ 0 when none does).
double PlanarObstacles::part_bound(const Part& part, const Vector2d& a, const Vector2d& b) {
  double bound = -kInf;
  for (size_t f = 0; f < part.normals.size(); ++f)
    bound = std::max(bound, std::min(part.normals[f].dot(a), part.normals[f].dot(b)) - part.offsets[f]);
  return bound;
}

double PlanarObstacles::segment_distance(int k, const Vector2d& a, const Vector2d& b, double cutoff) const {
  const Shape& shape = shapes_[size_t(k)];
  if (shape.round) {
    const double z = shape.centre.z();
    return std::sqrt(plane_point_segment2(shape.centre.head<2>(), a, b) + z * z) - shape.radius;
  }
  double distance = kInf;
  for (const Part& part : shape.parts)
    // a part whose sides keep the segment beyond the cutoff, or farther than
    // the nearest so far, cannot be the nearest within the cutoff
    if (part_bound(part, a, b) < std::min(distance, cutoff)) distance = std::min(distance, part_distance(shape, part, a, b));
  return distance;
}

double PlanarObstacles::band_sum(const std::vector<Vector2d>& joints, const std::vector<double>& radii,
                                 double width) const {
  double sum = 0;
  for (size_t l = 0; l + 1 < joints.size(); ++l) {
    const Vector2d& a = joints[l];
    const Vector2d& b = joints[l + 1];
    for (size_t k = 0; k < shapes_.size(); ++k) {
      // a part whose side plane has the whole segment beyond the band needs
      // no exact distance: with every part so, the distance is ∞ (band 0)
      const double band = 1.0 - (segment_distance(int(k), a, b, width + radii[l]) - radii[l]) / width;
      if (band > 0) sum += band * band;
    }
  }
  return sum;
}

}  // namespace rrlab
