// Closest points of segments, points and triangles against brute force:
// golden-section search over one segment's parameter (the distance to a
// convex set is convex along a segment) with the test's own projections.
#include <rrlab/collision/segment_geometry.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace rrlab::collision {
namespace {

using Eigen::Vector3d;

// The test's own projection of p onto segment a-b.
Vector3d projected_on_segment(const Vector3d& a, const Vector3d& b, const Vector3d& p) {
  const Vector3d d = b - a;
  if (d.squaredNorm() == 0) return a;
  return a + std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) * d;
}

// min over s in [0, 1] of f(s), f convex: golden-section search.
template <typename F>
double golden_minimum(F f) {
  double left = 0, right = 1;
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i) {
    const double m1 = right - ratio * (right - left), m2 = left + ratio * (right - left);
    if (f(m1) < f(m2)) right = m2; else left = m1;
  }
  return std::min({f(0.5 * (left + right)), f(0.0), f(1.0)});
}

double brute_segments_distance(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2, const Vector3d& q2) {
  return golden_minimum([&](double s) {
    const Vector3d x = p1 + s * (q1 - p1);
    return (x - projected_on_segment(p2, q2, x)).norm();
  });
}

// Whether x lies on segment a-b (within tol).
bool on_segment(const Vector3d& a, const Vector3d& b, const Vector3d& x, double tol = 1e-12) {
  return (x - projected_on_segment(a, b, x)).norm() <= tol;
}

void expect_segments(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2, const Vector3d& q2,
                     double distance) {
  Vector3d c1, c2;
  closest_points_segments(p1, q1, p2, q2, c1, c2);
  EXPECT_NEAR((c1 - c2).norm(), distance, 1e-12);
  EXPECT_TRUE(on_segment(p1, q1, c1)) << c1.transpose();
  EXPECT_TRUE(on_segment(p2, q2, c2)) << c2.transpose();
  EXPECT_NEAR(brute_segments_distance(p1, q1, p2, q2), distance, 1e-9);
}

TEST(SegmentGeometry, CrossingSegments) {
  // meeting at the origin, and the same pair one apart in z
  expect_segments({-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, 0.0);
  expect_segments({-1, 0, 0}, {1, 0, 0}, {0, -1, 1}, {0, 1, 1}, 1.0);
  Vector3d c1, c2;
  closest_points_segments({-1, 0, 0}, {1, 0, 0}, {0, -1, 1}, {0, 1, 1}, c1, c2);
  EXPECT_NEAR(c1.norm(), 0.0, 1e-15);
  EXPECT_NEAR((c2 - Vector3d(0, 0, 1)).norm(), 0.0, 1e-15);
  // skew, the nearest pair at end points: (1, 0, 0) and (2, 0, 1)
  expect_segments({0, 0, 0}, {1, 0, 0}, {2, 0, 1}, {2, 3, 1}, std::sqrt(2.0));
}

TEST(SegmentGeometry, ParallelSegments) {
  // overlapping side by side: any pair across the overlap is nearest
  expect_segments({0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {3, 1, 0}, 1.0);
  // anti-parallel, overlapping
  expect_segments({0, 0, 0}, {2, 0, 0}, {3, 0, 2}, {1, 0, 2}, 2.0);
  // collinear and apart: the facing end points
  Vector3d c1, c2;
  closest_points_segments({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, c1, c2);
  EXPECT_NEAR((c1 - Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((c2 - Vector3d(2, 0, 0)).norm(), 0.0, 1e-15);
  // parallel, not overlapping: end to end diagonally
  expect_segments({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 0}, std::sqrt(2.0));
}

TEST(SegmentGeometry, DegenerateSegments) {
  Vector3d c1, c2;
  // two points
  closest_points_segments({1, 2, 3}, {1, 2, 3}, {1, 2, 5}, {1, 2, 5}, c1, c2);
  EXPECT_EQ(c1, Vector3d(1, 2, 3));
  EXPECT_EQ(c2, Vector3d(1, 2, 5));
  // a point against a segment, either way round
  expect_segments({0.5, 1, 0}, {0.5, 1, 0}, {0, 0, 0}, {1, 0, 0}, 1.0);
  expect_segments({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {2, 1, 0}, std::sqrt(2.0));
  closest_points_segments({0, 0, 0}, {1, 0, 0}, {0.25, -3, 0}, {0.25, -3, 0}, c1, c2);
  EXPECT_NEAR((c1 - Vector3d(0.25, 0, 0)).norm(), 0.0, 1e-15);
  // a zero-length segment's closest point is itself
  EXPECT_EQ(closest_point_on_segment({1, 1, 1}, {1, 1, 1}, {5, 0, 0}), Vector3d(1, 1, 1));
}

TEST(SegmentGeometry, RandomSegmentsAgainstBruteForce) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  auto random_point = [&] { return Vector3d(coordinate(rng), coordinate(rng), coordinate(rng)); };
  for (int trial = 0; trial < 500; ++trial) {
    const Vector3d p1 = random_point(), q1 = random_point(), p2 = random_point();
    // every fourth pair nearly parallel
    const Vector3d q2 = trial % 4 ? random_point() : Vector3d(p2 + (q1 - p1) * 0.7 + 1e-7 * random_point());
    Vector3d c1, c2;
    closest_points_segments(p1, q1, p2, q2, c1, c2);
    EXPECT_TRUE(on_segment(p1, q1, c1, 1e-12)) << trial;
    EXPECT_TRUE(on_segment(p2, q2, c2, 1e-12)) << trial;
    // points on both segments: never nearer than the minimum; within 1e-9 of
    // it, but for nearly parallel segments (here 1e-7 rad apart), where the
    // parameter s loses digits (a*e - b*b cancels) and the pair found is up to
    // the angle times the segment length farther (measured: 1.1e-8 m)
    const double brute = brute_segments_distance(p1, q1, p2, q2);
    EXPECT_GE((c1 - c2).norm(), brute - 1e-12) << trial;
    EXPECT_LE((c1 - c2).norm(), brute + (trial % 4 ? 1e-9 : 1e-7)) << trial;
    // a point's nearest point on a segment
    const Vector3d p = random_point();
    const double brute_point = golden_minimum([&](double s) { return (p1 + s * (q1 - p1) - p).norm(); });
    const Vector3d x = closest_point_on_segment(p1, q1, p);
    EXPECT_TRUE(on_segment(p1, q1, x)) << trial;
    EXPECT_NEAR((x - p).norm(), brute_point, 1e-9) << trial;
  }
}

TEST(SegmentGeometry, AnyPerpendicularIsAUnitNormalInThePlane) {
  for (const Vector3d& d : {Vector3d(1, 0, 0), Vector3d(0.3, -2, 0), Vector3d(1, 2, 3), Vector3d(0, 0, 2)}) {
    const Vector3d n = any_perpendicular(d);
    EXPECT_NEAR(n.norm(), 1.0, 1e-15);
    EXPECT_NEAR(n.dot(d), 0.0, 1e-15);
  }
  // a planar direction keeps planar arms planar
  EXPECT_EQ(any_perpendicular(Vector3d(0.3, -2, 0)).z(), 0.0);
  EXPECT_EQ(any_perpendicular(Vector3d::Zero()), Vector3d::UnitY());
}

// The nearest point of a triangle by its own means: the projection on the
// plane when inside (barycentric), else the nearest of the three edges.
Vector3d brute_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a).normalized();
  const Vector3d q = p - n.dot(p - a) * n;
  const double area = (b - a).cross(c - a).dot(n);
  const double u = (c - b).cross(q - b).dot(n) / area, v = (a - c).cross(q - c).dot(n) / area;
  if (u >= 0 && v >= 0 && u + v <= 1) return q;
  Vector3d best = projected_on_segment(a, b, p);
  for (const Vector3d& x : {projected_on_segment(b, c, p), projected_on_segment(c, a, p)})
    if ((x - p).norm() < (best - p).norm()) best = x;
  return best;
}

TEST(SegmentGeometry, ClosestOnTriangleAgainstBruteForce) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  auto random_point = [&] { return Vector3d(coordinate(rng), coordinate(rng), coordinate(rng)); };
  for (int trial = 0; trial < 1000; ++trial) {
    const Vector3d a = random_point(), b = random_point(), c = random_point(), p = 1.5 * random_point();
    const Vector3d x = closest_on_triangle(p, a, b, c);
    const Vector3d reference = brute_on_triangle(p, a, b, c);
    EXPECT_NEAR((x - p).norm(), (reference - p).norm(), 1e-9) << trial;
    EXPECT_NEAR((x - reference).norm(), 0.0, 1e-6) << trial;
  }
  // the vertex, edge and face regions of a right triangle in z = 0
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(closest_on_triangle({-1, -1, 0}, a, b, c), a);
  EXPECT_NEAR((closest_on_triangle({0.5, -1, 2}, a, b, c) - Vector3d(0.5, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((closest_on_triangle({0.2, 0.3, -4}, a, b, c) - Vector3d(0.2, 0.3, 0)).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace rrlab::collision
