// The witness's own checks (generator_witness.hpp): here, that a witness
// whose arm collides with itself is refused, by the engine's self-collision
// code over the pairs a case's robot checks.
#include <rrlab/generators/generator_witness.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace rrlab {
namespace witness_test {

// Three links: the planar rule checks the first against the last.
Model three_links() { return make_planar({{0.5, 0.02}, {0.2, 0.02}, {0.5, 0.02}}, Eigen::Vector2d::Zero()); }

TEST(GeneratorWitnessSelf, AStraightArmKeepsItsLinksApart) {
  const Model m = three_links();
  EXPECT_NEAR(witness_self_clearance(m, {Eigen::Vector3d::Zero()}), 0.2 - 2 * 0.02, 1e-9);
  GeneratedWitness w;
  w.steps = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0.1, 0.2, -0.2)};
  EXPECT_TRUE(keeps_self_clearance(m, w));
  EXPECT_GT(w.self_clearance, self_margin(m));
}

TEST(GeneratorWitnessSelf, AWitnessWhoseArmCrossesItselfIsRefused) {
  const Model m = three_links();
  GeneratedWitness w;
  // turned back by 2.5 rad twice: the last link crosses the first
  w.steps = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 2.5, 2.5)};
  EXPECT_FALSE(keeps_self_clearance(m, w));
  EXPECT_NEAR(w.self_clearance, -2 * 0.02, 1e-9);  // the axes cross: both radii deep
}

TEST(GeneratorWitnessSelf, TheMarginIsHalfTheThinnestLinkForTinyArms) {
  EXPECT_DOUBLE_EQ(self_margin(three_links()), kSelfClearance);
  EXPECT_DOUBLE_EQ(self_margin(make_planar({{0.01, 0.002}, {0.01, 0.004}}, Eigen::Vector2d::Zero())), 0.001);
}

}  // namespace witness_test
}  // namespace rrlab
