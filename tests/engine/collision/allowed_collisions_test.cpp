// The allowed-collision matrix: the planar rule, sampling (adjacent and
// always-touching pairs disabled, the rest checked), its cache and its limit.
#include <gtest/gtest.h>

#include <algorithm>

#include <rrlab/collision/allowed_collisions.hpp>
#include <rrlab/collision/self_collision.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

bool allowed_as(const AllowedCollisionMatrix& m, SelfPair p, AllowedReason reason) {
  return std::any_of(m.allowed.begin(), m.allowed.end(),
                     [&](const AllowedPair& a) { return a.pair == p && a.reason == reason; });
}

TEST(AllowedCollisions, PlanarArmsCheckEveryPairTwoOrMoreLinksApart) {
  const Model model = make_planar(std::vector<PlanarLinkSpec>(5, PlanarLinkSpec{0.5, 0.02}), {0, 0});
  const auto m = allowed_collision_matrix(model);
  EXPECT_EQ(m->samples, 0);
  EXPECT_EQ(m->checked, (std::vector<SelfPair>{{0, 2}, {0, 3}, {0, 4}, {1, 3}, {1, 4}, {2, 4}}));
  ASSERT_EQ(m->allowed.size(), 4u);
  for (int a = 0; a < 4; ++a) EXPECT_TRUE(allowed_as(*m, {a, a + 1}, AllowedReason::adjacent));
}

TEST(AllowedCollisions, APlanarMiddleLinkShorterThanItsNeighboursRadiiMakesThemAlwaysTouch) {
  // link 2 (0.05 m) is shorter than links 1 and 3's radii together (0.06 m)
  const Model model = make_planar({{0.5, 0.03}, {0.05, 0.03}, {0.5, 0.03}}, {0, 0});
  const auto m = allowed_collision_matrix(model);
  EXPECT_TRUE(m->checked.empty());
  EXPECT_TRUE(allowed_as(*m, {0, 2}, AllowedReason::always));
}

TEST(AllowedCollisions, SamplingDisablesNeighboursOfAZeroLengthLinkAsAlwaysTouching) {
  // a DH arm whose third link has no length: links 2 and 4 meet at its point in every configuration
  std::vector<DhLinkSpec> links(5);
  for (size_t i = 0; i < links.size(); ++i) {
    links[i].a = i == 2 ? 0.0 : 0.4;
    links[i].alpha = i % 2 ? 1.2 : -0.7;
    links[i].radius = 0.03;
  }
  const Model model = make_dh(links, Eigen::Isometry3d::Identity());
  const auto m = allowed_collision_matrix(model);
  EXPECT_EQ(m->samples, SelfCollisionLimits::samples);
  EXPECT_TRUE(allowed_as(*m, {1, 3}, AllowedReason::always));
  for (int a = 0; a < 4; ++a) EXPECT_TRUE(allowed_as(*m, {a, a + 1}, AllowedReason::adjacent));
  // every other pair is checked, and each pair appears once
  EXPECT_EQ(m->allowed.size() + m->checked.size(), size_t(5 * 4 / 2));
  for (const SelfPair& p : m->checked) EXPECT_FALSE(p == (SelfPair{1, 3}));
  // "never in contact" pairs stay checked
  for (const SelfPair& p : m->never_in_contact)
    EXPECT_NE(std::find(m->checked.begin(), m->checked.end(), p), m->checked.end());
}

TEST(AllowedCollisions, TheMatrixIsMadeOncePerRobotAndTheSameForACopy) {
  const Model model = test::random_model(ModelKind::dh, 6, 7);
  const auto first = allowed_collision_matrix(model);
  Model copy = model;
  copy.self_pairs = {{0, 3}};  // not part of the robot
  EXPECT_EQ(allowed_collision_matrix(copy).get(), first.get());
  Model other = model;
  other.links[2].radius += 0.01;
  EXPECT_NE(allowed_collision_matrix(other).get(), first.get());
}

TEST(AllowedCollisions, AssignedPairsLeaveOutTheUsersAndNoneWhenSwitchedOff) {
  Model model = make_planar(std::vector<PlanarLinkSpec>(4, PlanarLinkSpec{0.5, 0.02}), {0, 0});
  assign_self_pairs(model);
  EXPECT_EQ(model.self_pairs, (std::vector<SelfPair>{{0, 2}, {0, 3}, {1, 3}}));
  assign_self_pairs(model, true, {{0, 3}});
  EXPECT_EQ(model.self_pairs, (std::vector<SelfPair>{{0, 2}, {1, 3}}));
  assign_self_pairs(model, false);
  EXPECT_TRUE(model.self_pairs.empty());
}

TEST(AllowedCollisions, ARobotPastTheLinkLimitIsRefusedNamingTheSwitch) {
  const Model model =
      make_planar(std::vector<PlanarLinkSpec>(SelfCollisionLimits::max_links + 1, PlanarLinkSpec{0.1, 0.0}), {0, 0});
  try {
    (void)allowed_collision_matrix(model);
    FAIL() << "a robot of 65 links was accepted";
  } catch (const SelfCollisionError& e) {
    EXPECT_NE(std::string(e.what()).find("at most 64"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("robot.self_collision"), std::string::npos) << e.what();
  }
  Model unchecked = model;
  EXPECT_NO_THROW(assign_self_pairs(unchecked, false));
}

}  // namespace
}  // namespace rrlab
