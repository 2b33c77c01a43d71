// Convex primitives: the prism and box layout, the segment–box distance
// against sampling (golden-section search along the segment), the sign
// inside and outside, and the penetration depth against translations
// sampled over directions; spheres and walls in closed form.
#include <rrlab/collision/convex_polytope.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/collision/collision_test_support.hpp"

namespace rrlab::collision {
namespace {

using collision_testing::reference_box_distance;
using Eigen::Vector3d;

TEST(ConvexPolytope, PrismAndBoxLayout) {
  const ConvexPolytope triangle = make_prism({{0, 0}, {1, 0}, {0, 1}}, -0.5, 2.0);
  EXPECT_EQ(triangle.vertices.size(), 6u);
  EXPECT_EQ(triangle.faces.size(), 5u);  // bottom, top, three sides
  EXPECT_EQ(triangle.edges.size(), 9u);
  EXPECT_EQ(triangle.edge_axes.size(), 4u);  // three in the plane and z
  // bottom vertices first, then the top ones (make_fcl_prism relies on it)
  EXPECT_EQ(triangle.vertices[1], Vector3d(1, 0, -0.5));
  EXPECT_EQ(triangle.vertices[4], Vector3d(1, 0, 2.0));
  const ConvexPolytope box = make_box(Vector3d(2, 4, 6));
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(box.faces.size(), 6u);
  EXPECT_EQ(box.edges.size(), 12u);
  EXPECT_EQ(box.edge_axes.size(), 3u);
  // outward unit normals: every vertex on or inside every face, the centre strictly inside
  for (const ConvexPolytope* poly : {&triangle, &box}) {
    for (const Face& face : poly->faces) {
      EXPECT_NEAR(face.normal.norm(), 1.0, 1e-15);
      for (const Vector3d& v : poly->vertices) EXPECT_LE(face.normal.dot(v), face.offset + 1e-12);
    }
  }
  for (const Face& face : box.faces) EXPECT_LT(face.normal.dot(Vector3d::Zero()), face.offset);
}

constexpr double kBoxTolerance = 1e-9;

TEST(ConvexPolytope, SegmentBoxDistanceAgainstSampling) {
  const Vector3d size(0.6, 0.4, 0.8), lo = -size / 2, hi = size / 2;
  const ConvexPolytope box = make_box(size);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  int apart = 0, penetrating = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Vector3d a(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vector3d b = trial % 5 ? Vector3d(coordinate(rng), coordinate(rng), coordinate(rng)) : a;  // some points
    LinkObstacleDistance out;
    segment_polytope(box, a, b, out);
    EXPECT_NEAR(out.normal.norm(), 1.0, 1e-12) << trial;
    Vector3d on_link;
    const double reference = reference_box_distance(a, b, lo, hi, on_link);
    if (reference > 1e-6) {
      EXPECT_NEAR(out.distance, reference, kBoxTolerance) << trial;
      EXPECT_NEAR((out.on_link - out.on_obstacle).norm(), out.distance, kBoxTolerance) << trial;
      EXPECT_NEAR((out.on_link - out.on_obstacle - out.distance * out.normal).norm(), 0.0, 1e-9) << trial;
      ++apart;
    } else if (reference < 1e-9) {
      EXPECT_LE(out.distance, 1e-9) << trial;  // the segment meets the box
      ++penetrating;
    }
  }
  EXPECT_GT(apart, 500);
  EXPECT_GT(penetrating, 100);
}

TEST(ConvexPolytope, FacePlaneBoundNeverExceedsTheSignedDistance) {
  // separated or intersecting, the bound is ≤ the distance (culling relies on it), and tight
  // when a face is the nearest feature
  const ConvexPolytope prism = make_prism({{0, 0}, {1, 0}, {1.3, 0.8}, {0.2, 1.1}}, -0.5, 0.5);
  std::mt19937 rng(47);
  std::uniform_real_distribution<double> coordinate(-2, 3);
  int tight = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vector3d a(coordinate(rng), coordinate(rng), coordinate(rng) - 0.5);
    const Vector3d b(coordinate(rng), coordinate(rng), coordinate(rng) - 0.5);
    LinkObstacleDistance out;
    segment_polytope(prism, a, b, out);
    const double bound = separating_face_bound(prism, a, b);
    EXPECT_LE(bound, out.distance + 1e-12) << trial;
    tight += std::abs(bound - out.distance) < 1e-12;
  }
  EXPECT_GT(tight, 50);  // 91 of 2000 with this seed
}

TEST(ConvexPolytope, SignInsideAndOutside) {
  const ConvexPolytope box = make_box(Vector3d(2, 2, 2));
  LinkObstacleDistance out;
  // wholly inside: negative, as deep as the way out through the nearest face (z = 1)
  segment_polytope(box, Vector3d(-0.5, 0.2, 0.7), Vector3d(0.5, 0.2, 0.7), out);
  EXPECT_NEAR(out.distance, -0.3, 1e-12);
  EXPECT_NEAR((out.normal - Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  // outside: positive
  segment_polytope(box, Vector3d(-0.5, 0.2, 1.5), Vector3d(0.5, 0.2, 1.5), out);
  EXPECT_NEAR(out.distance, 0.5, 1e-12);
  EXPECT_NEAR((out.normal - Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  // on the surface: zero, with the face's normal
  segment_polytope(box, Vector3d(-0.5, 0.2, 1.0), Vector3d(0.5, 0.2, 1.0), out);
  EXPECT_NEAR(out.distance, 0.0, 1e-12);
  EXPECT_NEAR((out.normal - Vector3d::UnitZ()).norm(), 0.0, 1e-12);
}

// The depth is a translation that separates, and no sampled direction
// separates with less: for each direction u, the least t for which the
// segment moved by t·u clears the box (bisection on the sampled distance).
TEST(ConvexPolytope, PenetrationDepthIsTheLeastTranslation) {
  const Vector3d size(0.6, 0.4, 0.8), lo = -size / 2, hi = size / 2;
  const ConvexPolytope box = make_box(size);
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> coordinate(-0.5, 0.5);
  std::normal_distribution<double> gaussian;
  std::vector<Vector3d> directions;
  for (int i = 0; i < 100; ++i)
    directions.push_back(Vector3d(gaussian(rng), gaussian(rng), gaussian(rng)).normalized());
  Vector3d ignored;
  auto clear_after = [&](const Vector3d& a, const Vector3d& b, const Vector3d& shift) {
    return reference_box_distance(a + shift, b + shift, lo, hi, ignored) > 1e-10;
  };
  int checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Vector3d a(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vector3d b(coordinate(rng), coordinate(rng), coordinate(rng));
    LinkObstacleDistance out;
    segment_polytope(box, a, b, out);
    if (out.distance > -1e-3) continue;
    const double depth = -out.distance;
    // moved by the depth along the normal, the segment just touches
    EXPECT_LT(reference_box_distance(a + depth * out.normal, b + depth * out.normal, lo, hi, ignored), 1e-9) << trial;
    EXPECT_TRUE(clear_after(a, b, (depth + 1e-6) * out.normal)) << trial;
    for (const Vector3d& u : directions) {
      double inside = 0, outside = 3;  // 3 m clears the box from anywhere here
      for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (inside + outside);
        (clear_after(a, b, mid * u) ? outside : inside) = mid;
      }
      EXPECT_LE(depth, outside + 1e-9) << trial;
    }
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(ConvexPolytope, SegmentSphere) {
  LinkObstacleDistance out;
  segment_sphere(Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(1, 1, 0), 0.25, out);
  EXPECT_NEAR(out.distance, 0.75, 1e-15);
  EXPECT_EQ(out.on_link, Vector3d(1, 0, 0));
  EXPECT_NEAR((out.on_obstacle - Vector3d(1, 0.75, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((out.normal + Vector3d::UnitY()).norm(), 0.0, 1e-15);
  // the centre on the axis: as deep as the radius, pushed out across the segment
  segment_sphere(Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(1, 0, 0), 0.25, out);
  EXPECT_NEAR(out.distance, -0.25, 1e-15);
  EXPECT_NEAR(out.normal.dot(Vector3d::UnitX()), 0.0, 1e-15);
  EXPECT_NEAR(out.normal.norm(), 1.0, 1e-15);
}

TEST(ConvexPolytope, SegmentWall) {
  LinkObstacleDistance out;
  // the floor z = 0 (free side +z): the lower end point
  segment_wall(Vector3d(0, 0, 1), Vector3d(1, 0, 0.5), Vector3d(5, 5, 0), Vector3d::UnitZ(), out);
  EXPECT_NEAR(out.distance, 0.5, 1e-15);
  EXPECT_EQ(out.on_link, Vector3d(1, 0, 0.5));
  EXPECT_NEAR((out.on_obstacle - Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
  // parallel: the middle; below the plane: negative
  segment_wall(Vector3d(0, 0, -0.2), Vector3d(2, 0, -0.2), Vector3d::Zero(), Vector3d::UnitZ(), out);
  EXPECT_NEAR(out.distance, -0.2, 1e-15);
  EXPECT_EQ(out.on_link, Vector3d(1, 0, -0.2));
  EXPECT_EQ(out.normal, Vector3d::UnitZ());
}

}  // namespace
}  // namespace rrlab::collision
