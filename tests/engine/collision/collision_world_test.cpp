#include <rrlab/collision/collision_world.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <rrlab/collision/polygon.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/model/model.hpp>

#include "engine/collision/collision_test_support.hpp"

namespace rrlab {
namespace {

using collision_testing::expect_consistent;
using collision_testing::reference_box_distance;
using collision_testing::scene_of;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kExact = 1e-9;   // touching, separated distances, nearest points
constexpr double kDepth = 1e-6;   // penetration depths
const double kSqrt2 = std::sqrt(2.0);

// --- scene and arm helpers ---------------------------------------------------------

Obstacle placed(Obstacle o, const Vector3d& position) {
  o.position0 = o.position = position;
  return o;
}

Obstacle polygon(const std::vector<Vector2d>& points, const Vector3d& position = Vector3d::Zero()) {
  Obstacle o;
  o.id = "polygon";
  o.shape = ShapeKind::polygon;
  o.points = points;
  return placed(o, position);
}

Obstacle box(const Vector3d& centre, const Vector3d& size) {
  Obstacle o;
  o.id = "box";
  o.shape = ShapeKind::box;
  o.size = size;
  return placed(o, centre);
}

Obstacle sphere(const Vector3d& centre, double radius) {
  Obstacle o;
  o.id = "sphere";
  o.shape = ShapeKind::sphere;
  o.radius = radius;
  return placed(o, centre);
}

Obstacle point(const Vector3d& at) {
  Obstacle o;
  o.id = "point";
  o.shape = ShapeKind::point;
  return placed(o, at);
}

Obstacle wall(const Vector3d& on_plane, const Vector3d& normal) {
  Obstacle o;
  o.id = "wall";
  o.shape = ShapeKind::wall;
  o.normal = normal;
  return placed(o, on_plane);
}

Eigen::Matrix3d rotation_z(double angle) {
  return Eigen::AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix();
}

// One planar link from the origin along the angle q (rad).
Model one_link(double length, double radius = 0.0) {
  return make_planar({{length, radius}}, Vector2d::Zero());
}

DistanceTable distances(const Model& model, const VectorXd& q, const Scene& scene) {
  KinematicsData kin(model);
  forward_kinematics(model, q, kin);
  CollisionWorld world(model, scene);
  DistanceTable table;
  world.compute(kin, table);
  return table;
}

DistanceTable one_link_distances(double length, double angle, const Obstacle& obstacle,
                                 double radius = 0.0) {
  return distances(one_link(length, radius), VectorXd::Constant(1, angle), scene_of({obstacle}));
}

Vector3d xy(double x, double y) { return {x, y, 0.0}; }

void expect_pair(const LinkObstacleDistance& pair, double distance, const Vector3d& on_link,
                 const Vector3d& on_obstacle, const Vector3d& normal, double tolerance = kExact) {
  EXPECT_NEAR(pair.distance, distance, tolerance);
  EXPECT_NEAR((pair.on_link - on_link).norm(), 0.0, tolerance) << pair.on_link.transpose();
  EXPECT_NEAR((pair.on_obstacle - on_obstacle).norm(), 0.0, tolerance)
      << pair.on_obstacle.transpose();
  EXPECT_NEAR((pair.normal - normal).norm(), 0.0, tolerance) << pair.normal.transpose();
}

// Unit square [1, 2] x [-0.5, 0.5], extruded over z in [-1, 1].
const std::vector<Vector2d> kSquare{{1, -0.5}, {2, -0.5}, {2, 0.5}, {1, 0.5}};
// Sezgin-like L: foot [0, 2] x [0, 1], leg [0, 1] x [1, 2]; inner corner (1, 1).
const std::vector<Vector2d> kLShape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

// --- polygon -------------------------------------------------------------------------

TEST(CollisionWorld, ComputeNearIsExactBelowTheCutoffAndABoundAboveIt) {
  // a planar 3-link arm swept over an L and a box: pairs nearer than the
  // cutoff are the full computation's, bit for bit; the others carry a lower
  // bound above the cutoff
  const Model model = make_planar({{0.8, 0.05}, {0.7, 0.05}, {0.5, 0.05}}, Vector2d::Zero());
  Scene scene = scene_of({polygon(kLShape, Vector3d(0.6, 0.4, 0)), box(Vector3d(-0.9, 0.2, 0), Vector3d(0.3, 0.5, 1))});
  CollisionWorld world(model, scene);
  KinematicsData kin(model);
  DistanceTable full, near;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  int culled = 0, exact = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const VectorXd q = Vector3d(angle(rng), angle(rng), angle(rng));
    forward_kinematics(model, q, kin);
    world.compute(kin, full);
    world.compute_near(kin, near, 0.15);
    for (size_t k = 0; k < full.pairs.size(); ++k) {
      if (full.pairs[k].distance <= 0.15) {
        EXPECT_EQ(near.pairs[k].distance, full.pairs[k].distance) << trial;
        EXPECT_EQ(near.pairs[k].on_link, full.pairs[k].on_link) << trial;
        ++exact;
      } else if (std::isnan(near.pairs[k].normal.x())) {
        EXPECT_GT(near.pairs[k].distance, 0.15) << trial;
        EXPECT_LE(near.pairs[k].distance, full.pairs[k].distance + 1e-12) << trial;
        ++culled;
      }
    }
  }
  EXPECT_GT(culled, 500);
  EXPECT_GT(exact, 100);
}

TEST(CollisionWorld, SquareSeparated) {
  const auto table = one_link_distances(0.7, 0.0, polygon(kSquare));
  expect_pair(table.at(0, 0), 0.3, xy(0.7, 0), xy(1, 0), -Vector3d::UnitX());
  expect_consistent(table.at(0, 0), 0);
}

TEST(CollisionWorld, SquareCornerIsNearest) {
  // a link at 45° ending at (0.5, 0.5), level with the square's corner (1, 0.5)
  const double angle = std::numbers::pi / 4;
  const auto table = one_link_distances(kSqrt2 / 2, angle, polygon(kSquare));
  const Vector3d tip = xy(0.5, 0.5), corner = xy(1, 0.5);
  expect_pair(table.at(0, 0), 0.5, tip, corner, -Vector3d::UnitX());
  expect_consistent(table.at(0, 0), 0);
}

TEST(CollisionWorld, SquareTouching) {
  const auto table = one_link_distances(1.0, 0.0, polygon(kSquare));
  EXPECT_NEAR(table.at(0, 0).distance, 0.0, kExact);
  expect_pair(table.at(0, 0), 0.0, xy(1, 0), xy(1, 0), -Vector3d::UnitX());
}

TEST(CollisionWorld, SquarePenetrating) {
  // the tip is 0.2 deep; sliding sideways would need 0.5
  const auto table = one_link_distances(1.2, 0.0, polygon(kSquare));
  expect_pair(table.at(0, 0), -0.2, xy(1.2, 0), xy(1, 0), -Vector3d::UnitX(), kDepth);
  expect_consistent(table.at(0, 0), 0);
}

TEST(CollisionWorld, SquareCrossedSideways) {
  // a link across the whole square near its top edge leaves upwards (+y)
  const Model model = make_planar({{3.0, 0.0}}, Vector2d(0, 0.4));
  const auto table = distances(model, VectorXd::Zero(1), scene_of({polygon(kSquare)}));
  const auto& pair = table.at(0, 0);
  EXPECT_NEAR(pair.distance, -0.1, kDepth);
  EXPECT_NEAR((pair.normal - Vector3d::UnitY()).norm(), 0.0, kDepth);
  EXPECT_NEAR(pair.on_link.y(), 0.4, kExact);
  EXPECT_NEAR(pair.on_obstacle.y(), 0.5, kExact);
  EXPECT_GE(pair.on_link.x(), 1.0 - kExact);
  EXPECT_LE(pair.on_link.x(), 2.0 + kExact);
  expect_consistent(pair, 0);
}

TEST(CollisionWorld, PlacedAndRotatedPolygon) {
  // the square's own frame: [0, 1] x [-0.5, 0.5]; turned 90° and moved to (0, 1)
  Obstacle o = polygon({{0, -0.5}, {1, -0.5}, {1, 0.5}, {0, 0.5}}, xy(0, 1));
  o.rotation = rotation_z(std::numbers::pi / 2);  // now [-0.5, 0.5] x [1, 2]
  const auto table = one_link_distances(0.6, std::numbers::pi / 2, o);
  expect_pair(table.at(0, 0), 0.4, xy(0, 0.6), xy(0, 1), -Vector3d::UnitY());
}

TEST(CollisionWorld, LShapeInnerCornerRegion) {
  const Obstacle l_shape = polygon(kLShape);
  // a link hanging down into the notch, 0.3 above the foot and 0.6 right of the leg
  {
    const Model model = make_planar({{1.0, 0.0}}, Vector2d(1.6, 2.3));
    const auto table = distances(model, VectorXd::Constant(1, -std::numbers::pi / 2),
                                 scene_of({l_shape}));
    expect_pair(table.at(0, 0), 0.3, xy(1.6, 1.3), xy(1.6, 1.0), Vector3d::UnitY());
    expect_consistent(table.at(0, 0), 0);
  }
  // a link aiming at the inner corner along the diagonal stops 0.2 short of
  // both inner edges (either is a nearest point)
  {
    const Model model = make_planar({{kSqrt2 * 0.8, 0.0}}, Vector2d(2, 2));
    const auto table = distances(model, VectorXd::Constant(1, -3 * std::numbers::pi / 4),
                                 scene_of({l_shape}));
    const auto& pair = table.at(0, 0);
    EXPECT_NEAR(pair.distance, 0.2, kExact);
    EXPECT_NEAR((pair.on_link - xy(1.2, 1.2)).norm(), 0.0, kExact);
    const bool on_foot = (pair.on_obstacle - xy(1.2, 1.0)).norm() < kExact;
    const bool on_leg = (pair.on_obstacle - xy(1.0, 1.2)).norm() < kExact;
    EXPECT_TRUE(on_foot || on_leg) << pair.on_obstacle.transpose();
    expect_consistent(pair, 0);
  }
  // the same link touching the inner corner
  {
    const Model model = make_planar({{kSqrt2, 0.0}}, Vector2d(2, 2));
    const auto table = distances(model, VectorXd::Constant(1, -3 * std::numbers::pi / 4),
                                 scene_of({l_shape}));
    EXPECT_NEAR(table.at(0, 0).distance, 0.0, kExact);
    EXPECT_NEAR((table.at(0, 0).on_obstacle - xy(1, 1)).norm(), 0.0, kExact);
  }
}

TEST(CollisionWorld, LShapePenetratingOuterFace) {
  // from the right into the foot's face x = 2, 0.1 deep
  const Model model = make_planar({{1.1, 0.0}}, Vector2d(3, 0.5));
  const auto table =
      distances(model, VectorXd::Constant(1, std::numbers::pi), scene_of({polygon(kLShape)}));
  expect_pair(table.at(0, 0), -0.1, xy(1.9, 0.5), xy(2, 0.5), Vector3d::UnitX(), kDepth);
}

TEST(CollisionWorld, LShapeClockwiseInputGivesSameDistances) {
  std::vector<Vector2d> clockwise(kLShape.rbegin(), kLShape.rend());
  const Model model = make_planar({{1.0, 0.0}}, Vector2d(1.6, 2.3));
  const VectorXd q = VectorXd::Constant(1, -std::numbers::pi / 2);
  EXPECT_NEAR(distances(model, q, scene_of({polygon(clockwise)})).at(0, 0).distance, 0.3, kExact);
}

// --- box ----------------------------------------------------------------------------

TEST(CollisionWorld, BoxSeparatedTouchingPenetrating) {
  const Obstacle o = box(xy(1.5, 0), Vector3d(1, 1, 1));
  expect_pair(one_link_distances(0.7, 0, o).at(0, 0), 0.3, xy(0.7, 0), xy(1, 0),
              -Vector3d::UnitX());
  EXPECT_NEAR(one_link_distances(1.0, 0, o).at(0, 0).distance, 0.0, kExact);
  expect_pair(one_link_distances(1.25, 0, o).at(0, 0), -0.25, xy(1.25, 0), xy(1, 0),
              -Vector3d::UnitX(), kDepth);
}

TEST(CollisionWorld, RotatedBoxCorner) {
  // a unit box turned 45° about z: its corner points at the arm, at x = 2 - √2/2
  Obstacle o = box(xy(2, 0), Vector3d(1, 1, 1));
  o.rotation = rotation_z(std::numbers::pi / 4);
  const double corner = 2 - kSqrt2 / 2;
  expect_pair(one_link_distances(1.0, 0, o).at(0, 0), corner - 1, xy(1, 0), xy(corner, 0),
              -Vector3d::UnitX());
  EXPECT_NEAR(one_link_distances(corner, 0, o).at(0, 0).distance, 0.0, kExact);
  // 0.1 past the corner: the shortest way out is along either face normal,
  // 0.1 / √2, not back along the link
  const LinkObstacleDistance pair = one_link_distances(corner + 0.1, 0, o).at(0, 0);
  EXPECT_NEAR(pair.distance, -0.1 / kSqrt2, kDepth);
  EXPECT_NEAR(std::abs(pair.normal.y()), 1 / kSqrt2, kDepth);
  EXPECT_NEAR(pair.normal.x(), -1 / kSqrt2, kDepth);
  EXPECT_NEAR((pair.on_link - xy(corner + 0.1, 0)).norm(), 0.0, kDepth);
  expect_consistent(pair, 0);
}

TEST(CollisionWorld, SpatialArmAgainstBox) {
  const Model model = make_spatial_xz({{1.0, 0.05}, {0.8, 0.05}, {0.6, 0.05}}, Vector3d::Zero());
  const Vector3d centre(0.9, 0.6, 0.9), size(0.4, 0.5, 0.3);
  const Scene scene = scene_of({box(centre, size)});
  KinematicsData kin(model);
  CollisionWorld world(model, scene);
  DistanceTable table;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    VectorXd q(model.dof());
    for (int j = 0; j < q.size(); ++j) q[j] = angle(rng);
    forward_kinematics(model, q, kin);
    world.compute(kin, table);
    for (int l = 0; l < model.link_count(); ++l) {
      Vector3d on_link;
      const double reference = reference_box_distance(kin.link_start.col(l), kin.link_end.col(l),
                                                      centre - size / 2, centre + size / 2,
                                                      on_link);
      const auto& pair = table.at(l, 0);
      expect_consistent(pair, 0.05);
      if (reference < 1e-6) {
        EXPECT_LT(pair.distance, -0.05 + kExact);  // the axis meets the box
        continue;
      }
      EXPECT_NEAR(pair.distance, reference - 0.05, 1e-8);
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

TEST(CollisionWorld, SpatialArmThroughBox) {
  // arm stretched along +x at z = 0 through a box reaching 0.15 below it and
  // 0.25 above: both links leave downwards, 0.15 + radius 0.05 deep
  const Model model = make_spatial_xz({{1.0, 0.05}, {1.0, 0.05}}, Vector3d::Zero());
  const auto table = distances(model, VectorXd::Zero(4),
                               scene_of({box(Vector3d(1.0, 0, 0.05), Vector3d(0.4, 0.4, 0.4))}));
  for (int l = 0; l < 2; ++l) {
    const auto& pair = table.at(l, 0);
    EXPECT_NEAR(pair.distance, -0.2, kDepth);
    EXPECT_NEAR((pair.normal + Vector3d::UnitZ()).norm(), 0.0, kDepth);
    expect_consistent(pair, 0.05);
  }
  // on_link: the middle of the part of each link inside the box
  EXPECT_NEAR((table.at(0, 0).on_link - Vector3d(0.9, 0, 0)).norm(), 0.0, kExact);
  EXPECT_NEAR((table.at(1, 0).on_link - Vector3d(1.1, 0, 0)).norm(), 0.0, kExact);
  EXPECT_NEAR(table.at(0, 0).on_obstacle.z(), -0.15, kExact);
}

// --- sphere and point ---------------------------------------------------------------

TEST(CollisionWorld, Sphere) {
  const Obstacle o = sphere(xy(2, 0), 0.5);
  expect_pair(one_link_distances(1.0, 0, o).at(0, 0), 0.5, xy(1, 0), xy(1.5, 0),
              -Vector3d::UnitX());
  EXPECT_NEAR(one_link_distances(1.5, 0, o).at(0, 0).distance, 0.0, kExact);
  expect_pair(one_link_distances(1.7, 0, o).at(0, 0), -0.2, xy(1.7, 0), xy(1.5, 0),
              -Vector3d::UnitX(), kDepth);
  // a link through the centre: as deep as the radius, pushed out sideways
  const LinkObstacleDistance through = one_link_distances(3.0, 0, o).at(0, 0);
  EXPECT_NEAR(through.distance, -0.5, kDepth);
  EXPECT_NEAR(through.normal.x(), 0.0, kExact);
  EXPECT_NEAR(through.normal.z(), 0.0, kExact);  // stays in the plane of a planar arm
  expect_consistent(through, 0);
}

TEST(CollisionWorld, Point) {
  const Obstacle o = point(xy(1, 0.3));
  expect_pair(one_link_distances(2.0, 0, o).at(0, 0), 0.3, xy(1, 0), xy(1, 0.3),
              -Vector3d::UnitY());
  // beyond the tip: the tip is nearest
  expect_pair(one_link_distances(0.6, 0, o).at(0, 0), 0.5, xy(0.6, 0), xy(1, 0.3),
              Vector3d(-0.8, -0.6, 0));
  // on the axis: touching a bare segment, inside a capsule
  const Obstacle on_axis = point(xy(1, 0));
  EXPECT_NEAR(one_link_distances(2.0, 0, on_axis).at(0, 0).distance, 0.0, kExact);
  const LinkObstacleDistance inside = one_link_distances(2.0, 0, on_axis, 0.1).at(0, 0);
  EXPECT_NEAR(inside.distance, -0.1, kDepth);
  EXPECT_NEAR(std::abs(inside.normal.y()), 1.0, kExact);
}

// --- wall ---------------------------------------------------------------------------

TEST(CollisionWorld, Wall) {
  // solid for x > 1.5, free side towards -x
  const Obstacle o = wall(xy(1.5, 7), -Vector3d::UnitX());
  expect_pair(one_link_distances(1.0, 0, o).at(0, 0), 0.5, xy(1, 0), xy(1.5, 0),
              -Vector3d::UnitX());
  EXPECT_NEAR(one_link_distances(1.5, 0, o).at(0, 0).distance, 0.0, kExact);
  expect_pair(one_link_distances(1.8, 0, o).at(0, 0), -0.3, xy(1.8, 0), xy(1.5, 0),
              -Vector3d::UnitX(), kDepth);
  // tilted link: only the tip's x matters
  const double angle = std::numbers::pi / 6;
  EXPECT_NEAR(one_link_distances(1.0, angle, o).at(0, 0).distance, 1.5 - std::cos(angle), kExact);
}

TEST(CollisionWorld, WallParallelToLinkUsesItsMiddle) {
  const Obstacle floor = wall(xy(0, -0.5), Vector3d::UnitY());
  expect_pair(one_link_distances(2.0, 0, floor).at(0, 0), 0.5, xy(1, 0), xy(1, -0.5),
              Vector3d::UnitY());
}

TEST(CollisionWorld, RotatedWall) {
  // own normal +y turned by -90° points along +x: the solid is x < 3
  Obstacle o = wall(xy(3, 0), Vector3d::UnitY());
  o.rotation = rotation_z(-std::numbers::pi / 2);
  // a link along -x
  const LinkObstacleDistance pair = one_link_distances(1.0, std::numbers::pi, o).at(0, 0);
  EXPECT_NEAR(pair.distance, -4.0, kDepth);  // the tip at x = -1 is 4 deep
  EXPECT_NEAR((pair.normal - Vector3d::UnitX()).norm(), 0.0, kExact);
}

TEST(CollisionWorld, ZeroLengthLinkIsAPoint) {
  const Model model = make_planar({{0.0, 0.1}}, Vector2d(0.5, 0));
  const auto table = distances(model, VectorXd::Zero(1),
                               scene_of({polygon(kSquare), sphere(xy(0.5, 1), 0.2)}));
  expect_pair(table.at(0, 0), 0.4, xy(0.5, 0), xy(1, 0), -Vector3d::UnitX());
  expect_pair(table.at(0, 1), 0.7, xy(0.5, 0), xy(0.5, 0.8), -Vector3d::UnitY());
  // inside the square: out through the nearest face
  const Model inside = make_planar({{0.0, 0.0}}, Vector2d(1.2, 0.1));
  expect_pair(distances(inside, VectorXd::Zero(1), scene_of({polygon(kSquare)})).at(0, 0), -0.2,
              xy(1.2, 0.1), xy(1, 0.1), -Vector3d::UnitX(), kDepth);
}

// --- radius, motion, table -------------------------------------------------------------

TEST(CollisionWorld, LinkRadiusSubtracts) {
  const Obstacle square = polygon(kSquare);
  const LinkObstacleDistance bare = one_link_distances(0.7, 0, square).at(0, 0);
  const LinkObstacleDistance fat = one_link_distances(0.7, 0, square, 0.05).at(0, 0);
  EXPECT_NEAR(fat.distance, bare.distance - 0.05, kExact);
  EXPECT_NEAR((fat.on_link - bare.on_link).norm(), 0.0, kExact);  // still on the axis
  // the radius alone makes it touch and then penetrate
  EXPECT_NEAR(one_link_distances(0.7, 0, square, 0.3).at(0, 0).distance, 0.0, kExact);
  EXPECT_NEAR(one_link_distances(0.7, 0, square, 0.4).at(0, 0).distance, -0.1, kDepth);
  EXPECT_NEAR(one_link_distances(0.7, 0, sphere(xy(2, 0), 0.5), 0.1).at(0, 0).distance, 0.7,
              kExact);
}

TEST(CollisionWorld, MovingObstacleAfterAdvance) {
  const Model model = one_link(1.0);
  KinematicsData kin(model);
  forward_kinematics(model, VectorXd::Zero(1), kin);
  Obstacle moving = sphere(xy(3, 0), 0.5);
  moving.velocity = Vector3d(-0.25, 0, 0);
  Scene scene = scene_of({moving});
  CollisionWorld world(model, scene);
  DistanceTable table;
  world.compute(kin, table);
  EXPECT_NEAR(table.at(0, 0).distance, 1.5, kExact);
  scene.advance_to(4.0);  // centre at x = 2
  world.sync(scene);
  world.compute(kin, table);
  EXPECT_NEAR(table.at(0, 0).distance, 0.5, kExact);
  scene.advance_to(8.0);  // centre at x = 1: through the link
  world.sync(scene);
  world.compute(kin, table);
  EXPECT_NEAR(table.at(0, 0).distance, -0.5, kDepth);
}

TEST(CollisionWorld, MovingPolygon) {
  const Model model = one_link(0.7);
  KinematicsData kin(model);
  forward_kinematics(model, VectorXd::Zero(1), kin);
  Obstacle square = polygon(kSquare);
  square.velocity = Vector3d(-0.1, 0, 0);
  Scene scene = scene_of({square});
  CollisionWorld world(model, scene);
  DistanceTable table;
  scene.advance_to(2.0);
  world.sync(scene);
  world.compute(kin, table);
  expect_pair(table.at(0, 0), 0.1, xy(0.7, 0), xy(0.8, 0), -Vector3d::UnitX());
}

TEST(CollisionWorld, ReshapeRebuildsGeometry) {
  const Model model = one_link(1.0);
  KinematicsData kin(model);
  forward_kinematics(model, VectorXd::Zero(1), kin);
  Scene scene = scene_of({sphere(xy(2, 0), 0.5)});
  CollisionWorld world(model, scene);
  DistanceTable table;
  scene.obstacles[0].radius = 0.8;
  world.sync(scene, true);
  world.compute(kin, table);
  EXPECT_NEAR(table.at(0, 0).distance, 0.2, kExact);
  scene.obstacles.push_back(point(xy(1.1, 0)));
  world.sync(scene, true);
  world.compute(kin, table);
  ASSERT_EQ(table.obstacles, 2);
  EXPECT_NEAR(table.at(0, 1).distance, 0.1, kExact);
  EXPECT_EQ(table.min_obstacle, 1);
  scene.obstacles.clear();
  world.sync(scene, true);
  world.compute(kin, table);
  EXPECT_EQ(table.obstacles, 0);
  EXPECT_EQ(table.min_link, -1);
  EXPECT_EQ(table.nearest_obstacle(0), -1);
  EXPECT_TRUE(std::isinf(table.min_distance));
}

TEST(CollisionWorld, BadGeometryIsRejected) {
  const Model model = one_link(1.0);
  EXPECT_THROW(CollisionWorld(model, scene_of({polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}})})),
               std::invalid_argument);
  EXPECT_THROW(CollisionWorld(model, scene_of({box(xy(0, 0), Vector3d(1, 0, 1))})),
               std::invalid_argument);
  EXPECT_THROW(CollisionWorld(model, scene_of({wall(xy(0, 0), Vector3d::Zero())})),
               std::invalid_argument);
}

TEST(CollisionWorld, TableMinimumAndNearestObstacle) {
  const Model model = make_planar({{1.0, 0.0}, {1.0, 0.0}}, Vector2d::Zero());
  const Scene scene = scene_of({sphere(xy(1, 1), 0.2),  // 0.8 from link 0's tip
                                point(xy(2.0, -0.3)),   // 0.3 from link 1's tip
                                wall(xy(0, -2), Vector3d::UnitY())});
  const auto table = distances(model, VectorXd::Zero(2), scene);
  EXPECT_EQ(table.links, 2);
  EXPECT_EQ(table.obstacles, 3);
  EXPECT_NEAR(table.min_distance, 0.3, kExact);
  EXPECT_EQ(table.min_link, 1);
  EXPECT_EQ(table.min_obstacle, 1);
  EXPECT_EQ(table.nearest_obstacle(0), 0);
  EXPECT_EQ(table.nearest_obstacle(1), 1);
}

// --- against FCL ---------------------------------------------------------------------

// Random planar 3-link arms among every kind of obstacle. Apart, FCL's GJK
// agrees to its tolerance (and the exact distance is never above it).
// Penetrating, FCL's depth (libccd MPR, along its own direction) can only be
// larger than the minimum translation computed here.
TEST(CollisionWorld, AgreesWithFclOnRandomPoses) {
  const Model model = make_planar({{1.0, 0.03}, {0.8, 0.0}, {0.6, 0.05}}, Vector2d(0, 0));
  Obstacle turned_box = box(xy(-1.2, 0.9), Vector3d(0.5, 0.3, 0.4));
  turned_box.rotation = rotation_z(0.3);
  Obstacle l_shape = polygon(kLShape, xy(0.2, -2.4));
  l_shape.rotation = rotation_z(0.7);
  const Scene scene = scene_of({polygon(kSquare), l_shape, turned_box, sphere(xy(-1, -1), 0.3),
                                point(xy(0.5, 1.2)), wall(xy(0, 2.1), -Vector3d::UnitY())});
  KinematicsData kin(model);
  CollisionWorld world(model, scene);
  DistanceTable analytic, reference;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  int apart = 0, penetrating = 0;
  for (int trial = 0; trial < 300; ++trial) {
    VectorXd q(3);
    for (int j = 0; j < 3; ++j) q[j] = angle(rng);
    forward_kinematics(model, q, kin);
    world.compute(kin, analytic);
    world.compute_with_fcl(kin, reference);
    if (analytic.min_distance > 1e-3) {
      EXPECT_NEAR(analytic.min_distance, reference.min_distance, 1e-6);
      EXPECT_EQ(analytic.min_link, reference.min_link);
      EXPECT_EQ(analytic.min_obstacle, reference.min_obstacle);
    }
    for (size_t i = 0; i < analytic.pairs.size(); ++i) {
      const auto& ours = analytic.pairs[i];
      const auto& theirs = reference.pairs[i];
      expect_consistent(ours, model.links[i / scene.obstacles.size()].radius);
      if (ours.distance > 1e-3) {
        // GJK stops early, so FCL is never nearer; it is up to ~4e-7 farther
        EXPECT_LE(ours.distance, theirs.distance + 1e-12) << "pair " << i << " trial " << trial;
        EXPECT_NEAR(ours.distance, theirs.distance, 1e-6) << "pair " << i << " trial " << trial;
        EXPECT_NEAR((ours.on_link - theirs.on_link).norm(), 0.0, 1e-5) << "pair " << i;
        if (ours.distance > 1e-2) {
          EXPECT_NEAR((ours.normal - theirs.normal).norm(), 0.0, 1e-3) << "pair " << i;
        }
        ++apart;
      } else if (ours.distance < -1e-3) {
        EXPECT_GE(ours.distance, theirs.distance - 1e-5) << "pair " << i << " trial " << trial;
        ++penetrating;
      }
    }
  }
  EXPECT_GT(apart, 3000);
  EXPECT_GT(penetrating, 100);
}

// The reported depth is a translation that separates: moving the obstacle by
// it against the normal leaves link and obstacle just touching, and any less
// leaves them overlapping. (That no shorter one exists is the separating-axis
// argument in convex_polytope.cpp, best_separating_axis.)
TEST(CollisionWorld, DepthIsTheTranslationThatSeparates) {
  const Model model = make_spatial_xz({{1.0, 0.04}, {0.9, 0.0}}, Vector3d::Zero());
  Obstacle tilted = box(Vector3d(0.7, 0.3, 0.2), Vector3d(0.8, 0.6, 0.5));
  tilted.rotation = (Eigen::AngleAxisd(0.4, Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(0.3, Vector3d::UnitX())).toRotationMatrix();
  Scene scene = scene_of({tilted});
  KinematicsData kin(model);
  CollisionWorld world(model, scene);
  DistanceTable table, moved_table;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    VectorXd q(model.dof());
    for (int j = 0; j < q.size(); ++j) q[j] = angle(rng);
    forward_kinematics(model, q, kin);
    world.sync(scene);
    world.compute(kin, table);
    for (int l = 0; l < model.link_count(); ++l) {
      const auto pair = table.at(l, 0);
      if (pair.distance > -1e-3) continue;
      Scene moved = scene;
      moved.obstacles[0].position += pair.distance * pair.normal;  // back by the depth
      world.sync(moved);
      world.compute(kin, moved_table);
      EXPECT_NEAR(moved_table.at(l, 0).distance, 0.0, 1e-9) << "trial " << trial;
      moved.obstacles[0].position += 1e-6 * pair.normal;  // a hair less
      world.sync(moved);
      world.compute(kin, moved_table);
      EXPECT_LT(moved_table.at(l, 0).distance, -0.5e-6);
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

}  // namespace
}  // namespace rrlab
