// The planar obstacle distances (the multi_preview GA's potential) against
// the collision world's 3D routines: the same signed distance for segments
// in z = 0, separated and overlapping, for every obstacle kind they accept.
#include <rrlab/collision/planar_obstacles.hpp>

#include <gtest/gtest.h>

#include <random>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/methods/multi_preview_avoidance.hpp>

#include "engine/collision/collision_test_support.hpp"

namespace rrlab {
namespace {

using collision_testing::scene_of;
using Eigen::Vector2d;
using Eigen::Vector3d;

Obstacle shaped(ShapeKind shape, const Vector3d& position, const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  Obstacle o;
  o.id = "o" + std::to_string(int(shape));
  o.shape = shape;
  o.position = o.position0 = position;
  o.rotation = rotation;
  return o;
}

Eigen::Matrix3d about_z(double angle) { return Eigen::AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix(); }

// An L-shaped (non-convex) polygon, a box turned about z, a thin box whose
// caps are nearer than its sides, a sphere off the plane and a point.
Scene mixed_scene() {
  Obstacle l = shaped(ShapeKind::polygon, {0.3, -0.2, 0.1}, about_z(0.4));
  l.points = {{0, 0}, {0.6, 0}, {0.6, 0.2}, {0.2, 0.2}, {0.2, 0.7}, {0, 0.7}};
  l.z_min = -0.5, l.z_max = 0.5;
  Obstacle box = shaped(ShapeKind::box, {-0.5, 0.4, 0}, about_z(-1.1));
  box.size = {0.3, 0.5, 2.0};
  Obstacle slab = shaped(ShapeKind::box, {0.1, 0.9, 0.02});
  slab.size = {0.8, 0.6, 0.1};  // z from −0.03 to 0.07: its caps are 3 cm from the plane
  Obstacle ball = shaped(ShapeKind::sphere, {-0.2, -0.6, 0.1});
  ball.radius = 0.25;
  Obstacle point = shaped(ShapeKind::point, {0.9, 0.5, 0});
  return scene_of({l, box, slab, ball, point});
}

TEST(PlanarObstacles, SignedDistancesMatchTheCollisionWorld) {
  const Scene scene = mixed_scene();
  PlanarObstacles planar;
  ASSERT_TRUE(planar.build(scene));
  ASSERT_TRUE(planar.place(scene, 0.0));
  // one-link models give the collision world the same segment
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.2, 1.4);
  int overlapping = 0, pairs = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vector2d a(coordinate(rng), coordinate(rng)), b(coordinate(rng), coordinate(rng));
    const Vector2d d = b - a;
    Model model = make_planar({{d.norm(), 0.0}}, a);
    KinematicsData kin(model);
    forward_kinematics(model, Eigen::VectorXd::Constant(1, std::atan2(d.y(), d.x())), kin);
    CollisionWorld world(model, scene);
    DistanceTable table;
    world.compute(kin, table);
    const Vector2d start = kin.link_start.col(0).head<2>(), end = kin.link_end.col(0).head<2>();
    for (int k = 0; k < int(scene.obstacles.size()); ++k, ++pairs) {
      const double expected = table.at(0, k).distance;
      overlapping += expected < 0;
      EXPECT_NEAR(planar.segment_distance(k, start, end), expected, 1e-12)
          << "obstacle " << k << " segment " << a.transpose() << " → " << b.transpose();
    }
  }
  EXPECT_GT(overlapping, pairs / 20) << "the trials must also cover overlapping segments";
}

TEST(PlanarObstacles, BandSumIsTheCollisionWorldsPotential) {
  const Scene scene = mixed_scene();
  PlanarObstacles planar;
  ASSERT_TRUE(planar.build(scene));
  ASSERT_TRUE(planar.place(scene, 0.0));
  const Model model = make_planar({{0.5, 0.03}, {0.4, 0.02}, {0.35, 0.05}, {0.3, 0.0}}, {0.05, -0.1});
  KinematicsData kin(model);
  CollisionWorld world(model, scene);
  DistanceTable table;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::vector<double> radii;
  for (const Link& link : model.links) radii.push_back(link.radius);
  int touching = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::VectorXd q(4);
    for (int j = 0; j < 4; ++j) q[j] = angle(rng);
    forward_kinematics(model, q, kin);
    std::vector<Vector2d> joints{kin.link_start.col(0).head<2>()};
    for (int l = 0; l < 4; ++l) joints.push_back(kin.link_end.col(l).head<2>());
    for (double width : {0.05, 0.3}) {
      world.compute_near(kin, table, width);
      const double expected = obstacle_potential(table, width, 1.0);
      touching += expected < 0;
      EXPECT_NEAR(-planar.band_sum(joints, radii, width), expected, 1e-10) << trial;
    }
  }
  EXPECT_GT(touching, 50);
}

TEST(PlanarObstacles, MovesObstaclesAheadAndRefusesWhatIsNotPlanar) {
  Obstacle moving = shaped(ShapeKind::sphere, {1.0, 0, 0});
  moving.radius = 0.1;
  moving.velocity = {-0.5, 0, 0};
  const Scene scene = scene_of({moving});
  PlanarObstacles planar;
  ASSERT_TRUE(planar.build(scene));
  ASSERT_TRUE(planar.place(scene, 1.0));  // at x = 0.5 a second later
  EXPECT_NEAR(planar.segment_distance(0, {0, 0}, {0.3, 0}), 0.1, 1e-15);

  Obstacle wall = shaped(ShapeKind::wall, {0, 1, 0});
  EXPECT_FALSE(planar.build(scene_of({wall})));
  Obstacle tilted = shaped(ShapeKind::box, {0, 1, 0}, Eigen::AngleAxisd(0.2, Vector3d::UnitX()).toRotationMatrix());
  tilted.size = {1, 1, 1};
  ASSERT_TRUE(planar.build(scene_of({tilted})));
  EXPECT_FALSE(planar.place(scene_of({tilted}), 0.0));
  Obstacle above = shaped(ShapeKind::box, {0, 1, 2.0});  // z from 1.5 to 2.5: the plane misses it
  above.size = {1, 1, 1};
  ASSERT_TRUE(planar.build(scene_of({above})));
  EXPECT_FALSE(planar.place(scene_of({above}), 0.0));
}

}  // namespace
}  // namespace rrlab
