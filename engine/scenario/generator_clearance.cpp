#include "scenario/generator_clearance.hpp"

#include <limits>

#include "collision/collision_world.hpp"
#include "kinematics/kinematics.hpp"

namespace rrlab {

std::vector<CapsuleSegment> arm_capsules(const Model& model, const Eigen::VectorXd& q) {
  KinematicsData kin(model);
  forward_kinematics(model, q, kin);
  std::vector<CapsuleSegment> capsules;
  for (int l = 0; l < model.link_count(); ++l)
    capsules.push_back({kin.link_start.col(l), kin.link_end.col(l), model.links[l].radius});
  return capsules;
}

std::vector<CapsuleSegment> path_capsules(const std::vector<Eigen::Vector3d>& points, double radius) {
  std::vector<CapsuleSegment> capsules;
  for (size_t i = 1; i < points.size(); ++i) capsules.push_back({points[i - 1], points[i], radius});
  return capsules;
}

double capsules_clearance(const std::vector<CapsuleSegment>& capsules, const Obstacle& obstacle) {
  if (capsules.empty()) return std::numeric_limits<double>::infinity();
  // A stand-in chain with one link per capsule carries the radii; its link
  // segments are then set to the capsules' own, which is all compute() reads.
  std::vector<PlanarLinkSpec> links;
  for (const CapsuleSegment& c : capsules) links.push_back({1.0, c.radius});
  const Model chain = make_planar(links, Eigen::Vector2d::Zero());
  KinematicsData kin(chain);
  for (size_t i = 0; i < capsules.size(); ++i) {
    kin.link_start.col(i) = capsules[i].a;
    kin.link_end.col(i) = capsules[i].b;
  }
  Scene scene;
  scene.obstacles.push_back(obstacle);
  scene.obstacles.back().position = obstacle.position0;
  CollisionWorld world(chain, scene);
  DistanceTable table;
  world.compute(kin, table);
  return table.min_distance;
}

}  // namespace rrlab
