#include <rrlab/sim/joint_smoothness.hpp>

#include <gtest/gtest.h>

#include <cmath>

#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/sim/simulator.hpp>

#include "engine/sim_helpers.hpp"

namespace rrlab {
namespace {

using nlohmann::json;

constexpr double kStep = 0.01;
const Eigen::Vector4d kWeights(1.0, -0.5, 0.25, 2.0);  // each joint's share of the speed

// Every joint at speed × its weight, integrated by the simulator (Euler).
class ConstantVelocity final : public Method {
 public:
  ConstantVelocity() : Method({{"speed", "speed", "rad/s", "", 0.3, -10, 10, 0.01, {}}}), speed_(slot("speed")) {}
  void step(const StepInput&, StepOutput& out) override { out.qdot = p(speed_) * kWeights; }

 private:
  ParamSlot speed_;
};

// q(t) = q0 + a t²/2 + c t³/6, integrated by the method itself (q_next exact).
class CubicPath final : public Method {
 public:
  static inline const Eigen::Vector4d a{0.5, -1.0, 0.2, 0.0}, c{1.0, 0.5, -2.0, 0.3};
  explicit CubicPath(Eigen::VectorXd q0) : Method({}), q0_(std::move(q0)) {}
  void step(const StepInput& in, StepOutput& out) override {
    const double t = double(in.state.step + 1) * in.dt;
    out.q_next = q0_ + a * (t * t / 2) + c * (t * t * t / 6);
    out.integrated = true;
  }

 private:
  Eigen::VectorXd q0_;
};

// q̇(t) = a t, commanded to the simulator's Euler step: q is quadratic in the step.
class LinearVelocity final : public Method {
 public:
  LinearVelocity() : Method({}) {}
  void step(const StepInput& in, StepOutput& out) override { out.qdot = CubicPath::a * in.state.t; }
};

json smooth_scenario(double duration, bool obstacle = false) {
  json doc = {{"dt", kStep},
              {"duration", duration},
              {"robot", test::planar_robot(4, 0.5, 0.02, {0.4, 0.3, -0.2, 0.1})},
              {"task", {{"space", "xy"}, {"trajectory", {{"type", "circle"}, {"center", {1.2, 0.6}}, {"radius", 0.2}}}}},
              {"method", {{"name", "pinv"}}}};
  if (obstacle) doc["obstacles"] = json::array({{{"id", "disc"}, {"shape", "sphere"}, {"center", {-1.0, -1.0}}, {"radius", 0.1}}});
  return doc;
}

template <typename M>
Simulator smooth_simulator(double duration, bool obstacle = false) {
  const Scenario sc = parse_scenario(smooth_scenario(duration, obstacle));
  const Eigen::VectorXd q0 = sc.q0;
  return Simulator(sc, "test_method", [q0](const MethodContext&) -> std::unique_ptr<Method> {
    if constexpr (std::is_same_v<M, CubicPath>) return std::make_unique<CubicPath>(q0);
    else return std::make_unique<M>();
  });
}

void run_steps(Simulator& sim, long steps) {
  for (long i = 0; i < steps; ++i) sim.step();
}

// The analytic values of CubicPath over a run of `steps` steps: q̈ = a + c t at
// t_k = k dt (central differences are exact on cubics), jerk c throughout.
JointSmoothness cubic_expected(long steps) {
  double sum = 0, max = 0;
  for (long k = 1; k < steps; ++k) {
    const double norm = (CubicPath::a + CubicPath::c * (double(k) * kStep)).norm();
    sum += norm * norm;
    max = std::max(max, norm);
  }
  return {std::sqrt(sum / double(steps - 1)), max, CubicPath::c.norm(), CubicPath::c.norm()};
}

void expect_smoothness(const JointSmoothness& got, const JointSmoothness& want, double tolerance) {
  ASSERT_TRUE(got.rms_qddot && got.max_qddot && got.rms_jerk && got.max_jerk);
  EXPECT_NEAR(*got.rms_qddot, *want.rms_qddot, tolerance);
  EXPECT_NEAR(*got.max_qddot, *want.max_qddot, tolerance);
  EXPECT_NEAR(*got.rms_jerk, *want.rms_jerk, tolerance);
  EXPECT_NEAR(*got.max_jerk, *want.max_jerk, tolerance);
}

TEST(JointSmoothness, TheNormIsEuclideanOverJoints) {
  JointSmoothnessMeter meter;
  meter.restart(Eigen::Vector2d::Zero(), 0.5);
  for (double t : {0.5, 1.0, 1.5}) meter.add(Eigen::Vector2d(3.0, 4.0) * (t * t / 2));  // q̈ = (3, 4)
  const JointSmoothness s = meter.stats();
  ASSERT_TRUE(s.max_qddot && s.max_jerk);
  EXPECT_NEAR(*s.rms_qddot, 5.0, 1e-12);
  EXPECT_NEAR(*s.max_qddot, 5.0, 1e-12);
  EXPECT_NEAR(*s.max_jerk, 0.0, 1e-12);
}

TEST(JointSmoothness, ATooShortRunHasNone) {
  Simulator sim = smooth_simulator<ConstantVelocity>(1.0);
  EXPECT_FALSE(sim.summary().smoothness.rms_qddot);
  run_steps(sim, 1);  // two positions: no second difference yet
  EXPECT_FALSE(sim.summary().smoothness.max_qddot);
  run_steps(sim, 1);
  EXPECT_TRUE(sim.summary().smoothness.rms_qddot && sim.summary().smoothness.max_qddot);
  EXPECT_FALSE(sim.summary().smoothness.rms_jerk || sim.summary().smoothness.max_jerk);
  const json j = summary_to_json(sim.summary());
  EXPECT_TRUE(j["rms_jerk"].is_null() && j["max_jerk"].is_null());
  EXPECT_TRUE(j["rms_qddot"].is_number());
  run_steps(sim, 1);
  EXPECT_TRUE(sim.summary().smoothness.rms_jerk && sim.summary().smoothness.max_jerk);
}

TEST(JointSmoothness, AConstantVelocityRunHasNoAccelerationOrJerk) {
  Simulator sim = smooth_simulator<ConstantVelocity>(1.0);
  run_to_end(sim, nullptr);
  expect_smoothness(sim.summary().smoothness, {0, 0, 0, 0}, 1e-9);  // the start from rest is not counted
}

TEST(JointSmoothness, ACubicPathIntegratedByTheMethodGivesTheAnalyticValues) {
  Simulator sim = smooth_simulator<CubicPath>(1.0);
  run_to_end(sim, nullptr);
  expect_smoothness(sim.summary().smoothness, cubic_expected(100), 1e-7);
}

TEST(JointSmoothness, ALinearVelocityIntegratedBySimulatorGivesConstantAcceleration) {
  Simulator sim = smooth_simulator<LinearVelocity>(1.0);
  run_to_end(sim, nullptr);
  const double a = CubicPath::a.norm();
  expect_smoothness(sim.summary().smoothness, {a, a, 0, 0}, 1e-7);
}

TEST(JointSmoothness, AResetStartsTheHistoryAnewWithoutASpike) {
  Simulator sim = smooth_simulator<CubicPath>(1.0);
  run_steps(sim, 50);
  sim.reset();  // back to q0: differencing across the jump would read as a huge acceleration
  run_to_end(sim, nullptr);
  Simulator fresh = smooth_simulator<CubicPath>(1.0);
  run_to_end(fresh, nullptr);
  EXPECT_EQ(*sim.summary().smoothness.max_jerk, *fresh.summary().smoothness.max_jerk);
  EXPECT_EQ(*sim.summary().smoothness.rms_qddot, *fresh.summary().smoothness.rms_qddot);
  expect_smoothness(sim.summary().smoothness, cubic_expected(100), 1e-7);
}

TEST(JointSmoothness, AParameterChangeIsOneVelocityJump) {
  Simulator sim = smooth_simulator<ConstantVelocity>(1.0);
  run_steps(sim, 40);
  sim.set_param("speed", 0.5);  // (apply_input checks names against the registry, which has no test_method)
  run_to_end(sim, nullptr);
  const double jump = (0.2 * kWeights).norm();  // Δq̇, over one step
  const JointSmoothness& s = sim.summary().smoothness;
  EXPECT_NEAR(*s.max_qddot, jump / kStep, 1e-6);
  EXPECT_NEAR(*s.rms_qddot, jump / kStep / std::sqrt(99.0), 1e-6);  // one of 99 accelerations
  EXPECT_NEAR(*s.max_jerk, jump / (kStep * kStep), 1e-4);           // on, then off
}

TEST(JointSmoothness, ARenewedOrSwitchedMethodContinuesTheHistory) {
  Simulator sim = smooth_simulator<ConstantVelocity>(1.0, true);
  run_steps(sim, 40);
  // the arm goes on from where it is: the jump below is seen across a renewed
  // method (an obstacle added: same parameters) and a switch
  sim.switch_method("test_method");  // a new instance at the default speed, as before
  apply_input(sim, "obstacle_add", {{"id", "pin"}, {"shape", "point"}, {"position", {-1.5, 1.5}}});
  sim.set_param("speed", 0.5);
  run_to_end(sim, nullptr);
  EXPECT_EQ(sim.method().param("speed"), 0.5);
  EXPECT_NEAR(*sim.summary().smoothness.max_qddot, (0.2 * kWeights).norm() / kStep, 1e-6);
}

}  // namespace
}  // namespace rrlab
