// The shared constraint set of qp_ik, hqp and diffik: the joint-limit box,
// the damper rows against a finite difference of the distances they bound,
// and the least-violation level.
#include <rrlab/methods/velocity_constraints.hpp>

#include <gtest/gtest.h>

#include "engine/methods/velocity_method_scenarios.hpp"

namespace rrlab {
namespace {

TEST(VelocityConstraints, TheBoxIsTheJointRangeTimesGammaOverDt) {
  nlohmann::json doc = test::target_past_the_limits();
  doc["method"] = {{"name", "pinv"}};
  Simulator sim(parse_scenario(doc));
  sim.step();  // kinematics, Jacobian and distances evaluated at q0
  const Model& model = sim.model();
  VelocityConstraintBuilder builder(model, 0);
  VelocityConstraints c;
  builder.size(c);
  const State state{0, 0, sim.scenario().q0, Eigen::VectorXd::Zero(model.dof())};
  const StepInput at_start{model, state, sim.reference(), sim.scene(), 0.01, sim.kinematics(),
                           sim.task_jacobian(), sim.distances(), sim.task(), sim.self_distances()};
  builder.build(at_start, LimitSettings{0.25, 0.0}, DamperSettings{}, c);
  for (int i = 0; i < model.dof(); ++i) {
    EXPECT_NEAR(c.upper[i], 0.25 * (model.limits.upper[i] - state.q[i]) / 0.01, 1e-6) << i;
    EXPECT_NEAR(c.lower[i], 0.25 * (model.limits.lower[i] - state.q[i]) / 0.01, 1e-6) << i;
  }
  // with a step cap, no joint moves a point of the arm more than 0.02 m: the
  // base joint's farthest point is the hand (plus the capsule's radius)
  builder.build(at_start, LimitSettings{0.25, 0.02}, DamperSettings{}, c);
  const double reach = sim.kinematics().link_end.col(2).norm() + 0.02;
  EXPECT_NEAR(c.upper[0], 0.02 / (0.01 * reach), 1e-6);
}

// A damper row's A q̇ is the rate ḋ of its pair's distance (finite difference
// along q̇), and b = −ξ(d − d_s)/(d_i − d_s).
TEST(VelocityConstraints, DamperRowsAreTheDistanceRates) {
  for (const nlohmann::json& doc : {test::post_in_the_way(), test::folding_onto_itself()}) {
    nlohmann::json run = doc;
    run["method"] = {{"name", "pinv"}};
    Simulator sim(parse_scenario(run));
    int rows = 0;
    VelocityConstraintBuilder builder(sim.model(), int(sim.scene().obstacles.size()));
    VelocityConstraints c;
    builder.size(c);
    const DamperSettings dampers{0.3, 0.01, 0.5, true};
    while (!sim.done() && rows == 0) {
      sim.step();
      const State state{sim.frame().t, sim.frame().step, sim.frame().q, sim.frame().qdot};
      const StepInput in{sim.model(),        state,           sim.reference(), sim.scene(), 0.01, sim.kinematics(),
                         sim.task_jacobian(), sim.distances(), sim.task(),      sim.self_distances()};
      builder.build(in, LimitSettings{0.5, 0.0}, dampers, c);
      rows = c.rows;
    }
    ASSERT_GT(rows, 0);
    // the rate of the nearest pair's distance along q̇ = the applied velocity
    const Eigen::VectorXd q = sim.frame().q, qdot = sim.frame().qdot;
    const double h = 1e-6;
    KinematicsData kin(sim.model());
    forward_kinematics(sim.model(), q + h * qdot, kin);
    const DamperPair& pair = c.pairs[0];
    double moved;
    if (pair.other < 0) {
      CollisionWorld world(sim.model(), sim.scene());
      DistanceTable table;
      table.resize(sim.model().link_count(), int(sim.scene().obstacles.size()));
      world.compute(kin, table);
      moved = table.at(pair.link, -1 - pair.other).distance;
    } else {
      SelfCollisionWorld world(sim.model());
      SelfDistanceTable table;
      world.compute(kin, table);
      moved = INFINITY;
      for (const SelfPairDistance& p : table.pairs)
        if (p.pair.a == pair.link && p.pair.b == pair.other) moved = p.distance;
    }
    EXPECT_NEAR((moved - pair.distance) / h, c.A.row(0).dot(qdot), 1e-4 * (1 + qdot.norm()));
    EXPECT_NEAR(c.b[0], -0.5 * (pair.distance - 0.01) / (0.3 - 0.01), 1e-12);
  }
}

// Two rows that ask opposite things of one joint: the least violation
// splits the difference; rows that can hold get no slack (to the ε = 1e-6
// regularisation of q̇: a bias of ε|q̇|).
TEST(VelocityConstraints, TheLeastViolationIsZeroWhereTheRowsCanHold) {
  VelocityConstraints c;
  c.lower = Eigen::Vector2d(-1, -1);
  c.upper = Eigen::Vector2d(1, 1);
  c.A = Eigen::MatrixXd::Zero(3, 2);
  c.b = Eigen::VectorXd::Zero(3);
  c.pairs.resize(3);
  c.A.row(0) << 1, 0;  // q̇₁ ≥ 0.5
  c.b[0] = 0.5;
  c.A.row(1) << -1, 0;  // q̇₁ ≤ −0.5
  c.b[1] = 0.5;
  c.A.row(2) << 0, 1;  // q̇₂ ≥ 2: past the box
  c.b[2] = 2.0;
  LeastViolation level1(2, 3);
  Eigen::VectorXd slack(3);
  c.rows = 1;
  ASSERT_TRUE(level1.solve(c, slack));
  EXPECT_NEAR(slack[0], 0.0, 1e-6);
  c.rows = 3;
  ASSERT_TRUE(level1.solve(c, slack));
  EXPECT_NEAR(slack[0], 0.5, 1e-5);
  EXPECT_NEAR(slack[1], 0.5, 1e-5);
  EXPECT_NEAR(slack[2], 1.0, 1e-5);  // the box holds: q̇₂ = 1
  EXPECT_LE(level1.qdot()[1], 1.0);
}

}  // namespace
}  // namespace rrlab
