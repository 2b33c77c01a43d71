// The "witness" lane: it lands on the witness at every step, and refuses a
// scenario without one by name.
#include <rrlab/methods/witness_playback.hpp>

#include <gtest/gtest.h>

#include <rrlab/generators/generators.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {
namespace {

TEST(WitnessPlayback, LandsOnTheWitnessAtEveryStep) {
  const Scenario sc = parse_scenario(generate_scenario("planar_clutter", nullptr, 5, 3));
  ASSERT_TRUE(sc.witness);
  Simulator sim(sc, kWitnessMethod);
  Eigen::VectorXd expected;
  while (!sim.done()) {
    sim.step();
    sc.witness->at(sim.frame().t, expected);
    ASSERT_LT((sim.frame().q - expected).cwiseAbs().maxCoeff(), 1e-12) << "t = " << sim.frame().t;
  }
  EXPECT_FALSE(sim.summary().collided);
}

TEST(WitnessPlayback, IsFoundByNameButNotListed) {
  ASSERT_NE(find_method(kWitnessMethod), nullptr);
  for (const MethodInfo& info : method_registry()) EXPECT_NE(info.name, kWitnessMethod);
  EXPECT_EQ(method_names().find(kWitnessMethod), std::string::npos);
}

TEST(WitnessPlayback, AScenarioWithoutAWitnessIsRefusedByName) {
  nlohmann::json doc = generate_scenario("planar_clutter", nullptr, 5, 3);
  doc.erase("witness");
  try {
    Simulator sim(parse_scenario(doc), kWitnessMethod);
    FAIL() << "accepted";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.param(), "method");
    EXPECT_NE(std::string(e.what()).find("no witness"), std::string::npos) << e.what();
  }
}

TEST(WitnessTrajectory, InterpolatesBetweenSamplesAndHoldsOutside) {
  WitnessTrajectory w{0.5, {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, -2), Eigen::Vector2d(3, 0)}};
  Eigen::VectorXd q;
  w.at(0.25, q);
  EXPECT_TRUE(q.isApprox(Eigen::Vector2d(0.5, -1)));
  w.at(0.75, q);
  EXPECT_TRUE(q.isApprox(Eigen::Vector2d(2, -1)));
  w.at(5.0, q);
  EXPECT_EQ(q, Eigen::Vector2d(3, 0));
  w.at(-1.0, q);
  EXPECT_EQ(q, Eigen::Vector2d(0, 0));
  EXPECT_DOUBLE_EQ(w.end_time(), 1.0);
}

}  // namespace
}  // namespace rrlab
