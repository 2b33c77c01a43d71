// Link–link distances: capsule pairs against sampled points of the two
// segments, a folded planar arm, and mesh links (capsule–mesh, mesh–mesh)
// against the boxes' own gaps.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include <rrlab/collision/allowed_collisions.hpp>
#include <rrlab/collision/self_collision.hpp>
#include <rrlab/kinematics/kinematics.hpp>

#include "engine/test_models.hpp"
#include "support/mesh_shapes.hpp"

namespace rrlab {
namespace {

using Eigen::Vector3d;

Model planar_arm(int links, double length, double radius) {
  std::vector<PlanarLinkSpec> specs(size_t(links), PlanarLinkSpec{length, radius});
  Model model = make_planar(specs, {0, 0});
  assign_self_pairs(model);
  return model;
}

SelfDistanceTable self_distances(const Model& model, const Eigen::VectorXd& q) {
  KinematicsData kin(model);
  forward_kinematics(model, q, kin);
  SelfCollisionWorld world(model);
  SelfDistanceTable table;
  world.compute(kin, table);
  return table;
}

// The least distance between points of the two segments, sampled densely.
double sampled_gap(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1) {
  constexpr int kSamples = 300;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kSamples; ++i)
    for (int j = 0; j <= kSamples; ++j) {
      const Vector3d p = a0 + (a1 - a0) * (double(i) / kSamples), r = b0 + (b1 - b0) * (double(j) / kSamples);
      best = std::min(best, (p - r).norm());
    }
  return best;
}

TEST(SelfCollision, CapsulePairsMatchTheSegmentsSampledGapLessTheRadii) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    Model model = test::random_model(ModelKind::dh, 6, seed);
    for (size_t l = 0; l < model.links.size(); ++l) model.links[l].radius = 0.01 * double(l + 1);
    model.self_pairs.clear();
    for (int a = 0; a < model.link_count(); ++a)
      for (int b = a + 2; b < model.link_count(); ++b) model.self_pairs.push_back({a, b});
    const Eigen::VectorXd q = test::random_q(model.dof(), seed + 10);
    KinematicsData kin(model);
    forward_kinematics(model, q, kin);
    const SelfDistanceTable table = self_distances(model, q);
    ASSERT_EQ(table.pairs.size(), model.self_pairs.size());
    double least = std::numeric_limits<double>::infinity();
    for (const SelfPairDistance& d : table.pairs) {
      const int a = d.pair.a, b = d.pair.b;
      const double gap = sampled_gap(kin.link_start.col(a), kin.link_end.col(a), kin.link_start.col(b), kin.link_end.col(b));
      const double longest = std::max((kin.link_end.col(a) - kin.link_start.col(a)).norm(),
                                      (kin.link_end.col(b) - kin.link_start.col(b)).norm());
      // exact is below every sample, and within a sample spacing of the best
      EXPECT_LE(d.distance, gap - model.links[size_t(a)].radius - model.links[size_t(b)].radius + 1e-12);
      EXPECT_NEAR(d.distance, gap - model.links[size_t(a)].radius - model.links[size_t(b)].radius, longest / 300 + 1e-9);
      // the points are on the links and the normal points from b to a
      EXPECT_NEAR((d.on_a - d.on_b).norm() - model.links[size_t(a)].radius - model.links[size_t(b)].radius, d.distance, 1e-9);
      EXPECT_NEAR(d.normal.norm(), 1.0, 1e-12);
      least = std::min(least, d.distance);
    }
    EXPECT_EQ(table.min_distance, least);
    ASSERT_NE(table.nearest(), nullptr);
    EXPECT_EQ(table.nearest()->distance, least);
  }
}

TEST(SelfCollision, AFoldedPlanarArmCrossesItsFirstLinkWithItsThird) {
  const Model model = planar_arm(4, 1.0, 0.05);
  const double deg = std::numbers::pi / 180;
  Eigen::VectorXd q(4);
  q << 0, 150 * deg, 150 * deg, 0;  // link 3 comes back across link 1 (at x ≈ 0.42)
  const SelfDistanceTable folded = self_distances(model, q);
  ASSERT_NE(folded.nearest(), nullptr);
  EXPECT_LT(folded.min_distance, 0);
  EXPECT_EQ(folded.nearest()->pair, (SelfPair{0, 2}));
  EXPECT_NEAR(folded.min_distance, -0.1, 1e-12);  // crossing axes: both radii deep
  const SelfDistanceTable straight = self_distances(model, Eigen::VectorXd::Zero(4));
  EXPECT_NEAR(straight.min_distance, 1.0 - 0.1, 1e-12);  // links 1 and 3, one link apart along x
  EXPECT_DOUBLE_EQ(min_self_distance(model, q), folded.min_distance);
}

TEST(SelfCollision, WithoutPairsNothingIsMeasured) {
  Model model = planar_arm(3, 1.0, 0.05);
  model.self_pairs.clear();
  const SelfDistanceTable table = self_distances(model, Eigen::VectorXd::Zero(3));
  EXPECT_TRUE(table.pairs.empty());
  EXPECT_EQ(table.nearest(), nullptr);
  EXPECT_TRUE(std::isinf(table.min_distance));
  EXPECT_TRUE(std::isinf(min_self_distance(model, Eigen::VectorXd::Zero(3))));
}

// Mesh links carry boxes centred on their frames (each link's end): at q = 0
// on the x axis, at x = 1 (link 1) and x = 3 (link 3).
TEST(SelfCollision, MeshLinksAgainstCapsulesAndMeshes) {
  Model model = planar_arm(4, 1.0, 0.05);
  const auto box = std::make_shared<const TriangleMesh>(box_mesh(Vector3d(0.2, 0.2, 0.2)));
  model.links[0].mesh = box;
  model.links[2].mesh = box;
  model.self_pairs = {{0, 2}, {0, 3}, {1, 2}};
  const SelfDistanceTable table = self_distances(model, Eigen::VectorXd::Zero(4));
  EXPECT_NEAR(table.pairs[0].distance, 2.9 - 1.1, 1e-9);         // box faces at x = 1.1 and 2.9
  EXPECT_NEAR(table.pairs[1].distance, 3.0 - 1.1 - 0.05, 1e-9);  // box 1 against link 4's capsule (x from 3)
  EXPECT_NEAR(table.pairs[2].distance, 2.9 - 2.0 - 0.05, 1e-9);  // link 2's capsule (to x = 2) against box 3
  // normals point from b to a: towards -x in both mixed pairs
  EXPECT_LT(table.pairs[1].normal.x(), -0.99);
  EXPECT_LT(table.pairs[2].normal.x(), -0.99);
}

}  // namespace
}  // namespace rrlab
