#include <rrlab/kinematics/kinematics.hpp>

#include <gtest/gtest.h>

#include <cstring>

#include <Eigen/SVD>
#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

// Rotation vector of R_a R_bᵀ.
Eigen::Vector3d rotation_difference(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::AngleAxisd aa(Eigen::Matrix3d(a * b.transpose()));
  return aa.axis() * aa.angle();
}

struct KindCase {
  ModelKind kind;
  int joints;
};

class JacobianFiniteDifference : public ::testing::TestWithParam<KindCase> {};

// The Jacobian of points on every link against central finite differences
// of forward kinematics (linear and angular rows).
TEST_P(JacobianFiniteDifference, MatchesCentralDifferences) {
  const auto [kind, joints] = GetParam();
  for (unsigned seed = 0; seed < 5; ++seed) {
    const Model model = test::random_model(kind, joints, seed * 31 + joints);
    const int n = model.dof();
    const Eigen::VectorXd q = test::random_q(n, seed + 100);
    KinematicsData kin(model), probe(model);
    forward_kinematics(model, q, kin);
    Eigen::MatrixXd jac(6, n);
    for (int link = 0; link < model.link_count(); ++link) {
      // a point along the link, 30% from its start, plus a side offset
      const Eigen::Vector3d p = kin.link_start.col(link) + 0.3 * (kin.link_end.col(link) - kin.link_start.col(link)) +
                                Eigen::Vector3d(0.01, -0.02, 0.03);
      const Eigen::Isometry3d& frame = kin.joint_frames[model.links[link].last_joint];
      const Eigen::Vector3d local = frame.inverse() * p;
      point_jacobian(model, kin, link, p, jac);
      const double h = 1e-6;
      for (int j = 0; j < n; ++j) {
        Eigen::VectorXd qp = q, qm = q;
        qp[j] += h;
        qm[j] -= h;
        forward_kinematics(model, qp, probe);
        const Eigen::Isometry3d fp = probe.joint_frames[model.links[link].last_joint];
        forward_kinematics(model, qm, probe);
        const Eigen::Isometry3d fm = probe.joint_frames[model.links[link].last_joint];
        const Eigen::Vector3d v = (fp * local - fm * local) / (2 * h);
        const Eigen::Vector3d w = rotation_difference(fp.linear(), fm.linear()) / (2 * h);
        EXPECT_LT((jac.col(j).head<3>() - v).norm(), 1e-6) << "link " << link << " joint " << j;
        EXPECT_LT((jac.col(j).tail<3>() - w).norm(), 1e-6) << "link " << link << " joint " << j;
      }
      Eigen::MatrixXd lin(3, n);
      point_jacobian_linear(model, kin, link, p, lin);
      EXPECT_LT((lin - jac.topRows(3)).norm(), 1e-12);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllKinds, JacobianFiniteDifference,
    ::testing::Values(KindCase{ModelKind::planar, 2}, KindCase{ModelKind::planar, 7},
                      KindCase{ModelKind::planar, 20}, KindCase{ModelKind::spatial_xz, 2},
                      KindCase{ModelKind::spatial_xz, 8}, KindCase{ModelKind::spatial_xz, 20},
                      KindCase{ModelKind::dh, 2}, KindCase{ModelKind::dh, 7}, KindCase{ModelKind::dh, 20},
                      KindCase{ModelKind::urdf, 7}, KindCase{ModelKind::urdf, 20}));

TEST(TaskJacobian, SelectsRowsOfTheEndEffectorJacobian) {
  const Model model = test::random_model(ModelKind::dh, 7, 3);
  KinematicsData kin(model);
  forward_kinematics(model, test::random_q(7, 4), kin);
  Eigen::MatrixXd full(6, 7), xy(2, 7), xyz(3, 7), pose(6, 7);
  point_jacobian(model, kin, model.link_count() - 1, kin.end_effector().translation(), full);
  task_jacobian(model, kin, TaskSpace::xy, xy);
  task_jacobian(model, kin, TaskSpace::xyz, xyz);
  task_jacobian(model, kin, TaskSpace::pose, pose);
  EXPECT_LT((xy - full.topRows(2)).norm(), 1e-14);
  EXPECT_LT((xyz - full.topRows(3)).norm(), 1e-14);
  EXPECT_LT((pose - full).norm(), 1e-14);
}

// Our DH chains against Orocos KDL: same frames, same Jacobian.
TEST(DhAgainstKdl, ForwardKinematicsAndJacobian) {
  for (unsigned seed = 0; seed < 10; ++seed) {
    const int n = 2 + int(seed % 12);
    std::vector<DhLinkSpec> specs;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    KDL::Chain chain;
    for (int i = 0; i < n; ++i) {
      DhLinkSpec s{u(rng), 3 * u(rng), u(rng), 3 * u(rng), 0, i % 4 == 3 ? JointType::prismatic : JointType::revolute};
      specs.push_back(s);
      const KDL::Joint joint(s.joint == JointType::prismatic ? KDL::Joint::TransZ : KDL::Joint::RotZ);
      chain.addSegment(KDL::Segment(joint, KDL::Frame::DH(s.a, s.alpha, s.d, s.theta)));
    }
    const Model model = make_dh(specs, Eigen::Isometry3d::Identity());
    const Eigen::VectorXd q = test::random_q(n, seed + 7);
    KinematicsData kin(model);
    forward_kinematics(model, q, kin);
    Eigen::MatrixXd jac(6, n);
    task_jacobian(model, kin, TaskSpace::pose, jac);

    KDL::JntArray kq(n);
    kq.data = q;
    KDL::Frame frame;
    KDL::ChainFkSolverPos_recursive fk(chain);
    ASSERT_GE(fk.JntToCart(kq, frame), 0);
    KDL::Jacobian kjac(n);
    KDL::ChainJntToJacSolver jac_solver(chain);
    ASSERT_GE(jac_solver.JntToJac(kq, kjac), 0);

    const Eigen::Isometry3d& ee = kin.end_effector();
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(ee.translation()[r], frame.p(r), 1e-12);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(ee.linear()(r, c), frame.M(r, c), 1e-12);
    }
    EXPECT_LT((jac - kjac.data).norm(), 1e-12) << "seed " << seed;
  }
}

TEST(JacobianConditioning, MatchesSvd) {
  const Model model = test::random_model(ModelKind::dh, 7, 11);
  KinematicsData kin(model);
  forward_kinematics(model, test::random_q(7, 12), kin);
  Eigen::MatrixXd jac(6, 7);
  task_jacobian(model, kin, TaskSpace::pose, jac);
  JacobianConditioning cond(6, 7);
  cond.compute(jac);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jac);
  const auto& s = svd.singularValues();
  EXPECT_NEAR(cond.manipulability(), s.prod(), 1e-9);
  EXPECT_NEAR(cond.sigma_max(), s[0], 1e-9);
  EXPECT_NEAR(cond.sigma_min(), s[5], 1e-7);
  EXPECT_NEAR(cond.condition_number(), s[0] / s[5], 1e-6 * s[0] / s[5]);
}

TEST(JacobianConditioning, SingularArmHasInfiniteConditionNumber) {
  const Model model = make_planar({{1.0}, {1.0}, {1.0}}, {0, 0});
  KinematicsData kin(model);
  forward_kinematics(model, Eigen::VectorXd::Zero(3), kin);  // stretched along +x
  Eigen::MatrixXd jac(2, 3);
  task_jacobian(model, kin, TaskSpace::xy, jac);
  JacobianConditioning cond(2, 3);
  cond.compute(jac);
  EXPECT_NEAR(cond.manipulability(), 0.0, 1e-12);
  EXPECT_GT(cond.condition_number(), 1e6);
}

// The joint plans the builders store (Model::plan_joints) skip only what adds
// nothing: the frames are bit for bit those of a model classified joint by
// joint as kinematics goes (no plans), from the base and from any joint.
// Planar (rotations about z, zero pre-transforms), spatial_xz (about x and
// z), DH with prismatic joints and offsets (general post rotations), and a
// general chain (arbitrary axes and origins), plus a DH arm with zero offsets
// (twists about x: two columns mixed).
TEST(ForwardKinematics, JointPlansGiveTheSameFramesBitForBit) {
  std::vector<Model> models;
  for (ModelKind kind : {ModelKind::planar, ModelKind::spatial_xz, ModelKind::dh, ModelKind::urdf})
    for (unsigned seed = 1; seed <= 3; ++seed) models.push_back(test::random_model(kind, 7, seed));
  models.push_back(make_dh(test::iiwa_dh(), Eigen::Isometry3d::Identity()));
  const auto same_bits = [](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
  };
  int axis_joints = 0, plans_checked = 0;
  for (const Model& planned : models) {
    ASSERT_EQ(planned.joint_plans.size(), planned.joints.size());
    for (const JointPlan& plan : planned.joint_plans) axis_joints += plan.axis >= 0;
    Model unplanned = planned;
    unplanned.joint_plans.clear();
    KinematicsData a(planned), b(unplanned);
    for (unsigned seed = 0; seed < 20; ++seed) {
      const Eigen::VectorXd q = test::random_q(planned.dof(), seed);
      const int first = int(seed % planned.dof());
      // from the base, then again from joint `first` after moving the joints from there on
      forward_kinematics(planned, q, a);
      forward_kinematics(unplanned, q, b);
      Eigen::VectorXd moved = q;
      for (int j = first; j < planned.dof(); ++j) moved[j] += 0.1 * (j + 1);
      forward_kinematics_from(planned, moved, a, first);
      forward_kinematics_from(unplanned, moved, b, first);
      for (int j = 0; j < planned.dof(); ++j) {
        ASSERT_TRUE(same_bits(a.joint_frames[j].matrix(), b.joint_frames[j].matrix())) << "joint " << j;
      }
      ASSERT_TRUE(same_bits(a.axis_points, b.axis_points));
      ASSERT_TRUE(same_bits(a.axis_dirs, b.axis_dirs));
      ASSERT_TRUE(same_bits(a.link_end, b.link_end));
      ++plans_checked;
    }
  }
  EXPECT_EQ(plans_checked, 20 * int(models.size()));
  EXPECT_GT(axis_joints, 50);  // most joints turn about a coordinate axis
}

TEST(ForwardKinematics, WithoutLinkSegmentsTheFramesAreTheSameAndTheSegmentsUntouched) {
  // an iteration that reads only frames and axes (direct_search's options)
  // skips the link segments: frames and axes bit for bit as with them, the
  // segments left as the last full call made them
  const Model model = test::random_model(ModelKind::dh, 7, 2);
  KinematicsData with(model), without(model);
  const Eigen::VectorXd q0 = test::random_q(model.dof(), 1), q1 = test::random_q(model.dof(), 2);
  forward_kinematics(model, q0, without);
  const Eigen::Matrix3Xd start0 = without.link_start, end0 = without.link_end;
  for (int first : {0, 3}) {
    forward_kinematics(model, q0, with);
    forward_kinematics_from(model, q1, with, first);
    forward_kinematics(model, q0, without);
    forward_kinematics_from(model, q1, without, first, false);
    for (int j = 0; j < model.dof(); ++j) EXPECT_EQ(with.joint_frames[j].matrix(), without.joint_frames[j].matrix());
    EXPECT_EQ(with.axis_points, without.axis_points);
    EXPECT_EQ(with.axis_dirs, without.axis_dirs);
    EXPECT_EQ(without.link_start, start0);
    EXPECT_EQ(without.link_end, end0);
    EXPECT_NE(with.link_end, end0);  // q1's segments differ from q0's
  }
}

}  // namespace
}  // namespace rrlab
