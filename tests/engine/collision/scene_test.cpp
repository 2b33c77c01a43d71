// Scenes: obstacles by id, their motion at constant velocity, shape names.
#include <rrlab/collision/scene.hpp>

#include <gtest/gtest.h>

#include <string>

namespace rrlab {
namespace {

TEST(Scene, FindsObstaclesById) {
  Scene scene;
  for (const char* id : {"table", "ball", "shelf"}) {
    Obstacle o;
    o.id = id;
    scene.obstacles.push_back(o);
  }
  EXPECT_EQ(scene.find("table"), 0);
  EXPECT_EQ(scene.find("shelf"), 2);
  EXPECT_EQ(scene.find("none"), -1);
  EXPECT_EQ(Scene{}.find("table"), -1);
}

TEST(Scene, AdvanceMovesFromTheStartPose) {
  Scene scene;
  Obstacle moving;
  moving.position0 = moving.position = Eigen::Vector3d(1, 0, 0);
  moving.velocity = Eigen::Vector3d(0.5, -1, 0);
  Obstacle still;
  still.position0 = still.position = Eigen::Vector3d(0, 2, 0);
  scene.obstacles = {moving, still};
  EXPECT_TRUE(scene.obstacles[0].moving());
  EXPECT_FALSE(scene.obstacles[1].moving());
  scene.advance_to(2.0);
  EXPECT_EQ(scene.obstacles[0].position, Eigen::Vector3d(2, -2, 0));
  EXPECT_EQ(scene.obstacles[1].position, Eigen::Vector3d(0, 2, 0));
  scene.advance_to(1.0);  // from position0, not from the current position
  EXPECT_EQ(scene.obstacles[0].position, Eigen::Vector3d(1.5, -1, 0));
}

TEST(Scene, ShapeNames) {
  EXPECT_EQ(std::string(to_string(ShapeKind::polygon)), "polygon");
  EXPECT_EQ(std::string(to_string(ShapeKind::box)), "box");
  EXPECT_EQ(std::string(to_string(ShapeKind::sphere)), "sphere");
  EXPECT_EQ(std::string(to_string(ShapeKind::point)), "point");
  EXPECT_EQ(std::string(to_string(ShapeKind::wall)), "wall");
  EXPECT_EQ(std::string(to_string(ShapeKind::mesh)), "mesh");
}

}  // namespace
}  // namespace rrlab
