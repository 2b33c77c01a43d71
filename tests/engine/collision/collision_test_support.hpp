// Helpers shared by the collision tests: a scene of obstacles, the check
// that a link-obstacle pair's points, normal and distance agree, and an
// independent segment–box distance.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include <rrlab/collision/collision_world.hpp>

namespace rrlab::collision_testing {

inline Scene scene_of(std::vector<Obstacle> obstacles) {
  Scene scene;
  scene.obstacles = std::move(obstacles);
  return scene;
}

// The normal is a unit vector, and the link point sits at the segment distance
// (capsule distance + radius) from the obstacle point along it; at contact the
// points coincide and only the normal is checked.
inline void expect_consistent(const LinkObstacleDistance& pair, double radius) {
  EXPECT_NEAR(pair.normal.norm(), 1.0, 1e-12);
  if (pair.distance + radius <= 1e-9) return;
  const Eigen::Vector3d gap = pair.on_link - pair.on_obstacle;
  EXPECT_NEAR((gap - (pair.distance + radius) * pair.normal).norm(), 0.0, 1e-9)
      << "gap " << gap.transpose() << " normal " << pair.normal.transpose();
}

// Nearest points of a segment and an axis-aligned box by golden-section search
// over the segment (the distance is convex along it): an independent reference.
inline double reference_box_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& lo,
                                     const Eigen::Vector3d& hi, Eigen::Vector3d& on_link) {
  auto distance_at = [&](double t) {
    const Eigen::Vector3d p = a + t * (b - a);
    return (p - p.cwiseMax(lo).cwiseMin(hi)).norm();
  };
  double left = 0, right = 1;
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i) {
    const double m1 = right - ratio * (right - left), m2 = left + ratio * (right - left);
    if (distance_at(m1) < distance_at(m2)) right = m2; else left = m1;
  }
  const double t = 0.5 * (left + right);
  on_link = a + t * (b - a);
  return distance_at(t);
}

}  // namespace rrlab::collision_testing
