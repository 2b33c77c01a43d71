#include <rrlab/sim/run_inputs.hpp>

#include <gtest/gtest.h>

#include <rrlab/sim/run_record.hpp>

#include "engine/sim_helpers.hpp"

namespace rrlab {
namespace {

using nlohmann::json;

json scenario(const std::string& trajectory_type = "circle") {
  json traj = trajectory_type == "joystick"
                  ? json{{"type", "joystick"}}
                  : json{{"type", "circle"}, {"center", {1.2, 0.6}}, {"radius", 0.2}};
  return {{"dt", 0.01},
          {"duration", 1.0},
          {"robot", test::planar_robot(4, 0.5, 0.02, {0.5, -0.3, -0.3, -0.3})},
          {"obstacles", json::array({{{"id", "disc"}, {"shape", "sphere"}, {"center", {0.3, 1.2}}, {"radius", 0.1}},
                                     {{"id", "pin"}, {"shape", "point"}, {"position", {1.6, 1.5}}, {"velocity", {0.1, 0}}}})},
          {"task", {{"space", "xy"}, {"trajectory", traj}}},
          {"method", {{"name", "gpm"}}}};
}

std::string error_path(Simulator& sim, const std::string& kind, const json& payload) {
  try {
    apply_input(sim, kind, payload);
  } catch (const ScenarioError& e) {
    return e.path();
  } catch (const InputStateError&) {
    return "<state>";
  }
  return "<none>";
}

TEST(RunInputs, ParamsAreValidatedBeforeAnyIsApplied) {
  Simulator sim(parse_scenario(scenario()));
  const double gain = sim.method().param("gain");
  EXPECT_EQ(error_path(sim, "params", {{"gain", 2.0}, {"nope", 1}}), "nope");
  EXPECT_EQ(sim.method().param("gain"), gain);  // nothing changed
  EXPECT_EQ(error_path(sim, "params", {{"gain", -1e9}}), "gain");
  apply_input(sim, "params", {{"gain", 2.0}});
  EXPECT_EQ(sim.method().param("gain"), 2.0);
}

TEST(RunInputs, MovingAnObstacleKeepsItsVelocityFromTheNewPlace) {
  Simulator sim(parse_scenario(scenario()));
  for (int i = 0; i < 50; ++i) sim.step();  // t = 0.5
  apply_input(sim, "obstacle", {{"id", "pin"}, {"position", {1.0, 1.0}}});
  const Obstacle& pin = sim.scene().obstacles[1];
  EXPECT_NEAR(pin.position.x(), 1.0, 1e-15);
  sim.step();
  EXPECT_NEAR(sim.scene().obstacles[1].position.x(), 1.0, 1e-12);  // advance_to(t) at the same t
  sim.step();
  EXPECT_NEAR(sim.scene().obstacles[1].position.x(), 1.001, 1e-12);  // then 0.1 m/s on
}

TEST(RunInputs, ObstacleEditsNameTheBadField) {
  Simulator sim(parse_scenario(scenario()));
  EXPECT_EQ(error_path(sim, "obstacle", {{"id", "ghost"}, {"position", {0, 0}}}), "id");
  EXPECT_EQ(error_path(sim, "obstacle", {{"id", "disc"}, {"position", {0, "x"}}}), "position[1]");
  EXPECT_EQ(error_path(sim, "obstacle", {{"id", "disc"}, {"radius", -1}}), "radius");
  EXPECT_EQ(error_path(sim, "obstacle", {{"id", "pin"}, {"size", {1, 1}}}), "size");
  EXPECT_EQ(error_path(sim, "obstacle", {{"id", "disc"}, {"colour", 1}}), "colour");
  EXPECT_EQ(error_path(sim, "obstacle", {{"id", "disc"}, {"position", {1e9, 0}}}), "position[0]");
  apply_input(sim, "obstacle", {{"id", "disc"}, {"radius", 0.3}});
  EXPECT_EQ(sim.scene().obstacles[0].radius, 0.3);
}

TEST(RunInputs, AddingAndRemovingObstaclesReshapesTheDistances) {
  Simulator sim(parse_scenario(scenario()));
  sim.step();
  apply_input(sim, "obstacle_add", {{"id", "box"}, {"shape", "box"}, {"center", {0.8, -0.5}}, {"size", {0.2, 0.2}}});
  EXPECT_EQ(error_path(sim, "obstacle_add", {{"id", "box"}, {"shape", "point"}, {"position", {0, 0}}}), "id");
  sim.step();
  EXPECT_EQ(sim.distances().obstacles, 3);
  apply_input(sim, "obstacle_remove", {{"id", "disc"}});
  apply_input(sim, "obstacle_remove", {{"id", "pin"}});
  sim.step();
  EXPECT_EQ(sim.distances().obstacles, 1);
  EXPECT_TRUE(sim.frame().q.allFinite());
}

TEST(RunInputs, JoystickOnlyOnJoystickTasks) {
  Simulator circle(parse_scenario(scenario()));
  EXPECT_EQ(error_path(circle, "joystick", {{"linear", {0.1, 0}}}), "<state>");
  Simulator joy(parse_scenario(scenario("joystick")));
  EXPECT_EQ(error_path(joy, "joystick", {{"linear", {100, 0}}}), "linear[0]");
  joy.step();
  const Eigen::Vector3d start = joy.frame().target;
  apply_input(joy, "joystick", {{"linear", {0.2, 0}}});
  for (int i = 0; i < 11; ++i) joy.step();
  EXPECT_NEAR(joy.frame().target.x() - start.x(), 0.2 * 0.1, 1e-9);
}

TEST(RunInputs, MethodSwitchAndResetAndUnknownKinds) {
  Simulator sim(parse_scenario(scenario()));
  for (int i = 0; i < 5; ++i) sim.step();
  EXPECT_EQ(error_path(sim, "method", {{"name", "magic"}}), "name");
  EXPECT_EQ(error_path(sim, "method", {{"name", "dls"}, {"params", {{"lambda", -1}}}}), "params.lambda");
  EXPECT_EQ(sim.method_name(), "gpm");
  apply_input(sim, "method", {{"name", "dls"}, {"params", {{"lambda", 0.1}}}});
  EXPECT_EQ(sim.method_name(), "dls");
  EXPECT_EQ(sim.method().param("lambda"), 0.1);
  apply_input(sim, "reset", json::object());
  EXPECT_EQ(sim.state().step, 0);
  EXPECT_EQ(error_path(sim, "teleport", json::object()), "kind");
}

TEST(RunRecord, EventsReplayToTheSameFrames) {
  // the same events applied at the same seq give bit-identical frames
  const json events = json::array({{{"seq", 3}, {"kind", "params"}, {"payload", {{"gain", 4}}}},
                                   {{"seq", 7}, {"kind", "obstacle"}, {"payload", {{"id", "disc"}, {"position", {0.5, 0.9}}}}},
                                   {{"seq", 9}, {"kind", "method"}, {"payload", {{"name", "sr_task_priority"}}}}});
  const json doc = {{"rrlab_record", 1}, {"scenario", scenario()}, {"frames", 20}, {"events", events}};
  std::vector<Eigen::VectorXd> runs[2];
  for (auto& q : runs) {
    RunRecordDoc record = parse_run_record(doc);
    Simulator sim(record.scenario);
    EventReplayer replayer(record.events);
    for (long seq = 0; seq < record.frames; ++seq) {
      replayer.apply_due(sim, seq);
      sim.step();
      q.push_back(sim.frame().q);
    }
    EXPECT_EQ(sim.method_name(), "sr_task_priority");
  }
  for (size_t i = 0; i < runs[0].size(); ++i) EXPECT_EQ(runs[0][i], runs[1][i]);
}

TEST(RunRecord, BadRecordsNameThePath) {
  const auto path_of = [](const json& doc) {
    try {
      parse_run_record(doc);
    } catch (const ScenarioError& e) {
      return e.path();
    }
    return std::string("<none>");
  };
  EXPECT_EQ(path_of({{"rrlab_record", 2}, {"scenario", scenario()}}), "rrlab_record");
  json bad = scenario();
  bad["dt"] = -1;
  EXPECT_EQ(path_of({{"rrlab_record", 1}, {"scenario", bad}}), "scenario.dt");
  EXPECT_EQ(path_of({{"rrlab_record", 1}, {"scenario", scenario()}, {"events", {{{"seq", 5}, {"kind", "reset"}}, {{"seq", 2}, {"kind", "reset"}}}}}),
            "events[1].seq");
}

}  // namespace
}  // namespace rrlab
