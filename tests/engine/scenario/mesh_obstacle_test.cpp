// The "mesh" obstacle shape of scenarios: the file found like a URDF robot's
// (confined to the scenario's directory), size limits, scale, and errors
// naming the JSON path and the file.
#include <rrlab/scenario/mesh_obstacle.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/mesh_shapes.hpp"
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/run_inputs.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

class MeshObstacleScenario : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rrlab_mesh_obstacle_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "meshes");
    write_obj(box_mesh({0.2, 0.4, 0.6}), (dir_ / "meshes/box.obj").string());
    std::ofstream(dir_ / "meshes/junk.stl") << "solid nothing\nthis is not an STL file\n";
    std::ofstream(dir_ / "meshes/junk.xyz") << "\x01\x02 not a mesh in any format\n";
    std::ofstream(dir_.parent_path() / "outside.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  static json scenario(const json& obstacle) {
    json doc = read_json_file(test::source_path("scenarios/03_dh7_pose.json"), "scenario file");
    doc["obstacles"] = json::array({obstacle});
    return doc;
  }
  static json mesh(const std::string& file) {
    return {{"id", "thing"}, {"shape", "mesh"}, {"file", file}, {"center", {0.6, 0.3, 0.2}}};
  }
  std::string error(const json& doc) const {
    try {
      parse_scenario(doc, dir_.string());
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "(accepted)";
  }

  fs::path dir_;
};

TEST_F(MeshObstacleScenario, LoadsScaledAndPlaced) {
  json o = mesh("meshes/box.obj");
  o["scale"] = {2, 1, 0.5};
  o["rpy"] = {0, 0, 30};
  json doc = scenario(o);
  doc["angle_unit"] = "deg";
  const Scenario sc = parse_scenario(doc, dir_.string());
  const Obstacle& box = sc.scene.obstacles[0];
  EXPECT_EQ(box.shape, ShapeKind::mesh);
  ASSERT_TRUE(box.mesh);
  EXPECT_EQ(box.mesh->triangles.size(), 12u);
  const Eigen::Vector3d extent = [&] {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    for (const auto& v : box.mesh->vertices) e = e.cwiseMax(v.cwiseAbs());
    return e;
  }();
  // half of (0.2, 0.4, 0.6) scaled; assimp reads single precision (measured 7.3e-9)
  EXPECT_LT((extent - Eigen::Vector3d(0.2, 0.2, 0.15)).norm(), 1e-7);
  EXPECT_LT((box.position - Eigen::Vector3d(0.6, 0.3, 0.2)).norm(), 1e-15);
  EXPECT_NEAR(box.rotation(1, 0), std::sin(M_PI / 6), 1e-12);
  // the scenario keeps naming the file; a live edit's round trip gives the same obstacle
  EXPECT_EQ(sc.json["obstacles"][0]["file"], "meshes/box.obj");
  const json back = obstacle_to_json(box);
  EXPECT_EQ(back["file"], "meshes/box.obj");
  const Obstacle again = parse_obstacle_json(back, "", dir_.string());
  EXPECT_LT((again.scale - Eigen::Vector3d(2, 1, 0.5)).norm(), 1e-15);
  EXPECT_LT((again.rotation - box.rotation).norm(), 1e-12);
  EXPECT_EQ(again.mesh->vertices.size(), box.mesh->vertices.size());
}

TEST_F(MeshObstacleScenario, ShippedScenarioLoads) {
  const Scenario sc = load_scenario_file(test::source_path("scenarios/43_urdf_iiwa14_mesh_obstacle.json"));
  ASSERT_EQ(sc.scene.obstacles[0].shape, ShapeKind::mesh);
  EXPECT_EQ(sc.scene.obstacles[0].mesh->triangles.size(), 576u);
  EXPECT_LT((sc.scene.obstacles[0].scale - Eigen::Vector3d::Constant(2)).norm(), 1e-15);
}

TEST_F(MeshObstacleScenario, FilesAreFoundLikeUrdfFiles) {
  EXPECT_EQ(error(scenario(mesh("meshes/nope.stl"))),
            "obstacles[0].file: no file \"meshes/nope.stl\" in the scenario directory");
  EXPECT_EQ(error(scenario(mesh("../outside.obj"))),
            "obstacles[0].file: \"../outside.obj\" leads outside the scenario directory");
  EXPECT_EQ(error(scenario(mesh("meshes/../../outside.obj"))),
            "obstacles[0].file: \"meshes/../../outside.obj\" leads outside the scenario directory");
  EXPECT_NE(error(scenario(mesh("/etc/passwd"))).find("obstacles[0].file: must be a path relative to the scenario's directory"),
            std::string::npos);
  EXPECT_EQ(error(scenario(mesh("package://robot/meshes/box.obj"))),
            "obstacles[0].file: \"package://robot/meshes/box.obj\": package:// and file:// URIs are not resolved; "
            "give a path relative to the scenario file");
  // a symbolic link out of the directory is refused too
  fs::create_symlink(dir_.parent_path() / "outside.obj", dir_ / "meshes/link.obj");
  EXPECT_EQ(error(scenario(mesh("meshes/link.obj"))),
            "obstacles[0].file: \"meshes/link.obj\" leads outside the scenario directory");
  // ./ and a detour that ends inside are fine
  EXPECT_EQ(error(scenario(mesh("./meshes/../meshes/box.obj"))), "(accepted)");
}

TEST_F(MeshObstacleScenario, UnreadableFileIsNamed) {
  const std::string message = error(scenario(mesh("meshes/junk.xyz")));
  EXPECT_EQ(message.rfind("obstacles[0].file: cannot read mesh 'meshes/junk.xyz': ", 0), 0u) << message;
  EXPECT_EQ(message.find(dir_.string()), std::string::npos) << "the server's path leaks: " << message;
  // an STL header with nothing in it: assimp reads no triangle
  EXPECT_EQ(error(scenario(mesh("meshes/junk.stl"))), "obstacles[0].file: mesh 'meshes/junk.stl' has no triangles");
}

TEST_F(MeshObstacleScenario, SizeLimitsNameTheFileAndTheLimit) {
  write_obj(sphere_mesh(0.1, 160, 70), (dir_ / "meshes/fine.obj").string());  // 160 x 138 = 22080 triangles
  EXPECT_EQ(error(scenario(mesh("meshes/fine.obj"))),
            "obstacles[0].file: \"meshes/fine.obj\" has 22080 triangles, at most 20000 allowed for a mesh obstacle");
  {
    std::ofstream big(dir_ / "meshes/big.obj");
    const std::string line(1023, '#');
    for (int i = 0; i <= 8 * 1024; ++i) big << line << '\n';
  }
  EXPECT_EQ(error(scenario(mesh("meshes/big.obj"))),
            "obstacles[0].file: \"meshes/big.obj\" has 8389632 bytes, at most 8388608 allowed for a mesh obstacle");
  // together: two meshes of 11800 triangles each pass alone, not both
  write_obj(sphere_mesh(0.1, 100, 60), (dir_ / "meshes/half.obj").string());
  json doc = scenario(mesh("meshes/half.obj"));
  EXPECT_EQ(error(doc), "(accepted)");
  json second = mesh("meshes/half.obj");
  second["id"] = "other";
  doc["obstacles"].push_back(second);
  EXPECT_EQ(error(doc), "obstacles[1].file: the mesh obstacles would have 23600 triangles together, at most 20000 allowed");
}

// A vertex with NaN, an infinity or 1e300 once reached FCL's BVH fit ("too
// many iterations in Jacobi transform") and every distance: refused by name.
TEST_F(MeshObstacleScenario, NonFiniteAndAbsurdVerticesAreRefused) {
  {
    // a binary STL (OBJ's reader takes "nan" for 0): one triangle with a NaN x
    std::ofstream stl(dir_ / "meshes/nan.stl", std::ios::binary);
    const std::string header(80, ' ');
    stl.write(header.data(), 80);
    const std::uint32_t count = 1;
    stl.write(reinterpret_cast<const char*>(&count), 4);
    const float values[12] = {0, 0, 1, std::nanf(""), 0, 0, 1, 0, 0, 0, 1, 0};  // normal, three vertices
    stl.write(reinterpret_cast<const char*>(values), sizeof values);
    const std::uint16_t attributes = 0;
    stl.write(reinterpret_cast<const char*>(&attributes), 2);
  }
  for (const auto& [name, vertex] : std::vector<std::pair<std::string, std::string>>{
           {"nan.stl", ""}, {"inf.obj", "v 0 inf 0"}, {"huge.obj", "v 0 0 1e300"}, {"far.obj", "v 20000 0 0"}}) {
    if (!vertex.empty()) std::ofstream(dir_ / ("meshes/" + name)) << "v 0 0 0\nv 1 0 0\n" << vertex << "\nf 1 2 3\n";
    const std::string message = error(scenario(mesh("meshes/" + name)));
    EXPECT_EQ(message.rfind("obstacles[0].file: mesh 'meshes/" + name + "' has a vertex at (", 0), 0u) << message;
    EXPECT_NE(message.find("every coordinate must be finite and within 10000 m"), std::string::npos) << name << ": " << message;
  }
  // a large file unit scaled down is fine: 20000 mm is 20 m
  std::ofstream(dir_ / "meshes/mm.obj") << "v 0 0 0\nv 1 0 0\nv 20000 0 0\nf 1 2 3\n";
  json doc = scenario(mesh("meshes/mm.obj"));
  doc["obstacles"][0]["scale"] = 0.001;
  EXPECT_EQ(error(doc), "(accepted)");
}

TEST_F(MeshObstacleScenario, BadScale) {
  const auto with_scale = [&](const json& scale) {
    json o = mesh("meshes/box.obj");
    o["scale"] = scale;
    return error(scenario(o));
  };
  EXPECT_EQ(with_scale(0), "obstacles[0].scale: must be in (0, 1000], got 0");
  EXPECT_EQ(with_scale(-2), "obstacles[0].scale: must be in (0, 1000], got -2");
  EXPECT_EQ(with_scale(json::array({1, 0.5, -1})), "obstacles[0].scale[2]: must be in (0, 1000], got -1");
  EXPECT_EQ(with_scale(1e6), "obstacles[0].scale: must be in (0, 1000], got 1e+06");
  EXPECT_EQ(with_scale(json(std::nan(""))), "obstacles[0].scale: must be a finite number");
  EXPECT_EQ(with_scale(json::array({1, 2})), "obstacles[0].scale: must have 3 numbers, got 2");
  EXPECT_EQ(with_scale("big"), "obstacles[0].scale: must be an array of numbers, got a string");
}

TEST_F(MeshObstacleScenario, KeysAndRobotsChecked) {
  json o = mesh("meshes/box.obj");
  o["size"] = {1, 1, 1};
  EXPECT_NE(error(scenario(o)).find("obstacles[0].size: unknown key"), std::string::npos) << error(scenario(o));
  json no_file = mesh("meshes/box.obj");
  no_file.erase("file");
  EXPECT_EQ(error(scenario(no_file)), "obstacles[0].file: is required");
  // planar arms see obstacles as x-y footprints: a mesh has none here
  json planar = read_json_file(test::source_path("scenarios/01_planar7_obstacles.json"), "scenario file");
  planar["obstacles"] = json::array({mesh("meshes/box.obj")});
  EXPECT_EQ(error(planar), "obstacles[0].shape: mesh obstacles need a spatial robot (spatial_xz, dh or urdf), not a planar one");
}

}  // namespace
}  // namespace rrlab
