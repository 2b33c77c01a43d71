// Each obstacle kind's geometry, built from its scenario description, and a
// known distance of a segment to it through the kind's own function.
#include <rrlab/collision/obstacle_geometry.hpp>

#include <gtest/gtest.h>

#include <numbers>
#include <stdexcept>
#include <string>

#include "support/mesh_shapes.hpp"

namespace rrlab::collision {
namespace {

using Eigen::Vector3d;

Obstacle obstacle_of(ShapeKind shape, const std::string& id = "o") {
  Obstacle o;
  o.id = id;
  o.shape = shape;
  return o;
}

// The geometry posed: turned a quarter about z and moved to `position`.
ObstacleGeometry posed_geometry(const Obstacle& o, const Vector3d& position) {
  ObstacleGeometry g = build_geometry(o);
  g.rotation = Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitZ()).toRotationMatrix();
  g.position = position;
  return g;
}

TEST(ObstacleGeometry, Polygon) {
  Obstacle o = obstacle_of(ShapeKind::polygon);
  o.points = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};  // an L: two convex parts
  o.z_min = 0;
  o.z_max = 0.5;
  const ObstacleGeometry g = posed_geometry(o, Vector3d(1, 0, 0));  // turned: the foot along +y from (1, 0)
  EXPECT_EQ(g.shape, ShapeKind::polygon);
  EXPECT_EQ(g.parts.size(), 2u);
  LinkObstacleDistance out;
  // a vertical segment above the foot: 0.25 above the top face z = 0.5
  segment_polytopes(g, Vector3d(0.5, 1.5, 0.75), Vector3d(0.5, 1.5, 2), out);
  EXPECT_NEAR(out.distance, 0.25, 1e-12);
  EXPECT_NEAR((out.normal - Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((out.on_obstacle - Vector3d(0.5, 1.5, 0.5)).norm(), 0.0, 1e-12);
}

TEST(ObstacleGeometry, Box) {
  Obstacle o = obstacle_of(ShapeKind::box);
  o.size = Vector3d(2, 1, 1);  // turned: 1 along x, 2 along y
  const ObstacleGeometry g = posed_geometry(o, Vector3d(3, 0, 0));
  EXPECT_EQ(g.parts.size(), 1u);
  EXPECT_EQ(g.parts[0].vertices.size(), 8u);
  LinkObstacleDistance out;
  segment_polytopes(g, Vector3d(0, 0, 0), Vector3d(2, 0, 0), out);  // the face x = 2.5
  EXPECT_NEAR(out.distance, 0.5, 1e-12);
  EXPECT_NEAR((out.on_link - Vector3d(2, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((out.normal + Vector3d::UnitX()).norm(), 0.0, 1e-12);
  segment_polytopes(g, Vector3d(0, 0, 0), Vector3d(2.7, 0, 0), out);  // 0.2 deep
  EXPECT_NEAR(out.distance, -0.2, 1e-12);
}

TEST(ObstacleGeometry, SphereAndPoint) {
  Obstacle o = obstacle_of(ShapeKind::sphere);
  o.radius = 0.5;
  const ObstacleGeometry sphere = posed_geometry(o, Vector3d(1, 2, 0));
  EXPECT_EQ(sphere.radius, 0.5);
  EXPECT_TRUE(sphere.parts.empty());
  LinkObstacleDistance out;
  segment_sphere_obstacle(sphere, Vector3d(0, 0, 0), Vector3d(2, 0, 0), out);
  EXPECT_NEAR(out.distance, 1.5, 1e-15);
  EXPECT_NEAR((out.on_obstacle - Vector3d(1, 1.5, 0)).norm(), 0.0, 1e-15);
  const ObstacleGeometry point = posed_geometry(obstacle_of(ShapeKind::point), Vector3d(1, 2, 0));
  EXPECT_EQ(point.radius, 0.0);
  segment_point(point, Vector3d(0, 0, 0), Vector3d(2, 0, 0), out);
  EXPECT_NEAR(out.distance, 2.0, 1e-15);
  EXPECT_EQ(out.on_obstacle, Vector3d(1, 2, 0));
}

TEST(ObstacleGeometry, Wall) {
  Obstacle o = obstacle_of(ShapeKind::wall);
  o.normal = Vector3d(3, 0, 0);  // unit once built; turned: +y
  const ObstacleGeometry g = posed_geometry(o, Vector3d(0, -1, 0));
  EXPECT_NEAR((g.normal - Vector3d::UnitX()).norm(), 0.0, 1e-15);
  LinkObstacleDistance out;
  segment_wall_obstacle(g, Vector3d(0, 0.5, 0), Vector3d(1, -1.25, 0), out);
  EXPECT_NEAR(out.distance, -0.25, 1e-15);  // the end below y = -1
  EXPECT_NEAR((out.normal - Vector3d::UnitY()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((out.on_obstacle - Vector3d(1, -1, 0)).norm(), 0.0, 1e-15);
}

TEST(ObstacleGeometry, MeshBuiltOnceAndReused) {
  Obstacle o = obstacle_of(ShapeKind::mesh);
  o.mesh = std::make_shared<TriangleMesh>(box_mesh(Vector3d(1, 1, 1)));
  const ObstacleGeometry g = posed_geometry(o, Vector3d(0, 0, 2));
  ASSERT_TRUE(g.bvh);
  EXPECT_TRUE(g.closed);
  EXPECT_NEAR((g.bounds.min() - Vector3d::Constant(-0.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((g.bounds.max() - Vector3d::Constant(0.5)).norm(), 0.0, 1e-15);
  LinkObstacleDistance out;
  segment_mesh_obstacle(g, Vector3d(-1, 0, 0), Vector3d(1, 0, 0), out);  // 1.5 below the bottom face
  EXPECT_NEAR(out.distance, 1.5, 1e-12);
  EXPECT_NEAR((out.normal + Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  // rebuilt with the previous geometry: the same tree, not a new one
  EXPECT_EQ(build_geometry(o, {g}).bvh, g.bvh);
  EXPECT_NE(build_geometry(o).bvh, g.bvh);
  // without its top face the mesh is open
  TriangleMesh open = box_mesh(Vector3d(1, 1, 1));
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);
  o.mesh = std::make_shared<TriangleMesh>(open);
  EXPECT_FALSE(build_geometry(o).closed);
}

TEST(ObstacleGeometry, BadGeometryNamesTheObstacle) {
  auto message = [](const Obstacle& o) {
    try {
      build_geometry(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Obstacle polygon = obstacle_of(ShapeKind::polygon, "bow");
  polygon.points = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};  // edges cross
  EXPECT_EQ(message(polygon).rfind("obstacle 'bow': ", 0), 0u) << message(polygon);
  polygon.points = {{0, 0}, {1, 0}, {0, 1}};
  polygon.z_max = polygon.z_min;
  EXPECT_EQ(message(polygon), "obstacle 'bow': z_max must be > z_min");
  Obstacle box = obstacle_of(ShapeKind::box, "flat");
  box.size = Vector3d(1, 0, 1);
  EXPECT_EQ(message(box), "obstacle 'flat': box size must be > 0");
  Obstacle sphere = obstacle_of(ShapeKind::sphere, "ball");
  sphere.radius = -1;
  EXPECT_EQ(message(sphere), "obstacle 'ball': sphere radius must be >= 0");
  Obstacle wall = obstacle_of(ShapeKind::wall, "w");
  wall.normal = Vector3d::Zero();
  EXPECT_EQ(message(wall), "obstacle 'w': wall normal must be non-zero");
  EXPECT_EQ(message(obstacle_of(ShapeKind::mesh, "m")), "obstacle 'm': mesh has no triangles");
}

}  // namespace
}  // namespace rrlab::collision
