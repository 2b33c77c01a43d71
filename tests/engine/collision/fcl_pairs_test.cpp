// The FCL adapters on known poses: a capsule against each of FCL's shapes
// (the reference backend), the inflation of thin capsules, and a mesh link
// against a box and a mesh (contact without depth).
#include <rrlab/collision/fcl_pairs.hpp>

#include <gtest/gtest.h>

#include <cmath>

#include "support/mesh_shapes.hpp"

namespace rrlab::collision {
namespace {

using Eigen::Vector3d;

// An obstacle of the given kind at `position`, built with its FCL shapes.
struct FclFixture {
  Obstacle obstacle;
  ObstacleGeometry geometry;
  std::shared_ptr<FclObstacle> shapes;
  explicit FclFixture(Obstacle o) : obstacle(std::move(o)) {
    geometry = build_geometry(obstacle);
    geometry.rotation = obstacle.rotation;
    geometry.position = obstacle.position;
    shapes = build_fcl(obstacle, geometry);
  }
};

Obstacle fcl_obstacle_at(ShapeKind shape, const Vector3d& position) {
  Obstacle o;
  o.id = "o";
  o.shape = shape;
  o.position0 = o.position = position;
  return o;
}

// The capsule along x from the origin, 1 long, against a shape whose near
// face (or surface) lies at x = 1.5 on the axis: 0.5 minus the radius.
TEST(FclPairs, CapsuleAgainstEachShape) {
  Obstacle box = fcl_obstacle_at(ShapeKind::box, Vector3d(2, 0, 0));
  box.size = Vector3d(1, 1, 1);
  Obstacle sphere = fcl_obstacle_at(ShapeKind::sphere, Vector3d(2, 0, 0));
  sphere.radius = 0.5;
  Obstacle point = fcl_obstacle_at(ShapeKind::point, Vector3d(1.5, 0, 0));
  Obstacle polygon = fcl_obstacle_at(ShapeKind::polygon, Vector3d(1.5, 0, 0));
  polygon.points = {{0, -0.5}, {1, -0.5}, {1, 0}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};  // an L, two parts
  Obstacle mesh = fcl_obstacle_at(ShapeKind::mesh, Vector3d(2, 0, 0));
  mesh.mesh = std::make_shared<TriangleMesh>(box_mesh(Vector3d(1, 1, 1)));
  const std::shared_ptr<FclCapsule> capsule = make_fcl_capsule(0.1);
  pose_fcl_capsule(*capsule, Vector3d::Zero(), Vector3d(1, 0, 0), 0.1);
  for (const Obstacle& o : {box, sphere, point, polygon, mesh}) {
    const FclFixture fixture(o);
    LinkObstacleDistance out;
    fcl_capsule_obstacle(*capsule, fixture.geometry, *fixture.shapes, out);
    EXPECT_NEAR(out.distance, 0.4, 1e-6) << to_string(o.shape);
    EXPECT_NEAR((out.on_link - Vector3d(1, 0, 0)).norm(), 0.0, 1e-5) << to_string(o.shape);  // back on the axis
    EXPECT_NEAR((out.normal + Vector3d::UnitX()).norm(), 0.0, 1e-5) << to_string(o.shape);
  }
  // penetrating the box 0.2 (plus the radius): the depth from fcl::collide
  pose_fcl_capsule(*capsule, Vector3d::Zero(), Vector3d(1.7, 0, 0), 0.1);
  const FclFixture fixture(box);
  LinkObstacleDistance out;
  fcl_capsule_obstacle(*capsule, fixture.geometry, *fixture.shapes, out);
  EXPECT_NEAR(out.distance, -0.3, 1e-4);  // libccd MPR's tolerance
  EXPECT_NEAR((out.normal + Vector3d::UnitX()).norm(), 0.0, 1e-3);
}

// A bare segment is inflated to 1 mm for GJK and the distance corrected;
// a wall has no FCL shape (FCL 0.7 has no Halfspace distance).
TEST(FclPairs, ThinCapsulesAndWalls) {
  Obstacle box = fcl_obstacle_at(ShapeKind::box, Vector3d(0.5, 0.3, 0));
  box.size = Vector3d(0.2, 0.2, 0.2);
  const FclFixture fixture(box);
  const std::shared_ptr<FclCapsule> segment = make_fcl_capsule(0.0);
  pose_fcl_capsule(*segment, Vector3d(0, 0, 0), Vector3d(1, 0, 0), 0.0);
  LinkObstacleDistance out;
  fcl_capsule_obstacle(*segment, fixture.geometry, *fixture.shapes, out);
  EXPECT_NEAR(out.distance, 0.2, 1e-6);  // the bare segment's distance, not the inflated capsule's
  Obstacle wall = fcl_obstacle_at(ShapeKind::wall, Vector3d::Zero());
  wall.normal = Vector3d::UnitZ();
  const FclFixture floor(wall);
  fcl_capsule_obstacle(*segment, floor.geometry, *floor.shapes, out);
  EXPECT_TRUE(std::isinf(out.distance));  // nothing to measure: the pair table keeps walls analytic
}

// A cube mesh link (1 m, posed at x = 0) against a box and the same box as a mesh.
TEST(FclPairs, MeshLinkAgainstBoxAndMesh) {
  const TriangleMesh cube = box_mesh(Vector3d(1, 1, 1));
  const std::shared_ptr<MeshBvh> bvh = make_bvh(cube);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Obstacle box = fcl_obstacle_at(ShapeKind::box, Vector3d(2, 0, 0));
  box.size = Vector3d(1, 1, 1);
  Obstacle mesh = fcl_obstacle_at(ShapeKind::mesh, Vector3d(2, 0, 0));
  mesh.mesh = std::make_shared<TriangleMesh>(cube);
  for (const Obstacle& o : {box, mesh}) {
    const FclFixture fixture(o);
    LinkObstacleDistance out;
    pose.translation() = Vector3d::Zero();
    fcl_mesh_obstacle(*bvh, pose, fixture.geometry, *fixture.shapes, out);
    EXPECT_NEAR(out.distance, 1.0, 1e-8) << to_string(o.shape);
    EXPECT_NEAR(out.on_link.x(), 0.5, 1e-7) << to_string(o.shape);
    EXPECT_NEAR(out.on_obstacle.x(), 1.5, 1e-7) << to_string(o.shape);
    EXPECT_NEAR((out.normal + Vector3d::UnitX()).norm(), 0.0, 1e-6) << to_string(o.shape);
    // overlapping: contact without depth, pointing from the obstacle's centre to the link's origin
    pose.translation() = Vector3d(1.2, 0, 0);
    fcl_mesh_obstacle(*bvh, pose, fixture.geometry, *fixture.shapes, out);
    EXPECT_EQ(out.distance, -kMeshContact) << to_string(o.shape);
    EXPECT_NEAR((out.normal + Vector3d::UnitX()).norm(), 0.0, 1e-15) << to_string(o.shape);
  }
}

}  // namespace
}  // namespace rrlab::collision
