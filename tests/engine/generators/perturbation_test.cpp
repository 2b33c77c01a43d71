// Perturbation families of a scenario: each draw does what its option says
// (obstacles moved within the radius and turned within the angle, path
// times scaled, start moved along the self-motion manifold with the hand
// where it was, path moved), every case starts free, and cases are the same
// for the same (scenario, options, seed, index).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/generators/perturbation.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {
namespace {

using nlohmann::json;

std::string catalogue(const std::string& name) { return std::string(RRLAB_SOURCE_DIR) + "/scenarios/" + name + ".json"; }

json base_doc(const std::string& name) { return read_json_file(catalogue(name), "scenario file"); }

PerturbationOptions all_options() {
  return parse_perturbation_options(json::parse(R"({"obstacles": {"shift": 0.03, "rotate_deg": 5}, "speed": [0.5, 2.0],
                                                   "q0_self_motion": 0.3, "path": {"shift": 0.02}})"),
                                    "");
}

Eigen::Vector3d hand_of(const Scenario& sc) {
  KinematicsData kin(sc.model);
  forward_kinematics(sc.model, sc.q0, kin);
  return kin.end_effector().translation();
}

TEST(Perturbation, EachDrawStaysWithinItsOptionAndTheHandKeepsItsPlace) {
  const std::string dir = std::string(RRLAB_SOURCE_DIR) + "/scenarios";
  for (const std::string name : {"10_sezgin_ex1_lshape", "17_chen_sim2_spatial16_window", "22_kapoor_square_circle"}) {
    SCOPED_TRACE(name);
    const json base = base_doc(name);
    const Scenario original = parse_scenario(base, dir);
    for (int index = 0; index < 12; ++index) {
      const json doc = perturb_scenario(base, dir, name, all_options(), 4, index);
      const Scenario sc = parse_scenario(doc, dir);
      const json& record = doc["perturbation"];
      EXPECT_EQ(record["of"], name);
      EXPECT_EQ(sc.name, original.name + "-p" + std::to_string(index));
      EXPECT_FALSE(doc.contains("witness"));
      // obstacles: moved at most 3 cm, turned at most 5°
      ASSERT_EQ(sc.scene.obstacles.size(), original.scene.obstacles.size());
      for (size_t k = 0; k < sc.scene.obstacles.size(); ++k) {
        Eigen::Vector3d shift = Eigen::Vector3d::Zero();
        for (size_t i = 0; i < record["obstacles"][k]["shift"].size(); ++i) shift[int(i)] = record["obstacles"][k]["shift"][i];
        EXPECT_LE(shift.norm(), 0.03 + 1e-9);
        EXPECT_LE(std::abs(record["obstacles"][k]["rotate_deg"].get<double>()), 5.0);
      }
      // speed: duration divided by s in [0.5, 2]
      const double s = record["speed"];
      EXPECT_GE(s, 0.5);
      EXPECT_LE(s, 2.0);
      EXPECT_NEAR(sc.duration, original.duration / s, 1e-6);
      // start: moved along the self-motion manifold, the hand where it was
      const double arc = record["q0_self_motion"];
      EXPECT_LE(arc, 0.3);
      EXPECT_LE((hand_of(sc) - hand_of(original)).norm(), 1e-8);
      if (arc > 0.01) {
        EXPECT_GT((sc.q0 - original.q0).norm(), 0.5 * arc);
      }
      // the start is inside the limits and clear of every obstacle
      for (int j = 0; j < sc.model.dof(); ++j) {
        EXPECT_GE(sc.q0[j], sc.model.limits.lower[j]);
        EXPECT_LE(sc.q0[j], sc.model.limits.upper[j]);
      }
      KinematicsData kin(sc.model);
      forward_kinematics(sc.model, sc.q0, kin);
      CollisionWorld world(sc.model, sc.scene);
      DistanceTable table;
      table.resize(sc.model.link_count(), int(sc.scene.obstacles.size()));
      world.compute(kin, table);
      EXPECT_GT(table.min_distance, 0);
      // path: moved at most 2 cm
      double path_shift = 0;
      for (const auto& v : record["path_shift"]) path_shift += v.get<double>() * v.get<double>();
      EXPECT_LE(std::sqrt(path_shift), 0.02 + 1e-9);
      // the same inputs, the same case
      EXPECT_EQ(doc, perturb_scenario(base, dir, name, all_options(), 4, index));
    }
  }
}

TEST(Perturbation, ObstaclesMoveAsDrawnAndTheRestStays) {
  const std::string dir = std::string(RRLAB_SOURCE_DIR) + "/scenarios";
  const json base = base_doc("01_planar7_obstacles");
  const PerturbationOptions only_shift = parse_perturbation_options(json::parse(R"({"obstacles": {"shift": 0.05}})"), "");
  const json doc = perturb_scenario(base, dir, "01_planar7_obstacles", only_shift, 9, 3);
  const Scenario before = parse_scenario(base, dir), after = parse_scenario(doc, dir);
  // where an obstacle is: its position, plus the mean of a polygon's points
  const auto place = [](const Obstacle& o) {
    Eigen::Vector3d at = o.position0;
    for (const Eigen::Vector2d& p : o.points) at.head<2>() += p / double(o.points.size());
    return at;
  };
  ASSERT_EQ(after.scene.obstacles.size(), 3u);  // a polygon, a sphere and a point
  for (size_t k = 0; k < after.scene.obstacles.size(); ++k) {
    const json& shift = doc["perturbation"]["obstacles"][k]["shift"];
    const Eigen::Vector3d d(shift[0].get<double>(), shift[1].get<double>(), 0);
    EXPECT_GT(d.norm(), 0) << k;
    EXPECT_LE((place(after.scene.obstacles[k]) - place(before.scene.obstacles[k]) - d).norm(), 4e-6) << k;
  }
  EXPECT_EQ(doc["robot"], base["robot"]);
  EXPECT_EQ(doc["task"], base["task"]);
  EXPECT_EQ(doc["duration"], base["duration"]);
  EXPECT_NE(perturb_scenario(base, dir, "01_planar7_obstacles", only_shift, 9, 4)["obstacles"], doc["obstacles"]);
  EXPECT_NE(perturb_scenario(base, dir, "01_planar7_obstacles", only_shift, 10, 3)["obstacles"], doc["obstacles"]);
}

TEST(Perturbation, ObstaclesTogetherMoveAndTurnAsOneScene) {
  // Chen's window: four boxes whose gaps make the opening; moved together
  // the opening keeps its shape (every distance between centres kept)
  const std::string dir = std::string(RRLAB_SOURCE_DIR) + "/scenarios";
  const std::string name = "17_chen_sim2_spatial16_window";
  const json base = base_doc(name);
  const PerturbationOptions together =
      parse_perturbation_options(json::parse(R"({"obstacles": {"shift": 0.03, "rotate_deg": 10, "together": true}})"), "");
  const Scenario before = parse_scenario(base, dir);
  for (int index = 0; index < 5; ++index) {
    const json doc = perturb_scenario(base, dir, name, together, 2, index);
    const Scenario after = parse_scenario(doc, dir);
    const json& record = doc["perturbation"]["obstacles"];
    for (size_t k = 1; k < record.size(); ++k) {
      EXPECT_EQ(record[k]["shift"], record[0]["shift"]);
      EXPECT_EQ(record[k]["rotate_deg"], record[0]["rotate_deg"]);
    }
    const auto& b = before.scene.obstacles;
    const auto& a = after.scene.obstacles;
    for (size_t i = 0; i < a.size(); ++i)
      for (size_t j = i + 1; j < a.size(); ++j)
        EXPECT_NEAR((a[i].position0 - a[j].position0).norm(), (b[i].position0 - b[j].position0).norm(), 1e-5) << i << " " << j;
    // turned by the drawn angle about z: the first box's rotation
    const double turn = record[0]["rotate_deg"].get<double>() * M_PI / 180.0;
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix() * b[0].rotation;
    EXPECT_LT((a[0].rotation - expected).norm(), 1e-6);
  }
}

TEST(Perturbation, BadOptionsAreNamed) {
  auto message = [](const char* text) {
    try {
      parse_perturbation_options(json::parse(text), "scenarios[2]");
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"obstacles": {"shift": -1}})").find("scenarios[2].obstacles.shift: must be in [0, 10]"), std::string::npos);
  EXPECT_NE(message(R"({"obstacles": {"move": 1}})").find("scenarios[2].obstacles"), std::string::npos);
  EXPECT_NE(message(R"({"obstacles": {"together": 1}})").find("scenarios[2].obstacles.together: must be true or false"),
            std::string::npos);
  EXPECT_NE(message(R"({"speed": [2, 1]})").find("scenarios[2].speed: must be [min, max]"), std::string::npos);
  EXPECT_NE(message(R"({"speed": [0, 1]})").find("scenarios[2].speed[0]"), std::string::npos);
  EXPECT_NE(message(R"({"q0_self_motion": "a lot"})").find("scenarios[2].q0_self_motion"), std::string::npos);
  EXPECT_NE(message(R"({"path": {"shift": 1e9}})").find("scenarios[2].path.shift"), std::string::npos);
}

TEST(Perturbation, AFamilyThatCannotStartFreeSaysWhatToReduce) {
  // every obstacle moved onto the arm: no draw can start clear
  const std::string dir = std::string(RRLAB_SOURCE_DIR) + "/scenarios";
  json base = base_doc("01_planar7_obstacles");
  base["obstacles"] = json::array({{{"shape", "sphere"}, {"center", {0.5, 0.0}}, {"radius", 0.3}}});
  base["robot"]["q0"] = json::array({0, 0, 0, 0, 0, 0, 0});
  try {
    perturb_scenario(base, dir, "blocked", parse_perturbation_options(json::parse(R"({"obstacles": {"shift": 0.01}})"), ""), 1, 0);
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("reduce obstacles.shift"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rrlab
