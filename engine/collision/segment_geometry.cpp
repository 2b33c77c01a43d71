// Exact closest points of segments, points and triangles.
#include <rrlab/collision/segment_geometry.hpp>

#include <algorithm>

namespace rrlab::collision {

using Eigen::Vector3d;

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

}  // namespace rrlab::collision
