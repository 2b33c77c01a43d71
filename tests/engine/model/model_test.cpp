#include <rrlab/model/model.hpp>

#include <gtest/gtest.h>

#include <rrlab/kinematics/kinematics.hpp>

namespace rrlab {
namespace {

TEST(PlanarModel, ForwardKinematicsOfKnownPose) {
  const Model model = make_planar({{1.0, 0.1}, {0.8}, {0.6}}, {0.5, -0.25});
  ASSERT_EQ(model.dof(), 3);
  ASSERT_EQ(model.link_count(), 3);
  EXPECT_DOUBLE_EQ(model.links[0].radius, 0.1);
  KinematicsData kin(model);
  Eigen::VectorXd q(3);
  q << M_PI / 2, -M_PI / 2, M_PI / 4;
  forward_kinematics(model, q, kin);
  // link 1 up, link 2 along +x, link 3 at 45°
  const Eigen::Vector3d ee(0.5 + 0.8 + 0.6 * std::sqrt(0.5), -0.25 + 1.0 + 0.6 * std::sqrt(0.5), 0);
  EXPECT_LT((kin.end_effector().translation() - ee).norm(), 1e-12);
  EXPECT_LT((kin.link_start.col(1) - Eigen::Vector3d(0.5, 0.75, 0)).norm(), 1e-12);
  EXPECT_LT((kin.link_end.col(1) - Eigen::Vector3d(1.3, 0.75, 0)).norm(), 1e-12);
}

// Chen et al. eq. 11–12: O_i = R(θ_1) ··· R(θ_i) L_i with
// R(θx, θz) = [1 0 0; 0 c s; 0 −s c] · Rz(θz) and L_i = (l_i, 0, 0).
TEST(SpatialXzModel, LinkVectorsFollowChenEquation12) {
  const std::vector<double> lengths = {2.4, 2.2, 2.0, 1.8};
  std::vector<PlanarLinkSpec> links;
  for (double l : lengths) links.push_back({l, 0});
  const Model model = make_spatial_xz(links, {0, 0, 3.0});
  ASSERT_EQ(model.dof(), 8);
  Eigen::VectorXd q(8);
  q << -M_PI, 1.1, 0.3, -1.4, -0.2, -1.2, 0.5, -0.8;  // Chen Simulation 3 with some θx
  KinematicsData kin(model);
  forward_kinematics(model, q, kin);

  auto chen_r = [](double tx, double tz) {
    Eigen::Matrix3d rx, rz;
    rx << 1, 0, 0, 0, std::cos(tx), std::sin(tx), 0, -std::sin(tx), std::cos(tx);
    rz << std::cos(tz), -std::sin(tz), 0, std::sin(tz), std::cos(tz), 0, 0, 0, 1;
    return Eigen::Matrix3d(rx * rz);
  };
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  Eigen::Vector3d x(0, 0, 3.0);
  for (int i = 0; i < 4; ++i) {
    r = r * chen_r(q[2 * i], q[2 * i + 1]);
    const Eigen::Vector3d o = r * Eigen::Vector3d(lengths[i], 0, 0);
    EXPECT_LT((kin.link_end.col(i) - kin.link_start.col(i) - o).norm(), 1e-12) << "link " << i;
    x += o;
  }
  EXPECT_LT((kin.end_effector().translation() - x).norm(), 1e-12);
}

TEST(DhModel, PrismaticJointSlidesAlongZ) {
  const Model model = make_dh({{0.5, 0, 0.1, 0, 0, JointType::prismatic}}, Eigen::Isometry3d::Identity());
  KinematicsData kin(model);
  Eigen::VectorXd q(1);
  q << 0.4;
  forward_kinematics(model, q, kin);
  EXPECT_LT((kin.end_effector().translation() - Eigen::Vector3d(0.5, 0, 0.5)).norm(), 1e-12);
}

TEST(JointLimits, UnboundedByDefault) {
  const Model model = make_planar({{1.0}, {1.0}}, {0, 0});
  EXPECT_FALSE(model.limits.has_position());
  EXPECT_FALSE(model.limits.has_velocity());
  EXPECT_FALSE(model.limits.has_acceleration());
}

}  // namespace
}  // namespace rrlab
