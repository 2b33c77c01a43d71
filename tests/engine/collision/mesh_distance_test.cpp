// Mesh links (a URDF <collision><mesh>, read with assimp) against the same
// shape as an analytic capsule, and against FCL's own BVH distance.
#include <fcl/fcl.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "collision/collision_world.hpp"
#include "collision/mesh_loader.hpp"
#include "collision/mesh_shapes.hpp"
#include "scenario/scenario.hpp"

namespace rrlab {
namespace {

using nlohmann::json;
constexpr double kRadius = 0.05, kLength = 0.4;

// The capsule of kRadius around the z segment [0, kLength] as a mesh
// (collision/mesh_shapes.hpp): 64 vertices around, 16 rings per cap.
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
