#include <rrlab/sim/simulator.hpp>
#include <rrlab/methods/registry.hpp>

#include <gtest/gtest.h>

#include <cstring>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"

namespace rrlab {
namespace {

using nlohmann::json;

json moving_obstacle_scenario() {
  const std::vector<double> q0 = {0.4, 0.4, 0.4, 0.4};
  return {{"dt", 0.01},
          {"duration", 2.0},
          {"robot", test::planar_robot(4, 0.5, 0.02, q0)},
          {"obstacles", {{{"id", "ball"}, {"shape", "sphere"}, {"center", {2.0, -1.0}}, {"radius", 0.1},
                          {"velocity", {-0.2, 0.3}}}}},
          {"task", {{"space", "xy"},
                    {"trajectory", {{"type", "circle"}, {"center", {1.0, 1.2}}, {"radius", 0.2}}}}},
          {"method", {{"name", "sr_task_priority"}}}};
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * size_t(a.size())) == 0;
}

TEST(Simulator, SameInputsGiveBitIdenticalFrames) {
  const auto a = test::run_scenario(moving_obstacle_scenario(), "closest_point");
  const auto b = test::run_scenario(moving_obstacle_scenario(), "closest_point");
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (size_t i = 0; i < a.frames.size(); ++i) {
    ASSERT_TRUE(same_bits(a.frames[i].q, b.frames[i].q)) << i;
    ASSERT_TRUE(same_bits(a.frames[i].qdot, b.frames[i].qdot)) << i;
    ASSERT_EQ(a.frames[i].min_distance, b.frames[i].min_distance) << i;
  }
}

// A method from outside the registry (the Python package's): built by its
// factory at the start and whenever the run starts over, run like any other.
TEST(Simulator, AnExternalMethodIsBuiltByItsFactoryAndRebuiltOnReset) {
  int built = 0;
  const MethodFactory factory = [&built](const MethodContext& ctx) {
    ++built;
    return find_method("pinv")->make(ctx);
  };
  const Scenario scenario = parse_scenario(moving_obstacle_scenario());
  Simulator external(scenario, "my_pinv", factory);
  Simulator builtin(scenario, "pinv");
  EXPECT_EQ(built, 1);
  EXPECT_EQ(external.method_name(), "my_pinv");
  for (int i = 0; i < 50; ++i) external.step(), builtin.step();
  EXPECT_TRUE(same_bits(external.state().q, builtin.state().q));
  EXPECT_EQ(external.summary().method, "my_pinv");
  external.reset();
  EXPECT_EQ(built, 2);
  external.switch_method("dls");  // a registry method by name, as before
  EXPECT_EQ(external.method_name(), "dls");
  EXPECT_EQ(built, 2);
}

TEST(Simulator, RecordsOneFramePerStepWithTimeFromTheStepIndex) {
  const auto r = test::run_scenario(moving_obstacle_scenario(), "pinv");
  ASSERT_EQ(r.frames.size(), 200u);
  EXPECT_EQ(r.summary.steps, 200);
  EXPECT_DOUBLE_EQ(r.frames[150].t, 150 * 0.01);
  EXPECT_EQ(r.frames[150].step, 150);
  EXPECT_EQ(r.summary.final_q.size(), 4);
}

TEST(Simulator, MovingObstacleFollowsItsVelocity) {
  Simulator sim(parse_scenario(moving_obstacle_scenario()));
  for (int i = 0; i < 100; ++i) sim.step();
  // the obstacle of the last step (t = 0.99 s)
  const Obstacle& ball = sim.scene().obstacles[0];
  EXPECT_LT((ball.position - Eigen::Vector3d(2.0 - 0.2 * 0.99, -1.0 + 0.3 * 0.99, 0)).norm(), 1e-12);
}

TEST(Simulator, MovedObstacleChangesDistances) {
  Simulator sim(parse_scenario(moving_obstacle_scenario()));
  sim.step();
  const double before = sim.frame().min_distance;
  Obstacle& ball = sim.scene().obstacles[0];
  ball.position0 += Eigen::Vector3d(-0.5, 0.5, 0);  // a user drag
  sim.scene_changed(false);
  sim.step();
  EXPECT_LT(sim.frame().min_distance, before - 0.3);
}

TEST(Simulator, ResizedAndRemovedObstacles) {
  Simulator sim(parse_scenario(moving_obstacle_scenario()));
  sim.step();
  sim.scene().obstacles[0].radius = 0.3;
  sim.scene_changed(true);
  sim.step();
  const double bigger = sim.frame().min_distance;
  sim.scene().obstacles.clear();
  sim.scene_changed(true);
  sim.step();
  EXPECT_TRUE(std::isinf(sim.frame().min_distance));
  EXPECT_TRUE(std::isfinite(bigger));
}

TEST(Simulator, SwitchingMethodContinuesFromTheCurrentState) {
  Simulator sim(parse_scenario(moving_obstacle_scenario()));
  for (int i = 0; i < 50; ++i) sim.step();
  const Eigen::VectorXd q = sim.state().q;
  sim.switch_method("dls");
  EXPECT_EQ(sim.method_name(), "dls");
  sim.step();
  EXPECT_TRUE(same_bits(sim.frame().q, q));
  EXPECT_EQ(sim.frame().step, 50);
  EXPECT_THROW(sim.switch_method("nope"), ParamError);
}

// run_to_end reads its stop flag between steps: set by the recorder after
// the tenth frame, the run ends there with RunInterrupted.
TEST(Simulator, RunToEndStopsBetweenSteps) {
  Simulator sim(parse_scenario(moving_obstacle_scenario()));
  std::atomic<bool> stop{false};
  struct StopAfter : Recorder {
    std::atomic<bool>& stop;
    int frames = 0;
    explicit StopAfter(std::atomic<bool>& s) : stop(s) {}
    void frame(const Frame&) override {
      if (++frames == 10) stop = true;
    }
  } recorder(stop);
  EXPECT_THROW(run_to_end(sim, &recorder, &stop), RunInterrupted);
  EXPECT_EQ(recorder.frames, 10);
  EXPECT_EQ(sim.state().step, 10);
  EXPECT_FALSE(sim.done());
}

TEST(Simulator, ResetReturnsToTheStart) {
  Simulator sim(parse_scenario(moving_obstacle_scenario()));
  sim.step();
  const Frame first = sim.frame();
  for (int i = 0; i < 30; ++i) sim.step();
  sim.reset();
  sim.step();
  EXPECT_TRUE(same_bits(sim.frame().q, first.q));
  EXPECT_TRUE(same_bits(sim.frame().qdot, first.qdot));
}

// After reset() every method repeats its first run bit for bit: its internal
// state (warm starts, GA populations, latches) starts over too.
TEST(Simulator, EveryMethodRepeatsItsRunAfterReset) {
  for (const MethodInfo& info : method_registry()) {
    std::unique_ptr<Simulator> sim;
    try {
      sim = std::make_unique<Simulator>(parse_scenario(moving_obstacle_scenario()), info.name);
    } catch (const std::exception&) {
      continue;  // a method that does not take this model
    }
    std::vector<Eigen::VectorXd> first, second;
    for (int i = 0; i < 40; ++i) {
      sim->step();
      first.push_back(sim->frame().q);
    }
    sim->reset();
    for (int i = 0; i < 40; ++i) {
      sim->step();
      second.push_back(sim->frame().q);
    }
    for (int i = 0; i < 40; ++i) EXPECT_TRUE(same_bits(first[size_t(i)], second[size_t(i)])) << info.name << " step " << i;
  }
}

TEST(Simulator, JoystickMovesTheTarget) {
  json doc = moving_obstacle_scenario();
  doc["task"]["trajectory"] = {{"type", "joystick"}};
  Simulator sim(parse_scenario(doc));
  sim.step();
  const Eigen::Vector3d start = sim.frame().ee_position;
  sim.task().set_joystick({0.1, 0, 0}, Eigen::Vector3d::Zero());
  for (int i = 0; i < 100; ++i) sim.step();
  EXPECT_NEAR(sim.frame().target.x() - start.x(), 0.1 * 0.99, 1e-9);
  EXPECT_NEAR(sim.frame().ee_position.x() - start.x(), 0.1, 0.01);
}

TEST(Simulator, SummaryRatiosUseTheLimits) {
  json doc = moving_obstacle_scenario();
  doc["robot"]["limits"] = {{"velocity", {1, 1, 1, 1}}, {"acceleration", {10, 10, 10, 10}}};
  const auto r = test::run_scenario(doc, "pinv");
  ASSERT_TRUE(r.summary.max_qdot_ratio.has_value());
  ASSERT_TRUE(r.summary.max_qddot_ratio.has_value());
  double expected = 0;
  for (const Frame& f : r.frames) expected = std::max(expected, f.qdot.cwiseAbs().maxCoeff());
  EXPECT_DOUBLE_EQ(*r.summary.max_qdot_ratio, expected);
  const auto unlimited = test::run_scenario(moving_obstacle_scenario(), "pinv");
  EXPECT_FALSE(unlimited.summary.max_qdot_ratio.has_value());
  EXPECT_TRUE(summary_to_json(unlimited.summary)["max_qdot_ratio"].is_null());
}

// Limits after integration: the summary counts the steps whose integrated q
// ended past a position limit and those whose applied q̇ exceeded a velocity
// limit, as the frames show them (frame k+1's q is step k's result).
TEST(Simulator, SummaryCountsStepsPastLimitsAfterIntegration) {
  json doc = moving_obstacle_scenario();
  const json inf = nullptr;
  doc["robot"]["limits"] = {{"lower", {inf, -0.5, -0.5, inf}}, {"upper", {inf, 0.45, 0.45, inf}},
                            {"velocity", {0.5, 0.5, 0.5, 0.5}}};
  const auto r = test::run_scenario(doc, "pinv");  // pinv knows no limits
  ASSERT_GE(r.frames.size(), 2u);
  long position = 0, velocity = 0;
  for (size_t k = 0; k < r.frames.size(); ++k) {
    const Eigen::VectorXd& q_after = k + 1 < r.frames.size() ? r.frames[k + 1].q : r.summary.final_q;
    for (int i : {1, 2})
      if (q_after[i] < -0.5 || q_after[i] > 0.45) {
        ++position;
        break;
      }
    if (r.frames[k].qdot.cwiseAbs().maxCoeff() > 0.5) ++velocity;
  }
  EXPECT_GT(position, 0);
  EXPECT_GT(velocity, 0);
  EXPECT_EQ(r.summary.position_limit_steps, position);
  ASSERT_TRUE(r.summary.velocity_limit_steps.has_value());
  EXPECT_EQ(*r.summary.velocity_limit_steps, velocity);
  const json j = summary_to_json(r.summary);
  EXPECT_EQ(j["position_limit_steps"], position);
  EXPECT_EQ(j["velocity_limit_steps"], velocity);

  const auto unlimited = test::run_scenario(moving_obstacle_scenario(), "pinv");
  EXPECT_EQ(unlimited.summary.position_limit_steps, 0);
  EXPECT_FALSE(unlimited.summary.velocity_limit_steps.has_value());
  EXPECT_TRUE(summary_to_json(unlimited.summary)["velocity_limit_steps"].is_null());
}

}  // namespace
}  // namespace rrlab
