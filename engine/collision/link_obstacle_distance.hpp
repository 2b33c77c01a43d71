// One link–obstacle distance: what every pair function fills in, and the
// rows of CollisionWorld's DistanceTable (collision_world.hpp).
#pragma once

#include <Eigen/Core>

namespace rrlab {

struct LinkObstacleDistance {
  double distance = 0;  // signed: < 0 is penetration depth
  Eigen::Vector3d on_link = Eigen::Vector3d::Zero();      // nearest point on the link's axis segment
  Eigen::Vector3d on_obstacle = Eigen::Vector3d::Zero();  // nearest point on the obstacle surface
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();       // unit, obstacle -> link: moving on_link along it increases distance
};

}  // namespace rrlab
