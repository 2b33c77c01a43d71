// Voronoi-boundary control points and nearest obstacle vertices on the
// geometry of Sezgin et al. Ex2 and Ex3.
#include <rrlab/collision/voronoi_points.hpp>

#include <gtest/gtest.h>

namespace rrlab {
namespace {

Obstacle moving_polygon(std::vector<Eigen::Vector2d> pts, Eigen::Vector3d velocity = Eigen::Vector3d::Zero()) {
  Obstacle o;
  o.shape = ShapeKind::polygon;
  o.points = std::move(pts);
  o.velocity = velocity;
  return o;
}

struct Buffers {
  std::vector<ControlPoint> a, b;
  std::vector<Eigen::Vector3d> out;
};

TEST(VoronoiPoints, Ex3NarrowGapGivesThePapersTwoPoints) {
  Scene scene;
  scene.obstacles = {moving_polygon({{1.4, 0.0}, {1.6, 0.0}, {1.6, 0.8}, {1.4, 0.8}}),
                     moving_polygon({{1.4, 1.2}, {1.6, 1.2}, {1.6, 2.0}, {1.4, 2.0}})};
  Buffers buf;
  voronoi_control_points(scene, 0.0, buf.a, buf.b, buf.out);
  ASSERT_EQ(buf.out.size(), 2u);  // the two equal gaps (0.4), in either order
  const bool first_left = buf.out[0].x() < buf.out[1].x();
  EXPECT_TRUE(buf.out[first_left ? 0 : 1].isApprox(Eigen::Vector3d(1.4, 1.0, 0), 1e-12));
  EXPECT_TRUE(buf.out[first_left ? 1 : 0].isApprox(Eigen::Vector3d(1.6, 1.0, 0), 1e-12));
}

TEST(VoronoiPoints, Ex2SmallestGapMidpointMovesWithTheTriangle) {
  Scene scene;
  scene.obstacles = {moving_polygon({{1.4, 1.4}, {1.6, 2.0}, {0.9, 1.9}}, {0.1, 0, 0}),
                     moving_polygon({{0.9, 0.3}, {1.4, 0.3}, {1.4, 0.8}, {0.9, 0.8}})};
  Buffers buf;
  voronoi_control_points(scene, 0.0, buf.a, buf.b, buf.out);
  ASSERT_EQ(buf.out.size(), 1u);  // (1.4, 1.4)–(1.4, 0.8): gap 0.6
  EXPECT_TRUE(buf.out[0].isApprox(Eigen::Vector3d(1.4, 1.1, 0), 1e-12));
  // one sampling period later (time offset 1): the triangle's vertex is at (1.5, 1.4)
  voronoi_control_points(scene, 1.0, buf.a, buf.b, buf.out);
  ASSERT_EQ(buf.out.size(), 1u);
  EXPECT_TRUE(buf.out[0].isApprox(Eigen::Vector3d(1.45, 1.1, 0), 1e-12));
  // the scene's own clock moves it too
  scene.advance_to(3.0);  // vertex at (1.7, 1.4): nearest rectangle vertex still (1.4, 0.8)
  voronoi_control_points(scene, 0.0, buf.a, buf.b, buf.out);
  ASSERT_EQ(buf.out.size(), 1u);
  EXPECT_TRUE(buf.out[0].isApprox(Eigen::Vector3d(1.55, 1.1, 0), 1e-12));
}

TEST(VoronoiPoints, GapToAWallIsHalfWayToTheWall) {
  Scene scene;
  Obstacle wall;
  wall.shape = ShapeKind::wall;
  wall.position = {0, 0, 0};
  wall.normal = {0, 1, 0};  // floor y = 0, free side y > 0
  scene.obstacles = {moving_polygon({{1.0, 0.6}, {2.0, 0.6}, {2.0, 1.0}, {1.0, 1.0}}), wall};
  Buffers buf;
  voronoi_control_points(scene, 0.0, buf.a, buf.b, buf.out);
  ASSERT_EQ(buf.out.size(), 2u);  // the two lower corners tie
  EXPECT_TRUE(buf.out[0].isApprox(Eigen::Vector3d(1.0, 0.3, 0), 1e-12));
  EXPECT_TRUE(buf.out[1].isApprox(Eigen::Vector3d(2.0, 0.3, 0), 1e-12));
}

TEST(VoronoiPoints, SphereGapsCountFromTheSurface) {
  Scene scene;
  Obstacle a, b;
  a.shape = b.shape = ShapeKind::sphere;
  a.radius = 0.5;
  b.radius = 0.25;
  a.position = {0, 0, 0};
  b.position = {2, 0, 0};
  scene.obstacles = {a, b};
  Buffers buf;
  voronoi_control_points(scene, 0.0, buf.a, buf.b, buf.out);
  ASSERT_EQ(buf.out.size(), 1u);
  EXPECT_TRUE(buf.out[0].isApprox(Eigen::Vector3d(1.125, 0, 0), 1e-12));  // between 0.5 and 1.75
}

TEST(VoronoiPoints, NearestVertexOfTheLShape) {
  Scene scene;
  scene.obstacles = {moving_polygon({{2.0, 0.0}, {2.0, 0.5}, {1.5, 0.5}, {1.5, 1.1}, {2.6, 1.1}, {2.6, 0.0}})};
  std::vector<ControlPoint> scratch;
  const NearestObstaclePoint np = nearest_obstacle_point(scene, {1.0, 0.4, 0}, 0.0, false, scratch);
  ASSERT_TRUE(np.found);
  EXPECT_TRUE(np.point.isApprox(Eigen::Vector3d(1.5, 0.5, 0)));
  EXPECT_NEAR(np.distance, std::hypot(0.5, 0.1), 1e-12);
  // with edge midpoints, the middle of the edge (1.5, 0.5)–(1.5, 1.1) is nearer to (1.0, 0.8)
  const NearestObstaclePoint mid = nearest_obstacle_point(scene, {1.0, 0.8, 0}, 0.0, true, scratch);
  EXPECT_TRUE(mid.point.isApprox(Eigen::Vector3d(1.5, 0.8, 0)));
}

// A vertex named by (obstacle, candidate) is found again, also after the
// obstacle moved; indices that name nothing give found = false.
TEST(VoronoiPoints, CandidateByIndexFollowsTheNearestVertex) {
  Scene scene;
  scene.obstacles = {moving_polygon({{2.0, 0.0}, {2.0, 0.5}, {1.5, 0.5}, {1.5, 1.1}, {2.6, 1.1}, {2.6, 0.0}}, {0.1, 0, 0})};
  std::vector<ControlPoint> scratch;
  const Eigen::Vector3d p(1.2, 0.4, 0);
  const NearestObstaclePoint nearest = nearest_obstacle_point(scene, p, 0.0, false, scratch);
  ASSERT_TRUE(nearest.found);
  EXPECT_EQ(nearest.candidate, 2);  // (1.5, 0.5)
  const NearestObstaclePoint again = obstacle_candidate(scene, 0, nearest.candidate, p, 0.0, false, scratch);
  ASSERT_TRUE(again.found);
  EXPECT_NEAR((again.point - nearest.point).norm(), 0.0, 1e-12);
  EXPECT_NEAR(again.distance, nearest.distance, 1e-12);
  const NearestObstaclePoint later = obstacle_candidate(scene, 0, 2, p, 1.0, false, scratch);
  EXPECT_NEAR((later.point - Eigen::Vector3d(1.6, 0.5, 0)).norm(), 0.0, 1e-12);  // moved 0.1 along x
  EXPECT_FALSE(obstacle_candidate(scene, 0, 6, p, 0.0, false, scratch).found);
  EXPECT_TRUE(obstacle_candidate(scene, 0, 11, p, 0.0, true, scratch).found);  // with edge midpoints: 12
  EXPECT_FALSE(obstacle_candidate(scene, 1, 0, p, 0.0, false, scratch).found);
  EXPECT_FALSE(obstacle_candidate(scene, -1, -1, p, 0.0, false, scratch).found);
}

}  // namespace
}  // namespace rrlab
