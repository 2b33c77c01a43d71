// Helpers shared by the collision tests: a scene of obstacles, and the check
// that a link-obstacle pair's points, normal and distance agree.
#pragma once

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "collision/collision_world.hpp"

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

}  // namespace rrlab::collision_testing
