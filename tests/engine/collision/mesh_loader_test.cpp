// Mesh files: read back what write_obj wrote, scaled; posed appends; the
// faults named. (A URDF link's mesh: mesh_distance_test.cpp, MeshLink.)
#include <rrlab/collision/mesh_loader.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/mesh_shapes.hpp"

namespace rrlab {
namespace {

using Eigen::Vector3d;

class MeshLoader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("rrlab_mesh_loader_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(MeshLoader, ReadsWhatWasWrittenScaled) {
  const TriangleMesh box = box_mesh(Vector3d(1, 2, 3));
  write_obj(box, path("box.obj"));
  const TriangleMesh read = load_mesh_file(path("box.obj"), Vector3d(2, 1, 0.5));
  ASSERT_EQ(read.triangles.size(), box.triangles.size());
  Eigen::AlignedBox3d bounds;
  for (const Vector3d& v : read.vertices) bounds.extend(v);
  EXPECT_NEAR((bounds.max() - Vector3d(1, 1, 0.75)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((bounds.min() + Vector3d(1, 1, 0.75)).norm(), 0.0, 1e-12);
}

TEST_F(MeshLoader, FaultsAreNamed) {
  EXPECT_THROW(load_mesh_file(path("none.stl"), Vector3d::Ones()), MeshError);
  write_obj(box_mesh(Vector3d(1, 1, 1)), path("box.obj"));
  try {
    load_mesh_file(path("box.obj"), Vector3d::Constant(1e5));  // 5e4 m from the origin
    FAIL();
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("every coordinate must be finite and within"), std::string::npos) << e.what();
  }
}

TEST(TriangleMesh, AppendPosesAndRenumbers) {
  TriangleMesh mesh = box_mesh(Vector3d(1, 1, 1));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Vector3d(5, 0, 0);
  mesh.append(box_mesh(Vector3d(1, 1, 1)), pose);
  ASSERT_EQ(mesh.vertices.size(), 16u);
  ASSERT_EQ(mesh.triangles.size(), 24u);
  EXPECT_EQ(mesh.vertices[8], Vector3d(4.5, -0.5, -0.5));
  EXPECT_EQ(mesh.triangles[12], Eigen::Vector3i(mesh.triangles[0] + Eigen::Vector3i::Constant(8)));
}

}  // namespace
}  // namespace rrlab
