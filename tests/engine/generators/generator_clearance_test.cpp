// Distances between two obstacles (what a perturbation's free gap is made
// of): exact for convex shapes apart, not above 0 when they touch or overlap,
// either way round, and two walls never measured against each other.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include <rrlab/collision/scene.hpp>
#include <rrlab/generators/generator_clearance.hpp>

namespace rrlab {
namespace {

Obstacle box(const Eigen::Vector3d& center, const Eigen::Vector3d& size, double yaw = 0) {
  Obstacle o;
  o.shape = ShapeKind::box;
  o.position0 = o.position = center;
  o.size = size;
  o.rotation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return o;
}

Obstacle sphere(const Eigen::Vector3d& center, double radius) {
  Obstacle o;
  o.shape = radius > 0 ? ShapeKind::sphere : ShapeKind::point;
  o.position0 = o.position = center;
  o.radius = radius;
  return o;
}

Obstacle wall(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  Obstacle o;
  o.shape = ShapeKind::wall;
  o.position0 = o.position = point;
  o.normal = normal;
  return o;
}

Obstacle polygon(const std::vector<Eigen::Vector2d>& points) {
  Obstacle o;
  o.shape = ShapeKind::polygon;
  o.points = points;
  return o;
}

TEST(ObstaclesDistance, ConvexShapesApartAreMeasuredExactlyEitherWayRound) {
  const Obstacle a = box({0, 0, 0}, {1, 1, 1});
  // face to face, 0.3 m apart
  EXPECT_NEAR(obstacles_distance(a, box({1.3, 0, 0}, {1, 1, 1})), 0.3, 1e-12);
  // edge to face: the second box turned 45 degrees, its edge nearest
  const double half_diagonal = std::sqrt(0.5);
  EXPECT_NEAR(obstacles_distance(a, box({1.0 + half_diagonal, 0, 0}, {1, 1, 1}, M_PI / 4)), 0.5, 1e-12);
  // a sphere off a corner, and a point
  const Eigen::Vector3d corner(0.5, 0.5, 0.5);
  const Obstacle ball = sphere(corner + Eigen::Vector3d(1, 1, 1).normalized() * 0.5, 0.2);
  EXPECT_NEAR(obstacles_distance(a, ball), 0.3, 1e-12);
  EXPECT_NEAR(obstacles_distance(ball, a), 0.3, 1e-12);
  EXPECT_NEAR(obstacles_distance(ball, sphere({3, 0, 0}, 0)), (ball.position0 - Eigen::Vector3d(3, 0, 0)).norm() - 0.2, 1e-12);
  // a wall below the box, and below the sphere
  const Obstacle floor = wall({0, 0, -1}, {0, 0, 1});
  EXPECT_NEAR(obstacles_distance(a, floor), 0.5, 1e-12);
  EXPECT_NEAR(obstacles_distance(floor, ball), ball.position0.z() + 1 - 0.2, 1e-12);
}

TEST(ObstaclesDistance, OverlapIsNegativeAndTwoWallsAreNotCompared) {
  const Obstacle a = box({0, 0, 0}, {1, 1, 1});
  EXPECT_LT(obstacles_distance(a, box({0.8, 0.2, 0.1}, {1, 1, 1})), 0);
  // overlapping with every edge on the other's faces, and touching: no gap either
  EXPECT_LE(obstacles_distance(a, box({0.8, 0, 0}, {1, 1, 1})), 0);
  EXPECT_LE(obstacles_distance(a, box({1.0, 0, 0}, {1, 1, 1})), 1e-12);
  // a small sphere inside the box: no edge of the box is near it, its centre is inside
  EXPECT_LT(obstacles_distance(a, sphere({0, 0, 0}, 0.1)), 0);
  EXPECT_TRUE(std::isinf(obstacles_distance(wall({0, 0, 0}, {0, 1, 0}), wall({0, 2, 0}, {0, -1, 0}))));
}

TEST(ObstaclesDistance, APolygonIsMeasuredByItsOutlineNotItsConvexParts) {
  // an L with inner edges y = 1 and x = 1: a sphere in the notch (inside the
  // L's convex hull) is as far as those edges, either way round
  const Obstacle l = polygon({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}});
  EXPECT_NEAR(obstacles_distance(l, sphere({1.6, 1.6, 0}, 0.2)), 0.4, 1e-12);
  EXPECT_NEAR(obstacles_distance(sphere({1.6, 1.6, 0}, 0.2), l), 0.4, 1e-12);
  EXPECT_NEAR(obstacles_distance(l, sphere({2.5, 1.3, 0}, 0.1)), 0.2, 1e-12);
}

}  // namespace
}  // namespace rrlab
