// One set of physical bounds for scenario files and live inputs: each value
// refused with its JSON path and the bound in the user's units.
#include <rrlab/scenario/physical_bounds.hpp>

#include <gtest/gtest.h>

#include <functional>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {
namespace {

using nlohmann::json;

json planar(const char* angle_unit = "rad") {
  return {{"name", "bounds"},
          {"dt", 0.01},
          {"duration", 0.1},
          {"angle_unit", angle_unit},
          {"robot",
           {{"kind", "planar"},
            {"links", {{{"length", 1.0}, {"radius", 0.05}}, {{"length", 1.0}}, {{"length", 0.5}}}},
            {"q0", {0.3, 0.4, 0.5}},
            {"limits", {{"lower", {-2, -2, -2}}, {"upper", {2, 2, 2}}, {"velocity", {1, 1, 1}}}}}},
          {"obstacles", {{{"id", "ball"}, {"shape", "sphere"}, {"center", {3, 3}}, {"radius", 0.2}}}},
          {"task", {{"space", "xy"}, {"trajectory", {{"type", "polyline"}, {"points", {{2, 1}, {1.5, 1.5}}}}}}}};
}

struct Case {
  std::string what;
  std::function<void(json&)> edit;
  std::string path, message;
};

std::string refusal(const json& doc, std::string& path) {
  try {
    parse_scenario(doc);
  } catch (const ScenarioError& e) {
    path = e.path();
    return e.what();
  }
  return "accepted";
}

TEST(PhysicalBounds, ScenarioValuesBeyondThemAreRefusedWithPathAndUnit) {
  const double huge = 1e308;
  const std::vector<Case> cases = {
      {"link length", [&](json& d) { d["robot"]["links"][1]["length"] = huge; }, "robot.links[1].length",
       "at most 10000 m, got 1e+308 m"},
      {"link radius", [&](json& d) { d["robot"]["links"][0]["radius"] = 2e4; }, "robot.links[0].radius",
       "at most 10000 m"},
      {"q0", [&](json& d) { d["robot"]["q0"][2] = huge; }, "robot.q0[2]", "at most 1000 rad"},
      {"velocity limit", [&](json& d) { d["robot"]["limits"]["velocity"][0] = huge; },
       "robot.limits.velocity[0]", "at most 1000 rad/s"},
      {"upper limit", [&](json& d) { d["robot"]["limits"]["upper"][0] = huge; }, "robot.limits.upper[0]",
       "at most 1000 rad"},
      {"sphere radius", [&](json& d) { d["obstacles"][0]["radius"] = huge; }, "obstacles[0].radius",
       "at most 10000 m"},
      {"obstacle centre", [&](json& d) { d["obstacles"][0]["center"][1] = -huge; }, "obstacles[0].center[1]",
       "at most 10000 m"},
      {"obstacle speed", [&](json& d) { d["obstacles"][0]["velocity"] = {0, 1e3}; }, "obstacles[0].velocity[1]",
       "at most 100 m/s, got 1000 m/s"},
      {"path point", [&](json& d) { d["task"]["trajectory"]["points"][1][0] = huge; },
       "task.trajectory.points[1][0]", "at most 10000 m"},
      {"base", [&](json& d) { d["robot"]["base"] = {huge, 0}; }, "robot.base[0]", "at most 10000 m"},
  };
  for (const Case& c : cases) {
    json doc = planar();
    c.edit(doc);
    std::string path;
    const std::string message = refusal(doc, path);
    EXPECT_EQ(path, c.path) << c.what << ": " << message;
    EXPECT_NE(message.find(c.message), std::string::npos) << c.what << ": " << message;
  }
}

TEST(PhysicalBounds, AnglesAreReportedInTheFilesUnit) {
  json doc = planar("deg");
  doc["robot"]["q0"] = {10, 20, 1e6};
  doc["robot"]["limits"] = {{"velocity", {90, 90, 1e6}}};
  std::string path;
  std::string message = refusal(doc, path);
  EXPECT_EQ(path, "robot.q0[2]");
  EXPECT_NE(message.find("at most 57295.8 deg, got 1e+06 deg"), std::string::npos) << message;
  doc["robot"]["q0"] = {10, 20, 30};
  message = refusal(doc, path);
  EXPECT_EQ(path, "robot.limits.velocity[2]");
  EXPECT_NE(message.find("deg/s"), std::string::npos) << message;
  doc["robot"]["limits"]["velocity"][2] = 90;
  EXPECT_EQ(refusal(doc, path), "accepted");
}

TEST(PhysicalBounds, AnEndlessDurationNamesSecondsNotAnOverflowedStepCount) {
  json doc = planar();
  doc["duration"] = 1e308;
  std::string path;
  const std::string message = refusal(doc, path);
  EXPECT_EQ(path, "duration");
  EXPECT_NE(message.find("at most 10000000 steps of dt = 0.01 s (at most 100000 s), got 1e+308 s"),
            std::string::npos)
      << message;
  EXPECT_EQ(message.find("-9223372036854775808"), std::string::npos) << message;
}

TEST(PhysicalBounds, LiveEditsUseTheSameBoundsAsFiles) {
  Simulator sim(parse_scenario(planar()));
  // A position accepted in a file is accepted live, one beyond the bound is refused in both.
  EXPECT_NO_THROW(apply_input(sim, "obstacle", {{"id", "ball"}, {"position", {9999, 0}}}));
  try {
    apply_input(sim, "obstacle", {{"id", "ball"}, {"position", {1e5, 0}}});
    FAIL() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.path(), "position[0]");
    EXPECT_NE(std::string(e.what()).find("at most 10000 m"), std::string::npos) << e.what();
  }
  try {
    apply_input(sim, "obstacle", {{"id", "ball"}, {"radius", 1e308}});
    FAIL() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.path(), "radius");
  }
  try {
    apply_input(sim, "obstacle_add", {{"id", "far"}, {"shape", "point"}, {"position", {0, 1e9}}});
    FAIL() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.path(), "position[1]");
  }
  EXPECT_EQ(sim.scene().obstacles.size(), 1u);
  EXPECT_NEAR(sim.scene().obstacles[0].radius, 0.2, 0);
}

}  // namespace
}  // namespace rrlab
