// Mesh distances (collision/mesh_distance.hpp): a segment against a mesh's
// tree against sampling, closed meshes and their inside, mesh links against
// walls and spheres; then mesh links (a URDF <collision><mesh>, read with
// assimp) against the same shape as an analytic capsule, and against FCL's
// own BVH distance.
#include <rrlab/collision/mesh_distance.hpp>

#include <fcl/fcl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/mesh_loader.hpp>
#include "support/mesh_shapes.hpp"
#include <rrlab/collision/segment_geometry.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {
namespace {

using nlohmann::json;
constexpr double kRadius = 0.05, kLength = 0.4;

// The capsule of kRadius around the z segment [0, kLength] as a mesh
// (tests/support/mesh_shapes.hpp): 64 vertices around, 16 rings per cap.
TriangleMesh test_capsule() { return capsule_mesh(kRadius, kLength, 64, 16); }

// A two-joint arm whose second link is the capsule, as a mesh or a cylinder primitive.
std::string arm_urdf(const std::string& geometry) {
  return R"(<robot name="m"><link name="base"/>
  <link name="l1"><collision><geometry><sphere radius="0.03"/></geometry></collision></link>
  <link name="l2"><collision><geometry>)" + geometry + R"(</geometry></collision></link><link name="tip"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" velocity="1" effort="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0.2 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" velocity="1" effort="1"/></joint>
  <joint name="jt" type="fixed"><parent link="l2"/><child link="tip"/><origin xyz="0 0 0.4"/></joint></robot>)";
}

json arm_scenario() {
  return {{"name", "mesh"},
          {"robot", {{"kind", "urdf"}, {"file", "arm.urdf"}, {"q0", {0.3, 0.8}}}},
          {"obstacles",
           {{{"id", "ball"}, {"shape", "sphere"}, {"center", {0.55, 0.1, 0.5}}, {"radius", 0.1}},
            {{"id", "crate"}, {"shape", "box"}, {"center", {0.1, 0.45, 0.3}}, {"size", {0.2, 0.2, 0.3}}, {"rpy", {0, 0, 0.4}}},
            {{"id", "floor"}, {"shape", "wall"}, {"point", {0, 0, 0.05}}, {"normal", {0, 0, 1}}}}},
          {"task", {{"space", "xy"}, {"trajectory", {{"type", "polyline"}, {"points", {{0.5, 0}, {0.5, 0.1}}}}}}}};
}

class MeshLink : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("rrlab_mesh_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    write_obj(test_capsule(), (dir_ / "capsule.obj").string());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  Scenario load(const std::string& geometry) {
    std::ofstream(dir_ / "arm.urdf") << arm_urdf(geometry);
    return parse_scenario(arm_scenario(), dir_.string());
  }
  std::filesystem::path dir_;
};

TEST_F(MeshLink, LoadsWithScale) {
  const TriangleMesh m = load_mesh_file((dir_ / "capsule.obj").string(), Eigen::Vector3d(2, 1, 1));
  EXPECT_EQ(m.triangles.size(), test_capsule().triangles.size());
  double max_x = 0;
  for (const auto& v : m.vertices) max_x = std::max(max_x, v.x());
  EXPECT_NEAR(max_x, 2 * kRadius, 1e-6);
  EXPECT_THROW(load_mesh_file((dir_ / "none.stl").string(), Eigen::Vector3d::Ones()), MeshError);
}

// The mesh link's distances against the cylinder primitive's capsule (the
// same shape, analytic) and against FCL's own BVH distance to each obstacle.
TEST_F(MeshLink, DistancesMatchTheCapsuleAndFcl) {
  const Scenario mesh = load(R"(<mesh filename="capsule.obj"/>)");
  const Scenario capsule = load(R"(<cylinder radius="0.05" length="0.4"/>)");
  ASSERT_TRUE(mesh.model.links[1].mesh);
  ASSERT_FALSE(capsule.model.links[1].mesh);
  EXPECT_NEAR(mesh.model.links[1].radius, kRadius, 1e-6);  // the bound around the segment
  EXPECT_EQ(mesh.json["robot"].value("file", ""), "arm.urdf");  // mesh files: not inlined

  CollisionWorld mesh_world(mesh.model, mesh.scene), capsule_world(capsule.model, capsule.scene);
  KinematicsData kin(mesh.model);
  DistanceTable a, b;
  double worst_capsule = 0, worst_fcl = 0;
  int capsule_checked = 0, fcl_checked = 0;
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Triangle> tris;
  for (const auto& t : mesh.model.links[1].mesh->triangles) tris.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel();
  bvh->addSubModel(mesh.model.links[1].mesh->vertices, tris);
  bvh->endModel();
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector2d q(-1.0 + 0.2 * i, -1.2 + 0.22 * i);
    forward_kinematics(mesh.model, q, kin);
    mesh_world.compute(kin, a);
    capsule_world.compute(kin, b);
    for (int o = 0; o < 3; ++o) {
      if (b.at(1, o).distance <= 0) continue;  // penetration: the mesh gives no depth
      worst_capsule = std::max(worst_capsule, std::abs(a.at(1, o).distance - b.at(1, o).distance));
      ++capsule_checked;
      // the nearest point on the link lies on the capsule's surface too
      EXPECT_LT((a.at(1, o).on_link - a.at(1, o).on_obstacle).norm() - a.at(1, o).distance, 1e-6);
    }
    // FCL directly, for the box (the sphere is measured by nearest triangle:
    // FCL 0.7.0's mesh–sphere distance reports contact at every pose here)
    const fcl::Transform3d pose = kin.joint_frames[1];
    for (int o = 1; o < 2; ++o) {
      const Obstacle& ob = mesh.scene.obstacles[size_t(o)];
      fcl::Transform3d op = fcl::Transform3d::Identity();
      op.linear() = ob.rotation;
      op.translation() = ob.position;
      std::shared_ptr<fcl::CollisionGeometryd> shape;
      if (o == 0) shape = std::make_shared<fcl::Sphered>(ob.radius);
      else shape = std::make_shared<fcl::Boxd>(ob.size);
      fcl::DistanceRequestd req(true, false, 0.0, 0.0, 1e-10, fcl::GST_INDEP);
      fcl::DistanceResultd res;
      fcl::distance(bvh.get(), pose, shape.get(), op, req, res);
      if (res.min_distance > 0) {
        worst_fcl = std::max(worst_fcl, std::abs(res.min_distance - a.at(1, o).distance));
        ++fcl_checked;
      }
    }
  }
  // inscribed tessellation: r (1 - cos(π/64)) = 6e-5 m around, similar over the caps
  EXPECT_LT(worst_capsule, 2e-4);
  EXPECT_LT(worst_fcl, 1e-12);
  EXPECT_GE(capsule_checked, 30);
  EXPECT_GE(fcl_checked, 10);
  std::cout << "mesh vs capsule: worst " << worst_capsule << " m over " << capsule_checked << " pairs\n";
}

TEST_F(MeshLink, MeshFaultsAreNamed) {
  try {
    load(R"(<mesh filename="package://arm/capsule.obj"/>)");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.path(), "robot.file");
    EXPECT_NE(std::string(e.what()).find("package:// and file:// URIs are not resolved"), std::string::npos) << e.what();
  }
  try {
    load(R"(<mesh filename="../../etc/passwd"/>)");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("leads outside the scenario directory"), std::string::npos) << e.what();
  }
  std::ofstream(dir_ / "broken.stl") << "solid nothing here\n";
  try {
    load(R"(<mesh filename="broken.stl"/>)");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("(link 'l2')"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rrlab

namespace rrlab::collision {
namespace {

using Eigen::Vector3d;

// The distance of a point to a mesh (in its frame): the nearest triangle.
double point_mesh_distance(const TriangleMesh& mesh, const Vector3d& p) {
  double best = INFINITY;
  for (const Eigen::Vector3i& t : mesh.triangles)
    best = std::min(best, (closest_on_triangle(p, mesh.vertices[size_t(t[0])], mesh.vertices[size_t(t[1])],
                                               mesh.vertices[size_t(t[2])]) -
                           p)
                              .norm());
  return best;
}

// Segment against a posed mesh, apart, against samples along the segment: the
// distance is 1-Lipschitz along it, so the exact minimum lies within half a
// sample step below the sampled one.
TEST(MeshDistance, SegmentMeshAgainstSampling) {
  const TriangleMesh ball = sphere_mesh(0.3, 16, 8);
  const std::shared_ptr<MeshBvh> bvh = make_bvh(ball);
  Eigen::AlignedBox3d bounds;
  for (const Vector3d& v : ball.vertices) bounds.extend(v);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.6, Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  const Vector3d position(0.1, -0.2, 0.3);
  std::mt19937 rng(51);
  std::uniform_real_distribution<double> coordinate(-0.7, 0.7);
  constexpr int kSamples = 1000;
  int apart = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vector3d a = position + Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vector3d b = position + Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    LinkObstacleDistance out;
    segment_mesh(*bvh, true, bounds, rotation, position, a, b, out);
    if (out.distance <= 0) continue;
    double sampled = INFINITY;
    for (int i = 0; i <= kSamples; ++i) {
      const Vector3d on_segment = a + (b - a) * (double(i) / kSamples);
      sampled = std::min(sampled, point_mesh_distance(ball, rotation.transpose() * (on_segment - position)));
    }
    EXPECT_LE(out.distance, sampled + 1e-12) << trial;
    EXPECT_GE(out.distance, sampled - 0.5 * (b - a).norm() / kSamples) << trial;
    EXPECT_NEAR((out.on_link - out.on_obstacle).norm(), out.distance, 1e-12) << trial;
    EXPECT_NEAR(point_mesh_distance(ball, rotation.transpose() * (out.on_obstacle - position)), 0.0, 1e-12) << trial;
    ++apart;
  }
  EXPECT_GT(apart, 20);
}

TEST(MeshDistance, ClosedMeshAndItsInside) {
  const TriangleMesh ball = sphere_mesh(0.5, 24, 12);
  EXPECT_TRUE(closed_mesh(ball));
  EXPECT_TRUE(closed_mesh(box_mesh(Vector3d(1, 2, 3))));
  TriangleMesh open = ball;
  open.triangles.pop_back();
  EXPECT_FALSE(closed_mesh(open));
  EXPECT_FALSE(closed_mesh(TriangleMesh{}));
  const std::shared_ptr<MeshBvh> bvh = make_bvh(ball);
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> coordinate(-0.7, 0.7);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Vector3d p(coordinate(rng), coordinate(rng), coordinate(rng));
    if (p.norm() < 0.45) {  // well inside the inscribed polyhedron
      EXPECT_TRUE(inside_mesh(*bvh, p)) << p.transpose();
      ++inside;
    } else if (p.norm() > 0.5) {
      EXPECT_FALSE(inside_mesh(*bvh, p)) << p.transpose();
      ++outside;
    }
  }
  EXPECT_GT(inside, 50);
  EXPECT_GT(outside, 50);
}

// A unit cube mesh as a link, turned a quarter about x and lifted to z = 2.
TEST(MeshDistance, MeshLinkAgainstWallAndSphere) {
  const TriangleMesh cube = box_mesh(Vector3d(1, 1, 1));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX()).toRotationMatrix();
  pose.translation() = Vector3d(0, 0, 2);
  LinkObstacleDistance out;
  // the floor z = 0: the lowest vertices at z = 1.5
  mesh_wall(cube, pose, Vector3d(3, 3, 0), Vector3d::UnitZ(), out);
  EXPECT_NEAR(out.distance, 1.5, 1e-12);
  EXPECT_NEAR(out.on_link.z(), 1.5, 1e-12);
  EXPECT_NEAR(out.on_obstacle.z(), 0.0, 1e-12);
  EXPECT_EQ(out.normal, Vector3d::UnitZ());
  // a sphere of 0.25 centred 1 beside the face x = 0.5
  mesh_sphere(cube, pose, Vector3d(1.5, 0.1, 2.2), 0.25, out);
  EXPECT_NEAR(out.distance, 0.75, 1e-12);
  EXPECT_NEAR((out.on_link - Vector3d(0.5, 0.1, 2.2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((out.on_obstacle - Vector3d(1.25, 0.1, 2.2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((out.normal + Vector3d::UnitX()).norm(), 0.0, 1e-12);
  // a point (radius 0)
  mesh_sphere(cube, pose, Vector3d(0, 0, 3), 0.0, out);
  EXPECT_NEAR(out.distance, 0.5, 1e-12);
}

}  // namespace
}  // namespace rrlab::collision
